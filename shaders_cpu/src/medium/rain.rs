//! Rain as motion-blurred drops (Garg & Nayar 2006, "Photorealistic rendering
//! of rain streaks"): during the exposure every drop sweeps a vertical streak
//! of length fall speed × shutter, and a pixel on the streak sees the drop for
//! a fraction of the exposure. Streaks sit in a hashed 3D grid of world-space
//! cells, a pure function of (frame seed, cell), so every view of a frame sees
//! the same drops.
//!
//! A streak is pre-filtered to the pixel it falls on: a vertical capsule of
//! radius R = max(r, θ·d/2) (θ the angular pixel size, d the streak's
//! distance to the rig) and length L_c = L + 2r; its `coverage` w = π r² / A,
//! A = 2R·L_c·sin α + π R²·|cos α| its projected area along a ray at α to the
//! vertical, is the fraction of a pixel's area × exposure the drop covers, so
//! ∫ w over the projection is the drop's area (the blend keeps energy).
//! Drop diameters follow Marshall & Palmer (1948), N(D) = N0·e^{−ΛD},
//! N0 = 8000 m⁻³mm⁻¹, Λ = 4.1·R^{−0.21} mm⁻¹, from a smallest drawn diameter
//! to 6 mm (larger drops break up); fall speeds follow Atlas et al. (1973),
//! v = 9.65 − 10.3·e^{−0.6 D} m/s (D in mm), unless one speed is given.
//! A pixel sees the field through [`Rain::opacity`]: the streaks its centre
//! ray meets before the surface, composited over the path-traced radiance
//! (the integrator's rain pass). World coordinates in f64 (metres, z up).

use std::f64::consts::PI;

use glam::DVec3;

/// Expected streaks per grid cell (sets the cell size).
const STREAKS_PER_CELL: f64 = 3.0;
/// Hits one cell may hand on (more in one cell are dropped: cells hold a
/// few streaks, or a few dozen capsules widened to coarse pixels).
const CELL_HITS: usize = 64;
/// Image length in pixels from which a streak gets the full opacity gain.
const RESOLVED_STREAK_PX: f64 = 24.0;
/// Largest drop diameter drawn, mm (larger drops break up).
pub const MAX_DROP_DIAMETER_MM: f64 = 6.0;
/// Below this sin² of the angle to the vertical a ray looks along the
/// streaks and meets none (their end caps are ignored).
const MIN_SIN2: f64 = 1e-8;

/// Number of drops per m³ with diameter ≥ `d_min_mm` at rain rate `rate_mm_per_h`.
pub fn marshall_palmer_count(rate_mm_per_h: f64, d_min_mm: f64) -> f64 {
    let lambda = 4.1 * rate_mm_per_h.powf(-0.21);
    8000.0 / lambda * (-lambda * d_min_mm).exp()
}

/// Marshall–Palmer slope Λ in 1/mm at rain rate `rate_mm_per_h`.
pub fn marshall_palmer_lambda(rate_mm_per_h: f64) -> f64 {
    4.1 * rate_mm_per_h.powf(-0.21)
}

/// Terminal fall speed in m/s of a drop of diameter `d_mm` (Atlas et al. 1973).
pub fn atlas_fall_speed(d_mm: f64) -> f64 {
    (9.65 - 10.3 * (-0.6 * d_mm).exp()).max(0.05)
}

/// A rain field of one frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rain {
    /// Streaks (drops at least `min_diameter_mm`) per m³.
    pub density_per_m3: f64,
    /// Smallest drawn drop diameter, mm.
    pub min_diameter_mm: f64,
    /// Marshall–Palmer slope Λ of the diameters, 1/mm.
    pub lambda_per_mm: f64,
    /// Exposure time, seconds: a streak is fall speed × shutter long.
    pub shutter_s: f64,
    /// One fall speed for every drop, m/s (None: Atlas et al. per diameter).
    pub fall_speed_m_per_s: Option<f64>,
    /// Cells whose centre lies within this distance of `center_world` hold rain.
    pub extent_m: f64,
    /// Centre of the rain volume (the rig), world metres.
    pub center_world: DVec3,
    /// Frame seed: streak positions are a pure function of it and the cell.
    pub seed: u64,
    /// Angular size of one pixel in radians (≥ 0): a streak narrower than
    /// the pixel footprint at its distance is widened to it (0: never).
    pub pixel_angle_rad: f64,
    /// Factor on every streak's coverage when composited (1: physical).
    pub opacity_gain: f64,
    /// Grid cell edge in metres (≥ twice the longest capsule).
    pub cell_m: f64,
}

