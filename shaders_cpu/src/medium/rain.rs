//! Rain as motion-blurred drops: every drop sweeps a thin vertical capsule
//! (a streak of length fall speed × shutter) during the exposure. Streaks sit
//! in a hashed 3D grid of world-space cells: a pure function of (frame seed,
//! cell), so every view of a frame sees the same drops (Garg & Nayar 2006
//! model rain appearance as such streaks).
//!
//! Drop count per m³ follows Marshall & Palmer (1948): N(D) = N0·e^{−ΛD},
//! N0 = 8000 m⁻³mm⁻¹, Λ = 4.1·R^{−0.21} mm⁻¹; drops at least `drop_diameter`
//! are drawn. A ray that meets a streak meets the drop itself with the
//! probability that the drop covers that height at some instant (2r/L); the
//! drop is then a water sphere (n = 1.333): Fresnel-chosen reflection or
//! refraction in and out. World coordinates in f64 (metres, z up).

use glam::{DVec3, Vec3};

/// Refractive index of water.
pub const WATER_ETA: f64 = 1.333;
/// Expected streaks per grid cell (sets the cell size).
const STREAKS_PER_CELL: f64 = 3.0;

/// Number of drops per m³ with diameter ≥ `d_min_mm` at rain rate `rate_mm_per_h`.
pub fn marshall_palmer_count(rate_mm_per_h: f64, d_min_mm: f64) -> f64 {
    let lambda = 4.1 * rate_mm_per_h.powf(-0.21);
    8000.0 / lambda * (-lambda * d_min_mm).exp()
}

/// A rain field of one frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rain {
    /// Streaks per m³.
    pub density_per_m3: f64,
    /// Streak (sweep) length in metres.
    pub streak_length_m: f64,
    /// Drop radius in metres.
    pub drop_radius_m: f64,
    /// Cells whose centre lies within this distance of `center_world` hold rain.
    pub extent_m: f64,
    /// Centre of the rain volume (the rig), world metres.
    pub center_world: DVec3,
    /// Frame seed: streak positions are a pure function of it and the cell.
    pub seed: u64,
    /// Grid cell edge in metres (≥ the streak length).
    pub cell_m: f64,
}

/// A ray meeting a streak.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StreakHit {
    /// Ray parameter where the capsule is entered.
    pub t: f64,
    /// Ray parameter where it is left.
    pub t_far: f64,
    /// The streak's axis (x, y) and its top z, world metres.
    pub axis_top: DVec3,
}

/// What a drop does to a ray (weights are 1: choices follow Fresnel).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum DropEvent {
    /// No drop at this instant and height: continue past `t_far`.
    Pass,
    /// Leaves the drop from `p_world` along unit `dir`.
    Redirect {
        /// Exit point, world metres.
        p_world: DVec3,
        /// New direction.
        dir: Vec3,
    },
}

