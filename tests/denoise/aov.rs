//! The auxiliary images for an external denoiser (`render::AovImages`,
//! written with `--hdr` as `left/albedo/` and `left/aov_normal/`): the
//! albedo and normal of the first visible surface, seen through glass.
//! A wall of known albedo 9.9 m ahead, sky around it; with a tinted glass
//! pane in front of part of it, the pane's pixels show the wall's normal and
//! its albedo times what the glass lets through.

use crate::common;

use common::{render_inline, Rendered};
use glam::Vec3;
use parallax::accel::Backend;
use parallax::render::AovImages;
use parallax::scene::mask_bits::{SKY, TRANSPARENT};

const W: u32 = 32;
const H: u32 = 18;
const ALBEDO: Vec3 = Vec3::new(0.2, 0.4, 0.6);

/// The wall (front face at x = 9.9 m, y in ±4 m, z in 0..3 m) under a
/// grey sky, plus `extra`.
fn scene(extra: &str) -> String {
    format!(
        "[sky]\nkind = \"gradient\"\nzenith = [0.2, 0.2, 0.2]\nhorizon = [0.3, 0.3, 0.3]\nground = [0.0, 0.0, 0.0]\n\
         [[material]]\nname = \"wall\"\nkind = \"diffuse\"\nalbedo = [0.2, 0.4, 0.6]\n\
         [[object]]\nkind = \"box\"\nsize = [0.2, 8.0, 3.0]\nmaterial = \"wall\"\n\
         transform = {{ translate = [10.0, 0.0, 1.5] }}\n{extra}"
    )
}

/// A smooth glass pane 5 m ahead over the image's left half (y in 0..3 m)
/// whose faces each halve green light.
const PANE: &str = "[[material]]\nname = \"glass\"\nkind = \"dielectric\"\nior = 1.5\n\
    roughness = 0.0\ntint = [1.0, 0.5, 1.0]\n\
    [[object]]\nkind = \"box\"\nsize = [0.05, 3.0, 4.0]\nmaterial = \"glass\"\n\
    transform = { translate = [5.0, 1.5, 1.5] }\n";

fn render(body: &str) -> (Rendered, AovImages) {
    let r = render_inline(body, (W, H), (64, 3, 4), "", Backend::Bvh);
    let aov = r.out.aov.clone().expect("a path-traced frame has AOVs");
    assert_eq!(aov.albedo.len(), (W * H) as usize);
    (r, aov)
}

/// Pixels whose 3 × 3 neighbourhood all pass `f` (inside the image).
fn interior(f: impl Fn(usize) -> bool) -> Vec<usize> {
    common::interior(W as usize, H as usize, |_, n| f(n))
}

#[test]
fn the_wall_shows_its_albedo_and_normal_and_the_sky_nothing() {
    let (r, aov) = render(&scene(""));
    let gt = &r.out.left;
    let wall = interior(|k| (gt.depth_z[k] - 9.9).abs() < 1e-3);
    let sky = interior(|k| gt.mask[k] & SKY != 0);
    assert!(
        wall.len() > 40 && sky.len() > 40,
        "{} {}",
        wall.len(),
        sky.len()
    );
    for &k in &wall {
        // Every sample hits the wall straight from the camera.
        assert!(
            (aov.albedo[k] - ALBEDO).abs().max_element() < 1e-6,
            "{k}: {}",
            aov.albedo[k]
        );
        assert!(
            (aov.normal[k] - Vec3::NEG_X).length() < 1e-5,
            "{k}: {}",
            aov.normal[k]
        );
    }
    for &k in &sky {
        assert_eq!(
            (aov.albedo[k], aov.normal[k]),
            (Vec3::ZERO, Vec3::ZERO),
            "{k}"
        );
    }
}

#[test]
fn through_glass_the_wall_is_seen_with_the_glass_throughput() {
    let (r, aov) = render(&scene(PANE));
    let gt = &r.out.left;
    // The pane's pixels with the wall behind (the wall's pixels without it).
    let (clear, _) = render(&scene(""));
    let behind = interior(|k| {
        gt.mask[k] & TRANSPARENT != 0 && (clear.out.left.depth_z[k] - 9.9).abs() < 1e-3
    });
    assert!(behind.len() > 10, "{}", behind.len());
    let mut mean = Vec3::ZERO;
    for &k in &behind {
        let ratio = aov.albedo[k] / ALBEDO;
        // What the glass lets through (per sample the throughput of the
        // reflect-or-refract choice, so above one where refraction was
        // picked less often than it transmits): green halved at each of
        // the pane's two faces.
        assert!((ratio.y - 0.25 * ratio.x).abs() < 1e-4, "{k}: {ratio}");
        assert!((ratio.z - ratio.x).abs() < 1e-4, "{k}: {ratio}");
        // The wall's normal, not the pane's (both face the camera: the
        // pane's side faces would tilt it).
        assert!(
            (aov.normal[k] - Vec3::NEG_X).length() < 1e-5,
            "{k}: {}",
            aov.normal[k]
        );
        mean += ratio;
    }
    // On average, two faces of Fresnel reflection at near-normal incidence
    // (≈ 4 % each) lost: 0.96² ≈ 0.92.
    let t = mean.x / behind.len() as f32;
    assert!((0.85..0.97).contains(&t), "mean transmitted share {t}");
}
