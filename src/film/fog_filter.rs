//! Image-space filtering of fog in-scattering (issue 4): each camera
//! sample's radiance is split into `l_fog`, the part whose first event is a
//! medium scatter before the first surface or the sky, and the rest
//! (`integrator::path::LiSample`). E[l_fog] = (1 − Tr)·S with S the mean
//! radiance scattered toward the camera along the ray: smooth in direction
//! and in optical depth, free of texture. So the filter estimates S per pixel
//! as a ratio of two cross-bilateral sums (Σ w·l_fog / Σ w·opacity, the same
//! weights on both), multiplies back by the pixel's own opacity and puts it in
//! place of the pixel's noisy l_fog: pixel = (L − l_fog) + opacity·S̃.
//! Weights: Gaussian in image distance (separable: a row pass, then a column
//! pass), Gaussian in the pixel-centre opacity and relative depth_z of the
//! ground-truth pass, and zero between sky and surface pixels (Eisemann &
//! Durand 2004, Petschnigg et al. 2004: joint/cross bilateral filtering).
//! Pixels are row-major (`Film`); every output pixel is a fixed-order sum,
//! so any thread count gives the same bytes.

use glam::{Vec3, Vec4};
use rayon::prelude::*;

use super::Film;

/// One view's first-scatter radiance, per pixel the mean over its samples.
#[derive(Clone, Debug, PartialEq)]
pub struct FogLayer {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// Mean first-medium-scatter radiance per pixel (part of the film's radiance).
    pub l_fog: Vec<Vec3>,
    /// Mean opacity 1 − Tr of the samples' first segments per pixel, in [0, 1].
    pub opacity: Vec<f32>,
}

impl FogLayer {
    /// A layer of `width × height` pixels with no fog.
    pub fn new(width: usize, height: usize) -> FogLayer {
        FogLayer {
            width,
            height,
            l_fog: vec![Vec3::ZERO; width * height],
            opacity: vec![0.0; width * height],
        }
    }

    /// Whether any pixel carries first-scatter radiance or opacity.
    pub fn is_empty(&self) -> bool {
        self.opacity.iter().all(|&o| o == 0.0) && self.l_fog.iter().all(|&l| l == Vec3::ZERO)
    }
}

/// The view's ground truth that steers the filter, per pixel (row-major).
#[derive(Clone, Copy, Debug)]
pub struct FogGuide<'a> {
    /// Pixel-centre depth_z in metres (+inf or NaN: sky).
    pub depth_z: &'a [f32],
    /// Opacity 1 − Tr of the pixel-centre ray up to that depth, in [0, 1].
    pub opacity: &'a [f32],
}

/// Filter widths.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FogFilter {
    /// Spatial Gaussian σ in pixels (> 0); the kernel reaches 3σ.
    pub sigma_px: f32,
    /// Range σ on the pixel-centre opacity difference (> 0).
    pub sigma_opacity: f32,
    /// Range σ on |Δdepth_z| / min(depth_z) between two surface pixels (> 0).
    pub sigma_depth_rel: f32,
}

impl FogFilter {
    /// The default widths for a view `width` pixels wide: the spatial σ
    /// scales with resolution (a fixed angular footprint) and is at least
    /// one pixel, so tiny test images still filter.
    pub fn for_width(width: usize) -> FogFilter {
        FogFilter {
            sigma_px: (width as f32 / 160.0 * SIGMA_PX_AT_160).max(1.0),
            sigma_opacity: 0.1,
            sigma_depth_rel: 0.3,
        }
    }
}

/// Spatial σ at 160 pixels across (the tuning images' width).
const SIGMA_PX_AT_160: f32 = 2.0;

