//! Speed along a route: the fastest closed-form-invertible profile under a
//! speed limit, a lateral-acceleration limit in curves (v ≤ √(a_lat·r))
//! and a longitudinal acceleration limit (v² changes by ≤ 2·a·Δs).
//!
//! The profile is sampled every `STEP_M` of arc length (forward and
//! backward passes twice round the loop, so it is periodic), integrated to
//! the time t(s) at which a vehicle starting at s = 0 reaches s, and
//! inverted by bisection plus linear interpolation: s(τ) is a direct,
//! deterministic function of the route time τ (no simulation).

use super::super::routes::Route;

/// Arc-length sampling step, metres.
const STEP_M: f64 = 0.25;

/// Speed limits of a profile.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Limits {
    /// Top speed, m/s.
    pub v_max_mps: f64,
    /// Lateral acceleration bound in curves, m/s².
    pub a_lat_mps2: f64,
    /// Longitudinal acceleration and braking bound, m/s².
    pub a_lon_mps2: f64,
}

/// The time at which a vehicle on a route reaches each arc length.
#[derive(Clone, Debug, PartialEq)]
pub struct SpeedProfile {
    step_m: f64,
    length_m: f64,
    /// Speed at sample k (s = k·step), m/s; periodic.
    speed_mps: Vec<f64>,
    /// Time at sample k, seconds; the last entry is the lap time.
    time_s: Vec<f64>,
}

impl SpeedProfile {
    /// The profile of `route` under `lim`.
    pub fn new(route: &Route, lim: Limits) -> Self {
        let length_m = route.length_m();
        // A multiple of 4 samples: a square loop's profile is then exactly
        // 4-fold symmetric (stand positions repeat every quarter lap).
        let n = 4 * (length_m / STEP_M / 4.0).ceil().max(1.0) as usize;
        let step_m = length_m / n as f64;
        // Curvature bound: the largest curvature within half a step.
        let cap: Vec<f64> = (0..n)
            .map(|k| {
                let s = k as f64 * step_m;
                let kappa = [s - step_m / 2.0, s, s + step_m / 2.0]
                    .iter()
                    .map(|&x| route.curvature(x))
                    .fold(0.0, f64::max);
                if kappa > 0.0 {
                    (lim.a_lat_mps2 / kappa).sqrt().min(lim.v_max_mps)
                } else {
                    lim.v_max_mps
                }
            })
            .collect();
        let mut v = cap.clone();
        let dv2 = 2.0 * lim.a_lon_mps2 * step_m;
        for _ in 0..2 {
            for k in 1..=n {
                let cur = (v[(k - 1) % n].powi(2) + dv2).sqrt();
                v[k % n] = v[k % n].min(cur);
            }
            for k in (0..n).rev() {
                let next = (v[(k + 1) % n].powi(2) + dv2).sqrt();
                v[k] = v[k].min(next);
            }
        }
        let mut time_s = vec![0.0; n + 1];
        for k in 0..n {
            time_s[k + 1] = time_s[k] + 2.0 * step_m / (v[k] + v[(k + 1) % n]);
        }
        SpeedProfile {
            step_m,
            length_m,
            speed_mps: v,
            time_s,
        }
    }

    /// Time of one lap, seconds.
    pub fn lap_s(&self) -> f64 {
        self.time_s[self.time_s.len() - 1]
    }

    /// Speed at arc length `s` (wrapped), m/s.
    pub fn speed_mps(&self, s: f64) -> f64 {
        let n = self.speed_mps.len();
        let x = s.rem_euclid(self.length_m) / self.step_m;
        let k = (x.floor() as usize).min(n - 1);
        let u = x - k as f64;
        self.speed_mps[k] * (1.0 - u) + self.speed_mps[(k + 1) % n] * u
    }

    /// Time at which arc length `s` ∈ [0, length] is reached from s = 0.
    pub fn time_at(&self, s: f64) -> f64 {
        let x = (s / self.step_m).clamp(0.0, (self.time_s.len() - 1) as f64);
        let k = (x.floor() as usize).min(self.time_s.len() - 2);
        let u = x - k as f64;
        self.time_s[k] * (1.0 - u) + self.time_s[k + 1] * u
    }

    /// Arc length (unwrapped) reached at route time `tau` from s = 0.
    pub fn arc_at(&self, tau: f64) -> f64 {
        let lap = self.lap_s();
        let laps = (tau / lap).floor();
        let t = tau - laps * lap;
        let k = self
            .time_s
            .partition_point(|&x| x <= t)
            .clamp(1, self.time_s.len() - 1)
            - 1;
        let (t0, t1) = (self.time_s[k], self.time_s[k + 1]);
        let u = ((t - t0) / (t1 - t0)).clamp(0.0, 1.0);
        laps * self.length_m + (k as f64 + u) * self.step_m
    }

    /// Smallest arc distance between two vehicles `dt` seconds apart in
    /// route time (the follower behind), over a lap, metres.
    pub fn min_spacing_m(&self, dt: f64) -> f64 {
        (0..self.time_s.len() - 1)
            .map(|k| self.arc_at(self.time_s[k] + dt) - k as f64 * self.step_m)
            .fold(f64::INFINITY, f64::min)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::town::layout::Layout;
    use crate::town::routes::{routes, Turns};

    fn plain_loop() -> Route {
        let l = Layout {
            nx: 1,
            ny: 1,
            pitch_m: 90.0,
            road_w_m: 7.0,
            parking_m: 0.0,
            lane_w_m: 3.5,
            lanes: 1,
            sidewalk_m: 4.0,
            sidewalks: true,
            river_row: None,
            roundabout: None,
            underpass: None,
            loop_radius_m: 0.0,
            median: false,
        };
        routes(&l, &Turns::new(3.5)).remove(0)
    }

    const LIM: Limits = Limits {
        v_max_mps: 15.0,
        a_lat_mps2: 3.0,
        a_lon_mps2: 3.0,
    };

    #[test]
    fn speed_respects_lateral_and_longitudinal_limits() {
        let route = plain_loop();
        let p = SpeedProfile::new(&route, LIM);
        let n = p.speed_mps.len();
        for k in 0..n {
            let s = k as f64 * p.step_m;
            let v = p.speed_mps[k];
            let kappa = route.curvature(s);
            assert!(v <= LIM.v_max_mps + 1e-12);
            assert!(
                v * v * kappa <= LIM.a_lat_mps2 + 1e-9,
                "{v} m/s at κ {kappa}"
            );
            let w = p.speed_mps[(k + 1) % n];
            assert!((w * w - v * v).abs() <= 2.0 * LIM.a_lon_mps2 * p.step_m + 1e-9);
        }
        // Full speed somewhere on a 80 m straight, a crawl in the corners.
        assert!(p.speed_mps.contains(&LIM.v_max_mps));
        let r = 1.0 / route.segments[1].curvature();
        let corner = route.starts_m[1] + route.segments[1].length_m() / 2.0;
        assert!((p.speed_mps(corner) - (LIM.a_lat_mps2 * r).sqrt()).abs() < 1e-6);
    }

    #[test]
    fn arc_at_inverts_time_at() {
        let p = SpeedProfile::new(&plain_loop(), LIM);
        for k in 0..500 {
            let s = p.length_m * k as f64 / 500.0;
            let back = p.arc_at(p.time_at(s));
            assert!((back - s).abs() < 1e-9, "{s} → {back}");
        }
        // Whole laps add the length.
        let t = 0.37 * p.lap_s();
        assert!((p.arc_at(t + 3.0 * p.lap_s()) - p.arc_at(t) - 3.0 * p.length_m).abs() < 1e-6);
    }
}
