//! Relief (bump) conserves energy through the whole path tracer: a sphere
//! under a constant white sky (every bounce escapes, so each point returns
//! its albedo × the sky) gives the same mean radiance with its texture's
//! relief at several strengths as with the relief off (`bump = 0`, same
//! albedo field), for a white and a grey base; and a plane seen at normal
//! incidence keeps its mean albedo. The BSDF-level furnace (every sample's
//! weight exactly the albedo) is `shaders_cpu/tests/normal_map.rs`.

use crate::common;

use common::{camera_block, mean_stderr, render, scene_from_toml, Rendered};
use parallax::accel::Backend;

/// Linear radiance (green) of left pixels whose 3×3 neighbourhood all hits
/// instance `id`.
fn interior_values(r: &Rendered, id: u16) -> Vec<f64> {
    let (w, h) = (r.out.left.width as usize, r.out.left.height as usize);
    let img = &r.out.images[0].rgb;
    let mut v = Vec::new();
    for j in 1..h - 1 {
        for i in 1..w - 1 {
            if (0..9).all(|n| r.out.left.instance[(j + n / 3 - 1) * w + i + n % 3 - 1] == id) {
                v.push(img[j * w + i].y as f64);
            }
        }
    }
    v
}

/// The sphere of `analytic_furnace` in a constant sky of radiance 1, its
/// diffuse material of albedo `rho` textured by `kind` at relief `bump`.
fn sphere(rho: f64, kind: &str, bump: f64, spp: u32) -> Vec<f64> {
    let text = format!(
        "{}[render]\nspp = {spp}\nmax_depth = 8\nseed = 3\nfilter_indirect = false\n[sky]\nkind = \"constant\"\nle = [1.0, 1.0, 1.0]\n\
[[material]]\nname = \"m\"\nkind = \"diffuse\"\nalbedo = [{rho:?}, {rho:?}, {rho:?}]\ntexture = {{ kind = \"{kind}\", bump = {bump:?} }}\n\
[[object]]\nkind = \"sphere\"\nradius = 2.0\nmaterial = \"m\"\ninstance = 7\ntransform = {{ translate = [8.0, 0.0, 1.65] }}\n",
        camera_block(96, 64, [0.0, 0.0, 1.65])
    );
    let mut loaded = scene_from_toml(&text);
    loaded.desc.camera.baselines_cm = vec![54.0];
    interior_values(&render(&loaded, Backend::default_backend(), spp), 7)
}

/// Bumped and flat means agree within 1 % and 4 standard errors of their
/// per-pixel difference.
fn same_energy(bumped: &[f64], flat: &[f64], what: &str) {
    assert_eq!(bumped.len(), flat.len(), "{what}: same pixels");
    assert!(flat.len() > 200, "{what}: too few pixels");
    let diff: Vec<f64> = bumped.iter().zip(flat).map(|(a, b)| a - b).collect();
    let (d, se) = mean_stderr(&diff);
    let (m, _) = mean_stderr(flat);
    eprintln!("{what}: flat {m:.5}, bumped − flat {d:.5} ± {se:.5}");
    assert!(d.abs() <= 0.01 * m, "{what}: bumped − flat = {d} of {m}");
    assert!(d.abs() <= 4.0 * se.max(1e-6), "{what}: z = {}", d / se);
}

#[test]
fn relief_keeps_a_white_and_a_grey_sphere_as_bright_as_flat() {
    for (rho, kind) in [(1.0, "bark"), (0.5, "brick"), (0.5, "soil")] {
        let flat = sphere(rho, kind, 0.0, 16);
        // The albedo field is the texture's: its mean is near the nominal
        // albedo (white clamps at 0.99 where the pattern brightens).
        let (m, _) = mean_stderr(&flat);
        assert!((m - rho).abs() < 0.1 * rho, "{kind}: flat mean {m}");
        for bump in [1.0, 2.5, 4.0] {
            same_energy(
                &sphere(rho, kind, bump, 16),
                &flat,
                &format!("{kind} ρ {rho} bump {bump}"),
            );
        }
    }
}

/// Camera 0.4 m above a plane looking straight down (3.3 mm pixels, so the
/// relief is resolved and not filtered away by the ray footprint), constant
/// sky 1.
fn plane_from_above(kind: &str, bump: f64) -> Vec<f64> {
    let text = format!(
        "[camera]\nwidth = 64\nheight = 48\nhfov_deg = 30.0\nbaselines_cm = [10.0]\nposition = [0.0, 0.0, 0.4]\npitch_deg = 90.0\n\
[render]\nspp = 16\nmax_depth = 4\nseed = 5\nfilter_indirect = false\n[sky]\nkind = \"constant\"\nle = [1.0, 1.0, 1.0]\n\
[[material]]\nname = \"m\"\nkind = \"diffuse\"\nalbedo = [0.5, 0.5, 0.5]\ntexture = {{ kind = \"{kind}\", bump = {bump:?} }}\n\
[[object]]\nkind = \"quad\"\nsize = [1000.0, 1000.0]\nmaterial = \"m\"\ninstance = 3\n"
    );
    interior_values(
        &render(&scene_from_toml(&text), Backend::default_backend(), 16),
        3,
    )
}

#[test]
fn relief_keeps_the_mean_albedo_at_normal_incidence() {
    for kind in ["asphalt", "paving", "grass"] {
        let flat = plane_from_above(kind, 0.0);
        let bumped = plane_from_above(kind, 2.0);
        same_energy(&bumped, &flat, &format!("{kind} from above"));
        // And the relief does show: pixels differ.
        let changed = bumped.iter().zip(&flat).filter(|(a, b)| a != b).count();
        assert!(
            changed * 2 > flat.len(),
            "{kind}: relief changed {changed} pixels"
        );
    }
}
