//! Procedural textures in rendered frames: a function of world position
//! (not of the render origin), ground truth untouched, and structure a
//! stereo matcher can use (consistent high-frequency energy in the image).

use crate::common;

use common::{render, scene_from_toml};
use glam::{DVec3, Vec3};
use parallax::accel::Backend;
use parallax::geometry::SurfaceInteraction;
use parallax::material::{textured_albedo, textured_bsdf};
use parallax::scene::build_scene;
use shaders_cpu::bsdf::Bsdf;

/// A road plane and a brick wall under a sun, the rig 1.5 m up pitched 12°
/// down; `texture` is `true` to give the road asphalt and the wall brick.
fn road_scene(width: u32, height: u32, spp: u32, seed: u32, texture: bool) -> String {
    let (road_tex, wall_tex) = if texture {
        (
            "texture = { kind = \"asphalt\", seed = 4 }\n",
            "texture = { kind = \"brick\", scale = 1.5 }\n",
        )
    } else {
        ("", "")
    };
    format!(
        "[camera]\nwidth = {width}\nheight = {height}\nhfov_deg = 50.0\n\
position = [1000.25, -3000.5, 1.5]\npitch_deg = 12.0\n\
[render]\nspp = {spp}\nmax_depth = 3\nseed = {seed}\n\
[sky]\nkind = \"constant\"\nle = [0.3, 0.35, 0.45]\n\
[[light]]\nkind = \"sun\"\nelevation_deg = 50.0\nazimuth_deg = 200.0\nirradiance = [9.0, 9.0, 9.0]\n\
[[material]]\nname = \"asphalt\"\nkind = \"diffuse\"\nalbedo = [0.085, 0.085, 0.09]\n{road_tex}\
[[material]]\nname = \"brick\"\nkind = \"diffuse\"\nalbedo = [0.42, 0.17, 0.11]\n{wall_tex}\
[[object]]\nkind = \"quad\"\nsize = [400.0, 400.0]\nmaterial = \"asphalt\"\n\
transform = {{ translate = [1000.0, -3000.0, 0.0] }}\n\
[[object]]\nkind = \"box\"\nsize = [30.0, 0.5, 6.0]\nmaterial = \"brick\"\n\
transform = {{ translate = [1015.0, -2996.0, 3.0] }}\n"
    )
}

#[test]
fn texture_depends_on_world_position_not_render_origin() {
    let loaded = scene_from_toml(&road_scene(16, 9, 1, 1, true));
    // Integer-metre origins and points on a 1/1024 m grid within 64 m: every
    // p_render is exact in f32, so both scenes see bit-identical world points.
    let a = build_scene(&loaded, DVec3::new(1000.0, -3000.0, 1.0)).unwrap();
    let b = build_scene(&loaded, DVec3::new(1037.0, -2981.0, -2.0)).unwrap();
    let mut distinct = std::collections::HashSet::new();
    for (m_a, m_b) in a.materials.iter().zip(&b.materials) {
        assert!(m_a.texture.is_some());
        for i in 0..2000u32 {
            let p_world = DVec3::new(
                1000.0 + (i * 37 % 20_000) as f64 / 1024.0,
                -3000.0 + (i * 101 % 20_000) as f64 / 1024.0,
                (i % 5) as f64 / 1024.0,
            );
            let n = if i % 2 == 0 { Vec3::Z } else { Vec3::Y };
            // Albedo and relief (the bumped normal) alike.
            let albedo = |s: &parallax::scene::Scene, m: &parallax::scene::Material| {
                let si = SurfaceInteraction {
                    p: (p_world - s.origin_world).as_vec3(),
                    p_error: Vec3::ZERO,
                    n_geo: n,
                    n_shading: n,
                    uv: glam::Vec2::ZERO,
                    material: 0,
                    semantic: 0,
                    instance: 0,
                };
                match textured_bsdf(m, s.origin_world, &si, true) {
                    b @ Bsdf::NormalMapped { wp, .. } => (b.diffuse_albedo().unwrap(), wp),
                    other => panic!("textured diffuse became {other:?}"),
                }
            };
            let (va, vb) = (albedo(&a, m_a), albedo(&b, m_b));
            assert_eq!(va, vb, "{} at {p_world}", m_a.name);
            assert_eq!(va.0, textured_albedo(m_a, p_world, n));
            distinct.insert(va.0.x.to_bits());
        }
    }
    assert!(
        distinct.len() > 1000,
        "texture varies: {} values",
        distinct.len()
    );
}

