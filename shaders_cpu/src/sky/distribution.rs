//! Importance sampling of a tabulated sky: a piecewise-constant 2D
//! distribution over an equal-area grid of the sphere (pbrt-v4 §A.5.2's
//! marginal/conditional construction on cells uniform in (z, φ)).
//!
//! Cells are uniform in z = cos θ and φ, so each spans the same solid angle
//! 4π/(n_z·n_φ) and the pdf per solid angle is exactly pmf(cell)·n_z·n_φ/(4π).
//! Weights are the cell's mean luminance (2 × 2 points) plus a floor of 1% of
//! the sphere mean, so the pdf is positive wherever the sky can emit.

use crate::sampling::{luminance, sin_cos_turns};
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// Rows along z ∈ [−1, 1] and columns along φ ∈ [−π, π].
pub const GRID: (usize, usize) = (64, 128);

/// A sampling distribution over directions built from a radiance function.
#[derive(Clone, Debug)]
pub struct SkyDistribution {
    /// Per-row marginal cdf (n_z entries, last = 1).
    marginal: Vec<f32>,
    /// Per-cell conditional cdf within each row.
    conditional: Vec<f32>,
    /// Per-cell probability.
    pmf: Vec<f32>,
    /// (1/4π)∫ le dω estimated on the grid (exact for piecewise-constant le).
    mean_le: Vec3,
    /// Mean luminance of each cell before the floor (row-major, z then φ).
    cell_lum: Vec<f32>,
}

impl SkyDistribution {
    /// Tabulates `le` (world direction → radiance) on the grid.
    pub fn new(le: impl Fn(Vec3) -> Vec3) -> Self {
        let (nz, nphi) = GRID;
        let mut w = vec![0.0f64; nz * nphi];
        let mut sum_le = glam::DVec3::ZERO;
        for j in 0..nz {
            for i in 0..nphi {
                let mut acc = 0.0;
                for s in 0..4 {
                    let u = Vec2::new(
                        (i as f32 + 0.25 + 0.5 * (s % 2) as f32) / nphi as f32,
                        (j as f32 + 0.25 + 0.5 * (s / 2) as f32) / nz as f32,
                    );
                    let l = le(dir_of(u));
                    sum_le += l.as_dvec3();
                    acc += luminance(l).max(0.0) as f64;
                }
                w[j * nphi + i] = acc / 4.0;
            }
        }
        let cell_lum = w.iter().map(|&x| x as f32).collect();
        Self::from_weights(w, (sum_le / (4 * nz * nphi) as f64).as_vec3(), cell_lum)
    }

    /// The same sky with each cell's luminance multiplied by
    /// `row_weight(z_lo, z_hi)` (≥ 0) of its row's z = cos θ range, e.g. the
    /// largest transmittance through fog over the row. The 1 % floor is
    /// taken from the reweighted mean, so the pdf stays positive everywhere.
    pub fn reweighted(&self, row_weight: impl Fn(f32, f32) -> f32) -> Self {
        let (nz, nphi) = GRID;
        let mut w = Vec::with_capacity(nz * nphi);
        for j in 0..nz {
            let z_lo = 2.0 * j as f32 / nz as f32 - 1.0;
            let z_hi = 2.0 * (j + 1) as f32 / nz as f32 - 1.0;
            let k = row_weight(z_lo, z_hi).max(0.0) as f64;
            let row = &self.cell_lum[j * nphi..(j + 1) * nphi];
            w.extend(row.iter().map(|&x| x as f64 * k));
        }
        Self::from_weights(w, self.mean_le, self.cell_lum.clone())
    }

