//! Image-space denoising of radiance, guided by the exact (pixel-centre)
//! depth of the ground-truth pass (issue 4; "fog filter" and
//! `[render] filter_indirect` in the files). The path tracer hands over,
//! per pixel, the smooth parts of its radiance ([`ViewInputs`], from
//! `integrator::DenoiseSum`); [`denoise_view`] replaces each by a filtered
//! estimate, one view at a time:
//!
//! - fog in-scattering (`first_scatter.rs`): `l_fog`, the part of a camera
//!   sample whose first event is a medium scatter, has mean opacity·S, S the
//!   mean radiance scattered toward the camera along the ray: smooth,
//!   textureless. Per pixel S̃ = Σw·l_fog / Σw·opacity, and pixel =
//!   (L − l_fog) + opacity·S̃;
//! - light on the first surface (`surface.rs`): all it reflects beyond its
//!   own next-event estimates (sky and indirect light, with a medium fog
//!   light too), filtered as a ratio to the surface's albedo times its
//!   bounce's openness with the direct light's edge-stopping kernel; in
//!   medium-free scenes the first-scatter cascade is skipped;
//! - direct light on that surface (`direct.rs`): its next-event estimates
//!   of sky and lamps (the sun's stays as traced), and at a glossy surface
//!   (paint) all its light; also as a ratio to the albedo, with
//!   edge-stopping on the per-pixel noise level (variance from the sample
//!   moments) so that shadow edges stay;
//! - light along smooth glass's reflection (`direct.rs`, medium-free
//!   scenes): what a window mirrors, as a ratio to the Fresnel reflectance
//!   that every sample meeting the glass records (reflected or not), with
//!   the same edge-stopping filter: a window's sparkle is the share of
//!   samples that happened to reflect, and the ratio does not have it.
//!
//! [`Features`] is the one place that switches the image side's added
//! features on; `--no-filter` turns every one off.
//!
//! Kernel (`atrous.rs`): edge-avoiding à-trous (Dammertz et al. 2010,
//! dilated B3 rows then columns) with range weights from the guide only
//! ([`DepthGuide`]: pixel-centre opacity, relative depth_z, normals, sky vs
//! surface: a joint bilateral, Petschnigg et al. 2004), so both sums are
//! filtered alike; the direct, reflection and first-surface components add
//! an edge-stopping weight on their own noise (`edge_stop.rs`). Row-major
//! pixels (`Film`); fixed-order sums: same bytes on any thread count.

mod atrous;
mod conserve;
mod direct;
mod edge_stop;
mod features;
mod first_scatter;
mod guide;
mod inputs;
pub mod oidn;
mod regions;
mod surface;
mod widths;

pub use crate::scene::desc::Denoiser;
pub use features::Features;
pub use guide::{denoise_view, DepthGuide};
pub use inputs::ViewInputs;
pub use widths::Widths;

use glam::Vec3;

use crate::film::Film;

/// A view's first visible surfaces, averaged over each pixel's samples
/// (row-major): what Open Image Denoise is guided by.
#[derive(Clone, Copy, Debug)]
pub struct SurfaceAux<'a> {
    /// Throughput × albedo.
    pub albedo: &'a [Vec3],
    /// Unit shading normal (zero where none).
    pub normal: &'a [Vec3],
}