/// Replaces the first-scatter part of every pixel of `film` by its
/// filtered estimate: `film = film − fog.l_fog + fog.opacity · S̃`. Pixels
/// whose neighbourhood has no opacity keep their radiance. Preconditions:
/// `fog` and `guide` match `film`'s size.
pub fn filter_fog(film: &mut Film, fog: &FogLayer, guide: &FogGuide<'_>, filter: &FogFilter) {
    let (w, h) = (film.width, film.height);
    let n = w * h;
    assert!(
        fog.width == w && fog.height == h && fog.l_fog.len() == n && fog.opacity.len() == n,
        "fog layer size does not match the film"
    );
    assert!(
        guide.depth_z.len() == n && guide.opacity.len() == n,
        "guide size does not match the film"
    );
    let keys: Vec<Key> = guide
        .depth_z
        .iter()
        .zip(guide.opacity)
        .map(|(&z, &o)| Key::new(z, o))
        .collect();
    let data: Vec<Vec4> = fog
        .l_fog
        .iter()
        .zip(&fog.opacity)
        .map(|(l, &o)| l.extend(o))
        .collect();
    let taps = spatial_taps(filter.sigma_px);
    let range = RangeWeight::new(filter);
    // Row pass: neighbours at stride 1 within the row.
    let rows = pass(&data, &keys, w, h, &taps, &range, Axis::Row);
    // Column pass on the row pass's sums.
    let sums = pass(&rows, &keys, w, h, &taps, &range, Axis::Column);
    for (k, px) in film.rgb.iter_mut().enumerate() {
        let s = sums[k];
        // Below this summed opacity the ratio is noise over nothing.
        if s.w > 1e-6 {
            *px = *px - fog.l_fog[k] + s.truncate() * (fog.opacity[k] / s.w);
        }
    }
}

/// Which neighbours a pass visits.
#[derive(Clone, Copy, Debug)]
enum Axis {
    Row,
    Column,
}

/// Weighted sums of `data` over each pixel's neighbours along `axis`
/// (spatial weight × range weight against the centre's key).
fn pass(
    data: &[Vec4],
    keys: &[Key],
    w: usize,
    h: usize,
    taps: &[f32],
    range: &RangeWeight,
    axis: Axis,
) -> Vec<Vec4> {
    let r = taps.len() - 1;
    let mut out = vec![Vec4::ZERO; w * h];
    out.par_chunks_mut(w).enumerate().for_each(|(j, row)| {
        for (i, o) in row.iter_mut().enumerate() {
            let c = j * w + i;
            let kc = keys[c];
            let (pos, len, stride) = match axis {
                Axis::Row => (i, w, 1),
                Axis::Column => (j, h, w),
            };
            let lo = pos.saturating_sub(r);
            let hi = (pos + r).min(len - 1);
            let mut s = Vec4::ZERO;
            for q in lo..=hi {
                let k = c + q * stride - pos * stride;
                let wr = range.weight(kc, keys[k]);
                if wr > 0.0 {
                    s += data[k] * (taps[q.abs_diff(pos)] * wr);
                }
            }
            *o = s;
        }
    });
    out
}

/// Gaussian weights at distances 0..=ceil(3σ) pixels.
fn spatial_taps(sigma_px: f32) -> Vec<f32> {
    let sigma = sigma_px.max(1e-3);
    let r = (3.0 * sigma).ceil() as usize;
    (0..=r)
        .map(|d| (-0.5 * (d as f32 / sigma).powi(2)).exp())
        .collect()
}

/// A pixel's guide values.
#[derive(Clone, Copy, Debug)]
struct Key {
    /// depth_z, or +inf for sky.
    z: f32,
    /// Pixel-centre opacity.
    opacity: f32,
}

impl Key {
    fn new(z: f32, opacity: f32) -> Key {
        Key {
            z: if z.is_finite() && z > 0.0 {
                z
            } else {
                f32::INFINITY
            },
            opacity: if opacity.is_finite() { opacity } else { 0.0 },
        }
    }
}