#[test]
fn ground_truth_is_bitwise_identical_with_and_without_textures() {
    let plain = render(
        &scene_from_toml(&road_scene(64, 36, 2, 1, false)),
        Backend::default_backend(),
        2,
    );
    let tex = render(
        &scene_from_toml(&road_scene(64, 36, 2, 1, true)),
        Backend::default_backend(),
        2,
    );
    let (l0, l1) = (&plain.out.left, &tex.out.left);
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&l0.depth_z), bits(&l1.depth_z));
    assert_eq!(l0.normal_world, l1.normal_world);
    assert_eq!(
        (&l0.semantic, &l0.instance, &l0.mask),
        (&l1.semantic, &l1.instance, &l1.mask)
    );
    for (b0, b1) in plain.out.baselines.iter().zip(&tex.out.baselines) {
        let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&b0.disparity_left), bits(&b1.disparity_left));
        assert_eq!(bits(&b0.disparity_right), bits(&b1.disparity_right));
        assert_eq!(bits(&b0.depth_right), bits(&b1.depth_right));
        assert_eq!(b0.occlusion, b1.occlusion);
    }
    // The radiance did change: the texture reached the path tracer.
    assert_ne!(plain.out.images[0].rgb, tex.out.images[0].rgb);
}

/// Horizontal luminance gradients of the left image over the road (rows
/// below the horizon), as (mean |g|, mean luminance).
fn road_gradients(text: &str) -> (Vec<f64>, f64) {
    let r = render(&scene_from_toml(text), Backend::default_backend(), 8);
    let film = &r.out.images[0];
    let lum = |k: usize| film.rgb[k].dot(Vec3::new(0.2126, 0.7152, 0.0722)) as f64;
    let (mut g, mut level, mut n) = (Vec::new(), 0.0, 0.0);
    for j in film.height * 3 / 5..film.height {
        for i in 0..film.width / 2 {
            let k = film.index(i, j);
            g.push(lum(k + 1) - lum(k));
            level += lum(k);
            n += 1.0;
        }
    }
    (g, level / n)
}

#[test]
fn textured_road_has_consistent_high_frequency_energy() {
    // Two renders with different sampler seeds: Monte Carlo noise is
    // independent between them, texture is shared, so the mean product of
    // their gradients measures texture alone; mean |g| is what a matcher sees.
    let stats = |texture: bool| {
        let (g1, level) = road_gradients(&road_scene(160, 90, 8, 1, texture));
        let (g2, _) = road_gradients(&road_scene(160, 90, 8, 2, texture));
        let n = g1.len() as f64;
        let abs = g1.iter().map(|g| g.abs()).sum::<f64>() / n / level;
        let shared = g1.iter().zip(&g2).map(|(a, b)| a * b).sum::<f64>() / n / (level * level);
        (abs, shared)
    };
    let (abs_plain, shared_plain) = stats(false);
    let (abs_tex, shared_tex) = stats(true);
    println!("mean |grad|/level: plain {abs_plain:.4}, textured {abs_tex:.4}");
    println!("shared gradient energy: plain {shared_plain:.2e}, textured {shared_tex:.2e}");
    assert!(
        abs_tex > 1.5 * abs_plain,
        "mean |grad| {abs_tex} vs {abs_plain}"
    );
    assert!(shared_tex > 1e-3, "textured shared energy {shared_tex}");
    assert!(
        shared_tex > 20.0 * shared_plain.abs(),
        "{shared_tex} vs {shared_plain}"
    );
}