/// Replaces the first-scatter part of every pixel of `film` by its
/// filtered estimate: `film = film − inputs.l_fog + inputs.opacity · S̃`.
/// Pixels whose neighbourhood has no opacity keep their radiance. Then the
/// same for the light on the first surface (`surface.rs`: fog light, or in
/// a medium-free scene sky and indirect light): `film −= l_surf − rho · Ẽ`;
/// and for direct light (`l_direct`) and light along glass's reflection
/// (`l_refl`), when `widths.direct_levels` > 0.
/// [`denoise_view`] calls it with the guide and widths of a rendered view.
/// Preconditions: `inputs` and `guide` match `film`'s size (`guide.normal`
/// may be empty).
pub fn denoise_guided(
    film: &mut Film,
    inputs: &ViewInputs,
    guide: &DepthGuide<'_>,
    widths: &Widths,
) {
    let (w, h) = (film.width, film.height);
    let n = w * h;
    assert!(
        inputs.width == w
            && inputs.height == h
            && inputs.l_fog.len() == n
            && inputs.opacity.len() == n,
        "denoiser inputs' size does not match the film"
    );
    assert!(
        guide.depth_z.len() == n && guide.opacity.len() == n,
        "guide size does not match the film"
    );
    // Without first-scatter light (a medium-free scene filtering indirect
    // light) every pixel would keep its radiance: skip the cascade.
    if inputs.has_first_scatter() {
        first_scatter::filter_first_scatter(film, inputs, guide, widths);
    }
    surface::filter_surface(film, inputs, guide, widths);
    if widths.direct_levels > 0 {
        direct::filter_direct(film, inputs, guide, widths, widths.direct_levels);
        direct::filter_reflection(film, inputs, guide, widths, widths.direct_levels);
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
        let mut fog = ViewInputs::new(w, h);
        fog.l_fog.fill(Vec3::new(1.0, 1.5, 2.0));
        fog.opacity.fill(0.5);
        let (z, o) = flat_guide(w * h, 10.0, 0.5);
        let guide = DepthGuide {
            depth_z: &z,
            opacity: &o,
            normal: &[],
        };
        denoise_guided(&mut film, &fog, &guide, &Widths::for_width(w));
        for px in &film.rgb {
            assert!(
                (*px - Vec3::new(2.0, 3.0, 4.0)).abs().max_element() < 1e-5,
                "{px}"
            );
        }
    }

    /// Filters an 8 × 4 view, left half sky and right half a wall at 20 m,
    /// opacity 0.5 everywhere, the film all fog light; `varying_sky` picks
    /// which side alternates ×1.5/×0.5 by column around its level (sky 1,
    /// wall 5), the other side is constant. Returns the filtered film.
    fn sky_wall_split(varying_sky: bool) -> Film {
        let (w, h) = (8, 4);
        let mut fog = ViewInputs::new(w, h);
        let mut z = vec![0.0f32; w * h];
        for j in 0..h {
            for i in 0..w {
                let k = j * w + i;
                let sky = i < w / 2;
                z[k] = if sky { f32::INFINITY } else { 20.0 };
                fog.opacity[k] = 0.5;
                let level = if sky { 1.0 } else { 5.0 };
                let wiggle = if sky == varying_sky {
                    if i % 2 == 0 {
                        1.5
                    } else {
                        0.5
                    }
                } else {
                    1.0
                };
                fog.l_fog[k] = Vec3::splat(level * wiggle);
            }
        }
        let mut film = Film {
            width: w,
            height: h,
            rgb: fog.l_fog.clone(),
        };
        let o = vec![0.5; w * h];
        let guide = DepthGuide {
            depth_z: &z,
            opacity: &o,
            normal: &[],
        };
        let f = Widths {
            sigma_px: 4.0,
            ..Widths::for_width(w)
        };
        denoise_guided(&mut film, &fog, &guide, &f);
        film
    }

    #[test]
    fn sky_and_a_visible_surface_never_mix() {
        let (w, h) = (8, 4);
        for varying_sky in [true, false] {
            let film = sky_wall_split(varying_sky);
            let (mut lo, mut hi) = (f32::MAX, f32::MIN);
            for j in 0..h {
                for i in 0..w {
                    let sky = i < w / 2;
                    let want = if sky { 1.0 } else { 5.0 };
                    let got = film.get(i, j);
                    if sky != varying_sky {
                        // The constant side: a zero range weight across the
                        // edge leaves it exactly as it was.
                        assert!(
                            (got - Vec3::splat(want)).abs().max_element() <= 1e-6 * want,
                            "varying sky {varying_sky}: ({i},{j}) {got} vs {want}"
                        );
                    } else {
                        // The varying side: smoothed toward its own level.
                        assert!(
                            (got.x - want).abs() < 0.5 * want,
                            "varying sky {varying_sky}: ({i},{j}) {got} vs {want}"
                        );
                        lo = lo.min(got.x);
                        hi = hi.max(got.x);
                    }
                }
            }
            // The ×1.5/×0.5 columns spanned one level; filtered, much less.
            let want = if varying_sky { 1.0 } else { 5.0 };
            assert!(
                hi - lo < 0.5 * want,
                "varying sky {varying_sky}: spread {lo}..{hi}"
            );
        }
    }

    /// Scattered leaves in a foggy sky (every third pixel of every third
    /// row, their depths a factor 3 apart in turn over 12 steps, so no two
    /// leaves within the filter's taps of each other are alike), hidden by
    /// the fog to `leaf_opacity` under a sky of opacity 1; their fog light
    /// is noise (×1.8 / ×0.2 in turn) around the sky's ratio 1. Returns
    /// the leaves' RMS error from that ratio × opacity, after and before
    /// the filter.
    fn scattered_leaves(leaf_opacity: f32) -> (f32, f32) {
        let (w, h) = (24, 24);
        let mut fog = ViewInputs::new(w, h);
        let mut z = vec![f32::INFINITY; w * h];
        let mut o = vec![1.0f32; w * h];
        fog.opacity.fill(1.0);
        fog.l_fog.fill(Vec3::ONE);
        let mut leaves = Vec::new();
        for j in (1..h).step_by(3) {
            for i in (1..w).step_by(3) {
                let k = j * w + i;
                let n = leaves.len();
                z[k] = 10.0 * 3f32.powi(n as i32 % 12);
                o[k] = leaf_opacity;
                fog.opacity[k] = leaf_opacity;
                let noise = if n % 2 == 0 { 1.8 } else { 0.2 };
                fog.l_fog[k] = Vec3::splat(leaf_opacity * noise);
                leaves.push(k);
            }
        }
        let mut film = Film {
            width: w,
            height: h,
            rgb: fog.l_fog.clone(),
        };
        let guide = DepthGuide {
            depth_z: &z,
            opacity: &o,
            normal: &[],
        };
        denoise_guided(&mut film, &fog, &guide, &Widths::for_width(w));
        let rms = |img: &[Vec3]| {
            let sum: f32 = leaves.iter().map(|&k| (img[k].x - o[k]).powi(2)).sum();
            (sum / leaves.len() as f32).sqrt()
        };
        (rms(&film.rgb), rms(&fog.l_fog))
    }

    #[test]
    fn leaves_the_fog_hides_take_the_sky_s_fog_light() {
        // Hidden (opacity 0.95): their noise mostly goes.
        let (after, before) = scattered_leaves(0.95);
        assert!(after < 0.3 * before, "hidden leaves: {after} vs {before}");
        // Seen through thinner fog (0.6): the sky's light stays out.
        let (after, before) = scattered_leaves(0.6);
        assert!(after > 0.99 * before, "visible leaves: {after} vs {before}");
    }
}
