//! The first denoiser component: fog in-scattering, `l_fog` (the part of a
//! camera sample whose first event is a medium scatter), filtered as a
//! ratio to the first segment's opacity: per pixel S̃ = Σw·l_fog /
//! Σw·opacity and pixel = (L − l_fog) + opacity·S̃. Range weights:
//! pixel-centre opacity, relative depth_z, and between sky and surface
//! how much of the surface the fog leaves visible.

use glam::Vec4;

use super::atrous::{atrous_levels, atrous_pass, ln_depth, soft_gaussian, Axis};
use super::{DepthGuide, ViewInputs, Widths};
use crate::film::Film;

/// The first component of [`super::denoise_guided`]: `film = film − l_fog + opacity · S̃`.
pub(super) fn filter_first_scatter(
    film: &mut Film,
    fog: &ViewInputs,
    guide: &DepthGuide<'_>,
    filter: &Widths,
) {
    let n = film.width * film.height;
    let (w, h) = (film.width, film.height);
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
    let range = RangeWeight::new(filter);
    let mut cur = data;
    let mut tmp = vec![Vec4::ZERO; n];
    let weight = |a: Key, b: Key| range.weight(a, b);
    for level in 0..atrous_levels(filter.sigma_px) {
        let step = 1usize << level;
        // Rows, then columns, of the dilated B3 kernel.
        atrous_pass(&cur, &mut tmp, &keys, (w, h), step, &weight, Axis::Row);
        atrous_pass(&tmp, &mut cur, &keys, (w, h), step, &weight, Axis::Column);
    }
    for (k, px) in film.rgb.iter_mut().enumerate() {
        let s = cur[k];
        // Below this mean opacity the ratio is noise over nothing.
        if s.w > 1e-7 {
            *px = *px - fog.l_fog[k] + s.truncate() * (fog.opacity[k] / s.w);
        }
    }
}

/// A pixel's guide values.
#[derive(Clone, Copy, Debug)]
struct Key {
    /// ln depth_z (a difference is the relative depth step), +inf for sky.
    ln_z: f32,
    /// Pixel-centre opacity.
    opacity: f32,
}

impl Key {
    fn new(z: f32, opacity: f32) -> Key {
        Key {
            ln_z: ln_depth(z),
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
    fn new(f: &Widths) -> Self {
        RangeWeight {
            inv_opacity2: 1.0 / f.sigma_opacity.max(1e-6).powi(2),
            inv_rel2: 1.0 / f.sigma_depth_rel.max(1e-6).powi(2),
        }
    }

    /// Weight of neighbour `b` for centre `a`, in [0, 1]: Gaussian in
    /// opacity and, between surfaces, in relative depth. Between sky and a
    /// surface also in the surface's transparency 1 − opacity: the sky
    /// ray's ratio differs from the surface ray's only through the fog
    /// beyond the surface, whose share of the sky ray's opacity that is, so
    /// a surface the fog hides takes the sky's light (the thin leaves and
    /// wires against a foggy sky would else keep their few samples' noise)
    /// and a visible one none.
    #[inline]
    fn weight(&self, a: Key, b: Key) -> f32 {
        let (sky_a, sky_b) = (a.ln_z.is_infinite(), b.ln_z.is_infinite());
        let d_o = a.opacity - b.opacity;
        let mut e = d_o * d_o * self.inv_opacity2;
        if sky_a != sky_b {
            let seen = 1.0 - if sky_a { b.opacity } else { a.opacity };
            e += seen * seen * self.inv_opacity2;
        } else if !sky_a {
            let rel = a.ln_z - b.ln_z;
            e += rel * rel * self.inv_rel2;
        }
        soft_gaussian(e)
    }
}