    /// Builds the cdfs from per-cell weights `w` (≥ 0), adding the floor.
    fn from_weights(mut w: Vec<f64>, mean_le: Vec3, cell_lum: Vec<f32>) -> Self {
        let (nz, nphi) = GRID;
        let mean = w.iter().sum::<f64>() / w.len() as f64;
        let floor = if mean > 0.0 { 0.01 * mean } else { 1.0 };
        w.iter_mut().for_each(|x| *x += floor);
        let total: f64 = w.iter().sum();
        let pmf: Vec<f32> = w.iter().map(|x| (x / total) as f32).collect();
        let mut marginal = Vec::with_capacity(nz);
        let mut conditional = Vec::with_capacity(nz * nphi);
        let mut acc_rows = 0.0f64;
        for j in 0..nz {
            let row = &w[j * nphi..(j + 1) * nphi];
            let row_sum: f64 = row.iter().sum();
            let mut acc = 0.0f64;
            for x in row {
                acc += x;
                conditional.push((acc / row_sum) as f32);
            }
            acc_rows += row_sum;
            marginal.push((acc_rows / total) as f32);
        }
        SkyDistribution {
            marginal,
            conditional,
            pmf,
            mean_le,
            cell_lum,
        }
    }

    /// Draws a direction; returns (dir, pdf per solid angle).
    pub fn sample(&self, u: Vec2) -> (Vec3, f32) {
        self.sample_if_row(u, |_, _| true)
            .expect("every row is kept")
    }

    /// [`SkyDistribution::sample`], offering the z = cos θ range of the
    /// drawn row to `row_kept` first and stopping (None) where it declines:
    /// a caller whose roulette drops most directions by a bound over their
    /// row skips the column search and the pdf. Kept draws are `sample`'s.
    pub fn sample_if_row(
        &self,
        u: Vec2,
        row_kept: impl FnOnce(f32, f32) -> bool,
    ) -> Option<(Vec3, f32)> {
        let (nz, nphi) = GRID;
        let (j, vy) = invert(&self.marginal, u.y);
        let z_lo = 2.0 * j as f32 / nz as f32 - 1.0;
        let z_hi = 2.0 * (j + 1) as f32 / nz as f32 - 1.0;
        if !row_kept(z_lo, z_hi) {
            return None;
        }
        let row = &self.conditional[j * nphi..(j + 1) * nphi];
        let (i, vx) = invert(row, u.x);
        let cell_u = Vec2::new((i as f32 + vx) / nphi as f32, (j as f32 + vy) / nz as f32);
        // The drawn cell's own density: `pdf(dir)` would find the cell
        // again from the direction (an atan2), the same one but where
        // rounding puts `dir` on a cell border.
        Some((dir_of(cell_u), self.cell_pdf(j, i)))
    }

    /// Pdf per solid angle of every direction in cell (row `j`, column `i`).
    fn cell_pdf(&self, j: usize, i: usize) -> f32 {
        let (nz, nphi) = GRID;
        self.pmf[j * nphi + i] * (nz * nphi) as f32 / (4.0 * PI)
    }

    /// Pdf per solid angle of [`SkyDistribution::sample`] producing `dir`.
    pub fn pdf(&self, dir: Vec3) -> f32 {
        let (nz, nphi) = GRID;
        let z = dir.z.clamp(-1.0, 1.0);
        let j = (((z + 1.0) * 0.5 * nz as f32) as usize).min(nz - 1);
        let phi = dir.y.atan2(dir.x);
        let i = (((phi + PI) / (2.0 * PI) * nphi as f32) as usize).min(nphi - 1);
        self.cell_pdf(j, i)
    }

    /// Mean radiance over the sphere, (1/4π)∫ le dω, from the tabulation points.
    pub fn mean_le(&self) -> Vec3 {
        self.mean_le
    }
}

/// Direction of unit grid coordinates (u.x along φ, u.y along z).
fn dir_of(u: Vec2) -> Vec3 {
    let z = (2.0 * u.y - 1.0).clamp(-1.0, 1.0);
    // φ = −π + 2π·u.x, i.e. u.x − 1/2 turns.
    let (sin_phi, cos_phi) = sin_cos_turns(u.x - 0.5);
    let r = (1.0 - z * z).max(0.0).sqrt();
    Vec3::new(r * cos_phi, r * sin_phi, z)
}