/// One drop's streak.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Streak {
    /// The streak's axis (x, y) and its top z, world metres.
    pub axis_top: DVec3,
    /// Drop radius, metres.
    pub drop_radius_m: f64,
    /// Sweep length (fall speed × shutter), metres.
    pub length_m: f64,
}

/// A ray meeting a streak capsule.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StreakHit {
    /// Ray parameter where the capsule is entered.
    pub t: f64,
    /// Ray parameter where it is left.
    pub t_far: f64,
    /// Ray parameter closest to the streak's axis: where the drop is met.
    pub t_axis: f64,
    /// The streak's axis (x, y) and its top z, world metres.
    pub axis_top: DVec3,
    /// Its drop's radius, metres.
    pub drop_radius_m: f64,
    /// Fraction of the pixel's area × exposure the drop covers along this
    /// ray, in (0, 1].
    pub coverage: f64,
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

/// Entry and exit ray parameters of a sphere at the origin, radius r.
pub(super) fn sphere_roots(o: DVec3, d: DVec3, r: f64) -> Option<(f64, f64)> {
    let b = o.dot(d);
    let c = o.length_squared() - r * r;
    let disc = b * b - c;
    (disc > 0.0).then(|| (-b - disc.sqrt(), -b + disc.sqrt()))
}

impl Rain {
    /// Streaks covering less than this of a pixel's area × exposure are left
    /// out of [`Rain::opacity`] (they would change no 8-bit pixel).
    pub const MIN_OPACITY_COVERAGE: f64 = 1e-4;