/// The range part of the kernel.
#[derive(Clone, Copy, Debug)]
struct RangeWeight {
    inv_opacity2: f32,
    inv_rel2: f32,
}

impl RangeWeight {
    fn new(f: &FogFilter) -> Self {
        RangeWeight {
            inv_opacity2: 1.0 / f.sigma_opacity.max(1e-6).powi(2),
            inv_rel2: 1.0 / f.sigma_depth_rel.max(1e-6).powi(2),
        }
    }

    /// Weight of neighbour `b` for centre `a`, in [0, 1]: zero between sky
    /// and surface, Gaussian in opacity and (surfaces) relative depth.
    #[inline]
    fn weight(&self, a: Key, b: Key) -> f32 {
        let sky_a = a.z.is_infinite();
        if sky_a != b.z.is_infinite() {
            return 0.0;
        }
        let d_o = a.opacity - b.opacity;
        let mut e = d_o * d_o * self.inv_opacity2;
        if !sky_a {
            let rel = (a.z - b.z) / a.z.min(b.z);
            e += rel * rel * self.inv_rel2;
        }
        if e > 18.0 {
            0.0
        } else {
            (-0.5 * e).exp()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn flat_guide(n: usize, z: f32, o: f32) -> (Vec<f32>, Vec<f32>) {
        (vec![z; n], vec![o; n])
    }

    #[test]
    fn constant_fog_is_a_fixed_point() {
        let (w, h) = (9, 7);
        let mut film = Film::uniform(w, h, Vec3::new(2.0, 3.0, 4.0));
        let mut fog = FogLayer::new(w, h);
        fog.l_fog.fill(Vec3::new(1.0, 1.5, 2.0));
        fog.opacity.fill(0.5);
        let (z, o) = flat_guide(w * h, 10.0, 0.5);
        let guide = FogGuide {
            depth_z: &z,
            opacity: &o,
        };
        filter_fog(&mut film, &fog, &guide, &FogFilter::for_width(w));
        for px in &film.rgb {
            assert!(
                (*px - Vec3::new(2.0, 3.0, 4.0)).abs().max_element() < 1e-5,
                "{px}"
            );
        }
    }

    #[test]
    fn sky_and_surface_never_mix() {
        let (w, h) = (8, 4);
        // Left half sky with fog radiance 1, right half a wall with 5.
        let mut fog = FogLayer::new(w, h);
        let mut z = vec![0.0f32; w * h];
        for j in 0..h {
            for i in 0..w {
                let k = j * w + i;
                let sky = i < w / 2;
                z[k] = if sky { f32::INFINITY } else { 20.0 };
                fog.opacity[k] = 0.5;
                fog.l_fog[k] =
                    Vec3::splat(if sky { 1.0 } else { 5.0 }) * if i % 2 == 0 { 1.5 } else { 0.5 };
            }
        }
        let mut film = Film {
            width: w,
            height: h,
            rgb: fog.l_fog.clone(),
        };
        let o = vec![0.5; w * h];
        let guide = FogGuide {
            depth_z: &z,
            opacity: &o,
        };
        let f = FogFilter {
            sigma_px: 4.0,
            ..FogFilter::for_width(w)
        };
        filter_fog(&mut film, &fog, &guide, &f);
        for j in 0..h {
            for i in 0..w {
                let want = if i < w / 2 { 1.0 } else { 5.0 };
                // Smoothed toward the side's mean, never toward the other side.
                let got = film.get(i, j).x;
                assert!((got - want).abs() < 0.5 * want, "({i},{j}) {got} vs {want}");
            }
        }
    }

    #[test]
    fn spatial_taps_are_a_gaussian_reaching_three_sigma() {
        let t = spatial_taps(2.0);
        assert_eq!(t.len(), 7);
        assert_eq!(t[0], 1.0);
        assert!((t[2] - (-0.5f32).exp()).abs() < 1e-6);
        assert_eq!(spatial_taps(0.4).len(), 3);
    }
}