fn mix64(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

fn unit(h: u64) -> f64 {
    (h >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

/// Unpolarised Fresnel reflectance of a dielectric, `cos_i` > 0, relative index `eta`.
pub fn fresnel_dielectric(cos_i: f64, eta: f64) -> f64 {
    let sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
    if sin2_t >= 1.0 {
        return 1.0;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    let rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    let rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    0.5 * (rs * rs + rp * rp)
}

/// Refracts unit `d` at a surface with unit normal `n` facing against `d`.
fn refract(d: DVec3, n: DVec3, eta: f64) -> Option<DVec3> {
    let cos_i = -d.dot(n);
    let sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
    if sin2_t >= 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    Some((d / eta + n * (cos_i / eta - cos_t)).normalize())
}

/// Entry and exit ray parameters of a sphere at the origin, radius r.
fn sphere_roots(o: DVec3, d: DVec3, r: f64) -> Option<(f64, f64)> {
    let b = o.dot(d);
    let c = o.length_squared() - r * r;
    let disc = b * b - c;
    (disc > 0.0).then(|| (-b - disc.sqrt(), -b + disc.sqrt()))
}

impl Rain {
    /// A field of `density_per_m3` streaks of `streak_length_m`, drop radius
    /// `drop_radius_m`, within `extent_m` of `center_world`, from `seed`.
    pub fn new(
        density_per_m3: f64,
        streak_length_m: f64,
        drop_radius_m: f64,
        extent_m: f64,
        center_world: DVec3,
        seed: u64,
    ) -> Self {
        let cell = (STREAKS_PER_CELL / density_per_m3.max(1e-9)).cbrt();
        let cell_m = cell.clamp(2.0 * (streak_length_m + 2.0 * drop_radius_m), 8.0);
        Rain {
            density_per_m3,
            streak_length_m,
            drop_radius_m,
            extent_m,
            center_world,
            seed,
            cell_m,
        }
    }

    fn cell_hash(&self, c: [i64; 3], k: u64) -> u64 {
        let h = mix64(self.seed ^ mix64(c[0] as u64));
        let h = mix64(h ^ mix64(c[1] as u64 ^ 0x5bd1_e995));
        let h = mix64(h ^ mix64(c[2] as u64 ^ 0x1b87_3593));
        mix64(h ^ k)
    }

    /// Streaks of cell `c`: (axis x, axis y, top z), each wholly inside the cell.
    pub fn streaks(&self, c: [i64; 3]) -> impl Iterator<Item = DVec3> + '_ {
        let s = self.cell_m;
        let lambda = self.density_per_m3 * s * s * s;
        let centre = (DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64) + 0.5) * s;
        let inside = centre.distance(self.center_world) <= self.extent_m;
        let count = if inside {
            (lambda + unit(self.cell_hash(c, u64::MAX))) as u64
        } else {
            0
        };
        let (r, len) = (self.drop_radius_m, self.streak_length_m);
        (0..count).map(move |k| {
            let h = self.cell_hash(c, k);
            let (ux, uy, uz) = (unit(h), unit(mix64(h ^ 1)), unit(mix64(h ^ 2)));
            DVec3::new(
                (c[0] as f64 * s) + r + ux * (s - 2.0 * r),
                (c[1] as f64 * s) + r + uy * (s - 2.0 * r),
                (c[2] as f64 * s) + len + r + uz * (s - len - 2.0 * r),
            )
        })
    }

    /// First streak along o + t·d (world, unit d) with t ∈ (t_min, t_max).
    pub fn intersect(&self, o: DVec3, d: DVec3, t_min: f64, t_max: f64) -> Option<StreakHit> {
        // Clip to the sphere of the rain volume (plus a cell of slack).
        let reach = self.extent_m + self.cell_m * 1.8;
        let (a, b) = sphere_roots(o - self.center_world, d, reach)?;
        let (mut t, t_end) = (t_min.max(a), t_max.min(b));
        if t >= t_end {
            return None;
        }
        // Amanatides–Woo grid traversal from the entry point.
        let s = self.cell_m;
        let p = o + d * t;
        let mut cell = [0i64; 3];
        let (mut t_next, mut t_delta, mut step) = ([0.0f64; 3], [0.0f64; 3], [0i64; 3]);
        for k in 0..3 {
            cell[k] = (p[k] / s).floor() as i64;
            if d[k] > 0.0 {
                step[k] = 1;
                t_next[k] = t + (((cell[k] + 1) as f64) * s - p[k]) / d[k];
                t_delta[k] = s / d[k];
            } else if d[k] < 0.0 {
                step[k] = -1;
                t_next[k] = t + ((cell[k] as f64) * s - p[k]) / d[k];
                t_delta[k] = -s / d[k];
            } else {
                t_next[k] = f64::INFINITY;
                t_delta[k] = f64::INFINITY;
            }
        }
        while t < t_end {
            let mut best: Option<StreakHit> = None;
            for axis_top in self.streaks(cell) {
                if let Some(h) = self.hit_streak(o, d, axis_top) {
                    if h.t > t_min && h.t < t_max && best.is_none_or(|b| h.t < b.t) {
                        best = Some(h);
                    }
                }
            }
            if best.is_some() {
                return best;
            }
            let k = if t_next[0] < t_next[1] && t_next[0] < t_next[2] {
                0
            } else if t_next[1] < t_next[2] {
                1
            } else {
                2
            };
            t = t_next[k];
            t_next[k] += t_delta[k];
            cell[k] += step[k];
        }
        None
    }

    /// Ray against one streak: a vertical cylinder of the drop radius between
    /// top − length and top (its thin end caps are ignored).
    fn hit_streak(&self, o: DVec3, d: DVec3, axis_top: DVec3) -> Option<StreakHit> {
        let (ox, oy) = (o.x - axis_top.x, o.y - axis_top.y);
        let a = d.x * d.x + d.y * d.y;
        if a < 1e-12 {
            return None;
        }
        let b = ox * d.x + oy * d.y;
        let c = ox * ox + oy * oy - self.drop_radius_m * self.drop_radius_m;
        let disc = b * b - a * c;
        if disc <= 0.0 {
            return None;
        }
        let (t0, t1) = ((-b - disc.sqrt()) / a, (-b + disc.sqrt()) / a);
        let z = o.z + d.z * t0;
        let bottom = axis_top.z - self.streak_length_m;
        (z >= bottom && z <= axis_top.z).then_some(StreakHit {
            t: t0,
            t_far: t1,
            axis_top,
        })
    }

    /// Samples what the drop does to a ray that met streak `hit`, from `u`.
    pub fn drop_event(&self, o: DVec3, d: DVec3, hit: &StreakHit, u: [f32; 4]) -> DropEvent {
        let r = self.drop_radius_m;
        // The drop covers a given height for 2r of its L + 2r sweep.
        if u[0] as f64 >= 2.0 * r / (self.streak_length_m + 2.0 * r) {
            return DropEvent::Pass;
        }
        let z_hit = o.z + d.z * hit.t;
        let c = DVec3::new(
            hit.axis_top.x,
            hit.axis_top.y,
            z_hit + r * (2.0 * u[1] as f64 - 1.0),
        );
        let Some((t_in, _)) = sphere_roots(o - c, d, r) else {
            return DropEvent::Pass;
        };
        let p_in = o + d * t_in;
        let n = (p_in - c) / r;
        let f = fresnel_dielectric((-d.dot(n)).clamp(0.0, 1.0), WATER_ETA);
        if (u[2] as f64) < f {
            let dir = d - n * (2.0 * d.dot(n));
            return DropEvent::Redirect {
                p_world: p_in,
                dir: dir.normalize().as_vec3(),
            };
        }
        let Some(d_in) = refract(d, n, WATER_ETA) else {
            return DropEvent::Pass;
        };
        // Inside the sphere the exit is the far root of the chord.
        let t_out = sphere_roots(p_in - c, d_in, r).map_or(0.0, |(_, t1)| t1.max(0.0));
        let p_out = p_in + d_in * t_out;
        let n_out = (p_out - c) / r;
        match refract(d_in, -n_out, 1.0 / WATER_ETA) {
            Some(d_out) => DropEvent::Redirect {
                p_world: p_out,
                dir: d_out.as_vec3(),
            },
            // Total internal reflection (rare at these angles): the drop lets it pass.
            None => DropEvent::Pass,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn marshall_palmer_total_matches_n0_over_lambda() {
        let n = marshall_palmer_count(1.0, 0.0);
        assert!((n - 8000.0 / 4.1).abs() < 1e-9);
    }

    #[test]
    fn fresnel_water_at_normal_incidence_is_two_percent() {
        let f = fresnel_dielectric(1.0, WATER_ETA);
        assert!((f - ((WATER_ETA - 1.0) / (WATER_ETA + 1.0)).powi(2)).abs() < 1e-12);
    }

    #[test]
    fn streaks_are_a_pure_function_of_seed_and_cell() {
        let a = Rain::new(50.0, 0.09, 0.00125, 30.0, DVec3::ZERO, 7);
        let b = Rain::new(50.0, 0.09, 0.00125, 30.0, DVec3::ZERO, 7);
        let c = [3, -2, 0];
        let sa: Vec<_> = a.streaks(c).collect();
        assert!(!sa.is_empty());
        assert_eq!(sa, b.streaks(c).collect::<Vec<_>>());
        let other = Rain::new(50.0, 0.09, 0.00125, 30.0, DVec3::ZERO, 8);
        assert_ne!(sa, other.streaks(c).collect::<Vec<_>>());
    }

    #[test]
    fn ray_through_a_streak_axis_hits_it() {
        let rain = Rain::new(20.0, 0.09, 0.00125, 30.0, DVec3::ZERO, 3);
        let c = [1, 1, 0];
        let s = rain.streaks(c).next().expect("a streak");
        let o = DVec3::new(s.x - 5.0, s.y, s.z - 0.04);
        let h = rain.intersect(o, DVec3::X, 0.0, 10.0).expect("hit");
        assert!(h.t <= 5.0 - rain.drop_radius_m + 1e-9, "{h:?}");
    }

    #[test]
    fn streak_is_hit_along_its_whole_length_and_missed_past_its_ends() {
        let rain = Rain::new(20.0, 0.15, 0.001, 30.0, DVec3::ZERO, 5);
        let c = [0, 2, 0];
        let s = rain.streaks(c).next().expect("a streak");
        let len = rain.streak_length_m;
        // Horizontal rays aimed at the axis from 4 m away, at heights along it.
        for k in 0..=10 {
            let z = s.z - len * (0.02 + 0.96 * k as f64 / 10.0);
            let o = DVec3::new(s.x - 4.0, s.y, z);
            let h = rain
                .hit_streak(o, DVec3::X, s)
                .expect("hit along the streak");
            assert!((h.t - (4.0 - rain.drop_radius_m)).abs() < 1e-9);
            assert!((h.t_far - h.t - 2.0 * rain.drop_radius_m).abs() < 1e-9);
        }
        for z in [s.z + 0.01, s.z - len - 0.01] {
            let o = DVec3::new(s.x - 4.0, s.y, z);
            assert!(rain.hit_streak(o, DVec3::X, s).is_none(), "z {z}");
        }
        // Aimed beside the axis by more than the radius: a miss.
        let o = DVec3::new(s.x - 4.0, s.y + 1.5 * rain.drop_radius_m, s.z - 0.5 * len);
        assert!(rain.hit_streak(o, DVec3::X, s).is_none());
    }
}