    /// A field of `density_per_m3` drops with diameters from
    /// `min_diameter_mm` (Marshall–Palmer slope `lambda_per_mm`), exposed for
    /// `shutter_s`, within `extent_m` of `center_world`, seed 0,
    /// pre-filtered to pixels of `pixel_angle_rad` radians, seen at the
    /// physical opacity (gain 1).
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        density_per_m3: f64,
        min_diameter_mm: f64,
        lambda_per_mm: f64,
        shutter_s: f64,
        fall_speed_m_per_s: Option<f64>,
        extent_m: f64,
        center_world: DVec3,
        pixel_angle_rad: f64,
    ) -> Self {
        Rain {
            density_per_m3,
            min_diameter_mm,
            lambda_per_mm,
            shutter_s,
            fall_speed_m_per_s,
            extent_m,
            center_world,
            seed: 0,
            pixel_angle_rad,
            opacity_gain: 1.0,
            cell_m: 0.0,
        }
        .sized()
    }

    /// The field of one frame: streaks drawn from `seed`, pre-filtered to
    /// pixels of `pixel_angle_rad` radians (the camera's 1/f_px).
    pub fn for_frame(&self, seed: u64, pixel_angle_rad: f64) -> Self {
        Rain {
            seed,
            pixel_angle_rad,
            ..*self
        }
        .sized()
    }

    /// Sets the grid cell: it holds whole capsules (twice their length, four
    /// widths) and about `STREAKS_PER_CELL` of them.
    fn sized(mut self) -> Self {
        let d_max = self.max_diameter_mm();
        let l_max = self.fall_speed(d_max) * self.shutter_s + 1e-3 * d_max;
        let lower = (2.0 * l_max).max(4.0 * self.max_radius());
        let cell = (STREAKS_PER_CELL / self.density_per_m3.max(1e-9)).cbrt();
        self.cell_m = cell.min(8.0).max(lower);
        self
    }

    fn max_diameter_mm(&self) -> f64 {
        self.min_diameter_mm.max(MAX_DROP_DIAMETER_MM)
    }

    /// Fall speed of a drop of diameter `d_mm`, m/s.
    pub fn fall_speed(&self, d_mm: f64) -> f64 {
        self.fall_speed_m_per_s
            .unwrap_or_else(|| atlas_fall_speed(d_mm))
    }

    /// Drop diameter in mm from `u` ∈ [0, 1): Marshall–Palmer truncated to
    /// [`min_diameter_mm`, 6 mm] (one size if the smallest is above 6 mm).
    pub fn diameter_mm(&self, u: f64) -> f64 {
        let (d0, lambda) = (self.min_diameter_mm, self.lambda_per_mm);
        let span = self.max_diameter_mm() - d0;
        if span <= 0.0 {
            return d0;
        }
        // Inverts the truncated exponential CDF (1 − e^{−Λx}) / (1 − e^{−Λ·span}).
        d0 - (-(u * (-(-lambda * span).exp_m1()))).ln_1p() / lambda
    }

    /// The widest capsule radius of the field, metres (capsules stop within
    /// the extent plus 16 m: a cell of slack at the 8 m cell cap).
    fn max_radius(&self) -> f64 {
        let far = self.extent_m + 16.0;
        (0.5e-3 * self.max_diameter_mm()).max(0.5 * self.pixel_angle_rad * far)
    }

    /// Capsule radius of `streak`, metres: its drop radius, or half the
    /// pixel footprint at the streak's distance from the rig.
    pub fn streak_radius(&self, streak: &Streak) -> f64 {
        let mid = streak.axis_top - DVec3::Z * (0.5 * streak.length_m);
        let dist = mid.distance(self.center_world);
        streak.drop_radius_m.max(0.5 * self.pixel_angle_rad * dist)
    }

    /// Coverage of the capsule (radius `radius`) of `streak` seen along a
    /// direction at angle α to the vertical: the drop's area over the
    /// capsule's projected area, π r² / (2R · L_c · sin α + π R² · |cos α|),
    /// in (0, 1].
    pub fn coverage(&self, streak: &Streak, radius: f64, sin_a: f64, cos_a: f64) -> f64 {
        let r = streak.drop_radius_m;
        let l_c = streak.length_m + 2.0 * r;
        let area = 2.0 * radius * l_c * sin_a + PI * radius * radius * cos_a.abs();
        (PI * r * r / area).min(1.0)
    }

    fn cell_hash(&self, c: [i64; 3]) -> u64 {
        let h = mix64(self.seed ^ mix64(c[0] as u64));
        let h = mix64(h ^ mix64(c[1] as u64 ^ 0x5bd1_e995));
        mix64(h ^ mix64(c[2] as u64 ^ 0x1b87_3593))
    }

    /// Number of streaks in cell `c` (0 outside the extent) and the
    /// cell's hash: stratified, ⌊λ + u⌋ has mean λ = density × cell volume.
    fn cell_count(&self, c: [i64; 3]) -> (u64, u64) {
        let s = self.cell_m;
        if self.cell_centre(c).distance(self.center_world) > self.extent_m {
            return (0, 0);
        }
        let base = self.cell_hash(c);
        let lambda = self.density_per_m3 * s * s * s;
        ((lambda + unit(mix64(base ^ u64::MAX))) as u64, base)
    }

    /// Axis (x, y) of the streak with hash `h` in cell `c`, kept the widest
    /// capsule radius away from the cell's walls.
    fn axis_xy(&self, c: [i64; 3], h: u64) -> (f64, f64) {
        let (s, m) = (self.cell_m, self.max_radius());
        (
            (c[0] as f64 * s) + m + unit(h) * (s - 2.0 * m),
            (c[1] as f64 * s) + m + unit(mix64(h ^ 1)) * (s - 2.0 * m),
        )
    }

    /// The streak with hash `h` in cell `c`.
    fn streak(&self, c: [i64; 3], h: u64) -> Streak {
        let s = self.cell_m;
        let (x, y) = self.axis_xy(c, h);
        let d_mm = self.diameter_mm(unit(mix64(h ^ 3)));
        let (r, len) = (0.5e-3 * d_mm, self.fall_speed(d_mm) * self.shutter_s);
        let uz = unit(mix64(h ^ 2));
        Streak {
            axis_top: DVec3::new(x, y, (c[2] as f64 * s) + len + r + uz * (s - len - 2.0 * r)),
            drop_radius_m: r,
            length_m: len,
        }
    }

    /// Streaks of cell `c`; each capsule lies wholly inside the cell, so a
    /// ray meets a streak in the cell that holds it.
    pub fn streaks(&self, c: [i64; 3]) -> impl Iterator<Item = Streak> + '_ {
        let (count, base) = self.cell_count(c);
        (0..count).map(move |k| self.streak(c, mix64(base ^ k)))
    }

    /// Horizontal layers of cells (their z index) that can hold rain.
    pub fn layers(&self) -> std::ops::RangeInclusive<i64> {
        let s = self.cell_m;
        let lo = ((self.center_world.z - self.extent_m) / s).floor() as i64 - 1;
        let hi = ((self.center_world.z + self.extent_m) / s).ceil() as i64 + 1;
        lo..=hi
    }

    /// The cells of layer `cz` around the rain volume, in (y, x) order.
    pub fn layer_cells(&self, cz: i64) -> impl Iterator<Item = [i64; 3]> {
        let s = self.cell_m;
        let c = self.center_world;
        let x0 = ((c.x - self.extent_m) / s).floor() as i64 - 1;
        let x1 = ((c.x + self.extent_m) / s).ceil() as i64 + 1;
        let y0 = ((c.y - self.extent_m) / s).floor() as i64 - 1;
        let y1 = ((c.y + self.extent_m) / s).ceil() as i64 + 1;
        (y0..=y1).flat_map(move |cy| (x0..=x1).map(move |cx| [cx, cy, cz]))
    }

    /// Centre of cell `c`, world metres.
    pub fn cell_centre(&self, c: [i64; 3]) -> DVec3 {
        (DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64) + 0.5) * self.cell_m
    }

    /// First streak along o + t·d (world, unit d) whose drop is met at
    /// t_axis ∈ (t_min, t_max), counting only streaks whose level coverage
    /// (`coverage` at α = 90°) is at least `min_coverage`.
    pub fn first_streak(
        &self,
        o: DVec3,
        d: DVec3,
        t_min: f64,
        t_max: f64,
        min_coverage: f64,
    ) -> Option<StreakHit> {
        let mut hit = [StreakHit::default()];
        let n = self.streaks_along(o, d, (t_min, t_max), min_coverage, &mut hit);
        (n == 1).then_some(hit[0])
    }

    /// The streaks along o + t·d as [`Rain::first_streak`] finds them, in
    /// order of t_axis, into `hits` (up to its length, one traversal);
    /// returns how many.
    pub fn streaks_along(
        &self,
        o: DVec3,
        d: DVec3,
        (t_min, t_max): (f64, f64),
        min_coverage: f64,
        hits: &mut [StreakHit],
    ) -> usize {
        let mut n = 0;
        if hits.is_empty() {
            return 0;
        }
        self.walk(o, d, t_min, t_max, min_coverage, |h| {
            hits[n] = h;
            n += 1;
            n < hits.len()
        });
        n
    }

    /// Hands the hits with t_axis ∈ (t_min, t_max) to `visit` in order
    /// until it returns false: cells in ray order (Amanatides–Woo), each
    /// cell's hits sorted (at most `CELL_HITS` per cell).
    fn walk(
        &self,
        o: DVec3,
        d: DVec3,
        t_min: f64,
        t_max: f64,
        min_coverage: f64,
        mut visit: impl FnMut(StreakHit) -> bool,
    ) {
        // Clip to the sphere of the rain volume (plus a cell of slack).
        let reach = self.extent_m + self.cell_m * 1.8;
        let Some((a, b)) = sphere_roots(o - self.center_world, d, reach) else {
            return;
        };
        let (mut t, t_end) = (t_min.max(a).max(0.0), t_max.min(b));
        if t >= t_end {
            return;
        }
        let sin2 = d.x * d.x + d.y * d.y;
        let max_r2 = self.max_radius().powi(2);
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
            // The drop is met inside the cell holding its capsule, so the
            // cells' hits come in ray order.
            let mut found = [StreakHit::default(); CELL_HITS];
            let mut n = 0;
            let (count, base) = self.cell_count(cell);
            for k in 0..count {
                let hash = mix64(base ^ k);
                // Cheap rejection on the axis alone: |w × d_xy| = b·|d_xy|.
                let (x, y) = self.axis_xy(cell, hash);
                let cross = (o.x - x) * d.y - (o.y - y) * d.x;
                if cross * cross >= max_r2 * sin2 {
                    continue;
                }
                let streak = self.streak(cell, hash);
                if let Some(h) = self.hit_streak(o, d, &streak, min_coverage) {
                    if h.t_axis > t_min && h.t_axis < t_max && n < CELL_HITS {
                        found[n] = h;
                        n += 1;
                    }
                }
            }
            found[..n].sort_unstable_by(|a, b| a.t_axis.total_cmp(&b.t_axis));
            for h in &found[..n] {
                if !visit(*h) {
                    return;
                }
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
    }

    /// Opacity of the rain in front of a pixel whose centre ray o + t·d
    /// reaches its surface at `t_max`: 1 − Π (1 − min(1, g · w)) over the
    /// streaks met, w their coverage. The pixel's radiance is then
    /// (1 − opacity)·L_behind + opacity·L_drop. The gain g rises from 1 to
    /// `opacity_gain` as a streak's image grows from a dot to
    /// `RESOLVED_STREAK_PX` pixels long: far drops stay the faint haze they
    /// are, near ones read as streaks.
    pub fn opacity(&self, o: DVec3, d: DVec3, t_max: f64) -> f64 {
        let mut clear = 1.0;
        self.walk(o, d, 0.0, t_max, self.min_opacity_coverage(), |h| {
            clear *= 1.0 - self.streak_opacity(&h);
            clear > 0.0
        });
        1.0 - clear
    }

    /// Smallest level coverage [`Rain::opacity`] counts.
    pub fn min_opacity_coverage(&self) -> f64 {
        Self::MIN_OPACITY_COVERAGE / self.opacity_gain.max(1.0)
    }

    /// Opacity one streak met at `hit` adds: min(1, g · w).
    pub fn streak_opacity(&self, hit: &StreakHit) -> f64 {
        (self.gain(hit) * hit.coverage).min(1.0)
    }

    /// Opacity gain of the streak of `hit` (see [`Rain::opacity`]).
    fn gain(&self, hit: &StreakHit) -> f64 {
        if self.opacity_gain == 1.0 || self.pixel_angle_rad <= 0.0 {
            return self.opacity_gain;
        }
        let len = self.fall_speed(2e3 * hit.drop_radius_m) * self.shutter_s;
        let len_px = len / (self.pixel_angle_rad * hit.t_axis.max(1e-3));
        1.0 + (self.opacity_gain - 1.0) * (len_px / RESOLVED_STREAK_PX).min(1.0)
    }

    /// Ray against one streak capsule, `None` below `min_coverage` (level
    /// coverage): the solid cylinder of the capsule
    /// radius about the vertical axis over the drop's sweep [top − L − r,
    /// top + r]. The drop is met where the ray passes closest to the axis,
    /// clamped into the part of the ray inside the cylinder.
    pub fn hit_streak(
        &self,
        o: DVec3,
        d: DVec3,
        streak: &Streak,
        min_coverage: f64,
    ) -> Option<StreakHit> {
        let axis_top = streak.axis_top;
        // Distance to a vertical line is horizontal: minimise it in xy.
        let sin2 = d.x * d.x + d.y * d.y;
        if sin2 < MIN_SIN2 {
            return None;
        }
        let (wx, wy) = (o.x - axis_top.x, o.y - axis_top.y);
        let t_axis = -(wx * d.x + wy * d.y) / sin2;
        let (bx, by) = (wx + d.x * t_axis, wy + d.y * t_axis);
        let b2 = bx * bx + by * by;
        let max_r = self.max_radius();
        if b2 >= max_r * max_r {
            return None;
        }
        let radius = self.streak_radius(streak);
        if b2 >= radius * radius || self.coverage(streak, radius, 1.0, 0.0) < min_coverage {
            return None;
        }
        let sin_a = sin2.sqrt();
        // |ray(t) − axis|² = b² + (t − t_axis)²·sin²α, clipped to the z slab.
        let half = (radius * radius - b2).sqrt() / sin_a;
        let (mut t_in, mut t_out) = (t_axis - half, t_axis + half);
        let r = streak.drop_radius_m;
        let (z0, z1) = (axis_top.z - streak.length_m - r, axis_top.z + r);
        if d.z != 0.0 {
            let (ta, tb) = ((z0 - o.z) / d.z, (z1 - o.z) / d.z);
            t_in = t_in.max(ta.min(tb));
            t_out = t_out.min(ta.max(tb));
        } else if o.z < z0 || o.z > z1 {
            return None;
        }
        (t_in < t_out).then(|| StreakHit {
            t: t_in,
            t_far: t_out,
            t_axis: t_axis.clamp(t_in, t_out),
            axis_top,
            drop_radius_m: r,
            coverage: self.coverage(streak, radius, sin_a, d.z),
        })
    }
}

#[cfg(test)]
pub(super) mod tests;