/// Index of the cdf interval containing `u` and the position within it.
/// The interval is the number of entries ≤ `u` (a cdf never decreases, so
/// it is the binary search's answer): counted over the whole row, whose
/// loads do not wait on each other as a binary search's do. Most draws
/// come from fog tables far larger than the caches, where each step of a
/// search waited for its cache line.
fn invert(cdf: &[f32], u: f32) -> (usize, f32) {
    let below = cdf.iter().fold(0usize, |n, &c| n + (c <= u) as usize);
    let k = below.min(cdf.len() - 1);
    let lo = if k == 0 { 0.0 } else { cdf[k - 1] };
    let width = cdf[k] - lo;
    let t = if width > 0.0 { (u - lo) / width } else { 0.5 };
    (k, t.clamp(0.0, 1.0 - f32::EPSILON))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn invert_finds_the_binary_searchs_interval() {
        // Ties, flat runs (zero-weight cells), u on an entry, below the
        // first and at the last.
        let cdf = [0.0, 0.0, 0.125, 0.25, 0.25, 0.25, 0.5, 0.875, 1.0, 1.0];
        let mut us: Vec<f32> = cdf.to_vec();
        us.extend([0.1, 0.3, 0.6, 0.9, 0.999_999, f32::MIN_POSITIVE]);
        us.extend(
            cdf.iter()
                .map(|&c| f32::from_bits(c.to_bits().saturating_sub(1))),
        );
        for u in us {
            let k = cdf.partition_point(|&c| c <= u).min(cdf.len() - 1);
            let (got, t) = invert(&cdf, u);
            assert_eq!(got, k, "u = {u}");
            let lo = if k == 0 { 0.0 } else { cdf[k - 1] };
            let width = cdf[k] - lo;
            let want = if width > 0.0 { (u - lo) / width } else { 0.5 };
            assert_eq!(t.to_bits(), want.clamp(0.0, 1.0 - f32::EPSILON).to_bits());
        }
        // The tables' own rows: every cell's interior maps back to it.
        let t = table();
        for (j, w) in t.marginal.windows(2).enumerate() {
            let u = 0.5 * (w[0] + w[1]);
            if w[1] > w[0] {
                assert_eq!(invert(&t.marginal, u).0, j + 1);
            }
        }
    }

    #[test]
    fn a_draws_pdf_is_the_pdf_of_its_direction() {
        // The drawn cell's density is the one `pdf` finds again from the
        // drawn direction, bit for bit, but for the few directions rounding
        // puts on a cell border (the neighbour's pmf there).
        let t = table();
        let n = 16384u32;
        let mut borders = 0;
        for k in 0..n {
            let u = Vec2::new((k as f32 * 0.618_034).fract(), (k as f32 + 0.5) / n as f32);
            let (dir, pdf) = t.sample(u);
            if pdf.to_bits() != t.pdf(dir).to_bits() {
                borders += 1;
            }
        }
        assert!(borders <= 4, "{borders} of {n} draws off their cell");
    }

    /// A sky bright toward +z and +x, so rows and columns differ.
    fn table() -> SkyDistribution {
        SkyDistribution::new(|d| Vec3::splat(1.0 + 4.0 * d.z.max(0.0) + (2.0 * d.x).exp()))
    }

    #[test]
    fn a_row_filter_keeps_samples_bits_and_declines_only_its_rows() {
        // Kept draws are `sample`'s to the bit; a draw is declined exactly
        // when its row is, and the row offered holds the drawn direction.
        let t = table();
        let mut declined = 0;
        for k in 0..4096u32 {
            let u = Vec2::new((k as f32 * 0.618_034).fract(), (k as f32 + 0.5) / 4096.0);
            let (dir, pdf) = t.sample(u);
            let mut row = None;
            let got = t.sample_if_row(u, |lo, hi| {
                row = Some((lo, hi));
                !(0.25..0.5).contains(&lo)
            });
            let (lo, hi) = row.expect("the row is offered");
            assert!(
                dir.z >= lo - 1e-6 && dir.z <= hi + 1e-6,
                "{dir} outside [{lo}, {hi}]"
            );
            match got {
                Some((d, p)) => {
                    assert_eq!((d.to_array(), p.to_bits()), (dir.to_array(), pdf.to_bits()));
                }
                None => {
                    assert!((0.25..0.5).contains(&lo), "row [{lo}, {hi}] declined");
                    declined += 1;
                }
            }
        }
        // The table's own share of z ∈ [0.25, 0.5).
        assert!(declined > 200 && declined < 2000, "{declined} declined");
    }
}
