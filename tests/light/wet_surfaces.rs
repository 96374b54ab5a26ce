//! Wet roads and puddles (`[wetness]`): a wet road under a gradient sky returns
//! F(water)·L_sky(mirror) plus a Lekner–Dorf-darkened diffuse rest, a puddle
//! is an exact water mirror, the ground truth's geometry is bit-identical with
//! and without wetness, and the mirror bit marks puddles only, at the same
//! world points in both views.

use crate::common;

use common::{camera_block, render, scene_from_toml, Rendered};
use parallax::accel::Backend;
use parallax::integrator::gt::view_gt;
use parallax::integrator::RenderCamera;
use parallax::material::wet::{internal_reflectance, WATER_IOR};
use parallax::scene::mask_bits;
use parallax::weather::{apply, draw_params, Weather};
use shaders_cpu::bsdf::fresnel::fr_dielectric;

const ZENITH: f64 = 0.3;
const HORIZON: f64 = 2.0;
const ALBEDO: f64 = 0.3;
const W: u32 = 64;
const H: u32 = 48;

/// Gradient sky radiance at elevation asin(mu) (`Sky::Gradient`).
fn sky(mu: f64) -> f64 {
    let t = mu.clamp(0.0, 1.0).asin() * 2.0 / std::f64::consts::PI;
    HORIZON + (ZENITH - HORIZON) * t
}

/// 2 ∫₀¹ g(μ) L(μ) μ dμ: a Lambert reflector's integral over the sky.
fn sky_integral(g: impl Fn(f64) -> f64) -> f64 {
    let n = 20_000;
    (0..n)
        .map(|i| {
            let mu = (i as f64 + 0.5) / n as f64;
            2.0 * g(mu) * sky(mu) * mu / n as f64
        })
        .sum()
}

/// A road plane (plus a building box) under the gradient sky, level rig.
fn road_scene(wetness: Option<(f64, f64)>, spp: u32) -> Rendered {
    road_scene_pitched(wetness, spp, 0.0)
}

/// [`road_scene`] with the rig pitched down by `pitch_deg`.
fn road_scene_pitched(wetness: Option<(f64, f64)>, spp: u32, pitch_deg: f64) -> Rendered {
    let wet = wetness.map_or(String::new(), |(w, cover)| {
        format!("[wetness]\nwetness = {w}\npuddle_cover = {cover}\nseed = 9\n")
    });
    let text = format!(
        r#"{}[render]
spp = {}
max_depth = 1
seed = 5
filter_indirect = false
[sky]
kind = "gradient"
zenith = [{ZENITH}, {ZENITH}, {ZENITH}]
horizon = [{HORIZON}, {HORIZON}, {HORIZON}]
ground = [0.0, 0.0, 0.0]
{wet}
[[material]]
name = "asphalt"
kind = "diffuse"
albedo = [{ALBEDO}, {ALBEDO}, {ALBEDO}]
[[object]]
kind = "quad"
size = [400.0, 400.0]
material = "asphalt"
semantic = "road"
instance = 1
[[object]]
kind = "box"
size = [2.0, 2.0, 2.0]
material = "asphalt"
semantic = "building"
instance = 2
transform = {{ translate = [30.0, 14.0, 1.0] }}
"#,
        camera_block(W, H, [0.0, 0.0, 1.65]),
        spp.max(1)
    );
    let mut loaded = scene_from_toml(&text);
    loaded.desc.camera.baselines_cm = vec![54.0];
    loaded.desc.camera.pitch_deg = pitch_deg;
    render(&loaded, Backend::default_backend(), spp)
}

/// (cos θo, mean radiance) of the road rows below the horizon, over the 8
/// central columns (clear of the box), for rows at least 3° below it.
fn road_rows(r: &Rendered) -> Vec<(f64, f64)> {
    let f = r.rig.left.intrinsics.f_px;
    let img = &r.out.images[0].rgb;
    let (cx, cy) = (W as usize / 2, H as f64 / 2.0);
    (0..H as usize)
        .filter_map(|j| {
            let dv = (j as f64 + 0.5 - cy) / f;
            if dv < 3f64.to_radians().tan() {
                return None;
            }
            let cos_o = dv / (1.0 + dv * dv).sqrt();
            let cols = cx - 4..cx + 4;
            let mean = cols.map(|i| img[j * W as usize + i].y as f64).sum::<f64>() / 8.0;
            Some((cos_o, mean))
        })
        .collect()
}

fn f_water(mu: f64) -> f64 {
    fr_dielectric(mu as f32, WATER_IOR) as f64
}

/// Lekner–Dorf soaked albedo of `a`.
fn soaked(a: f64) -> f64 {
    let ri = internal_reflectance(WATER_IOR) as f64;
    a * (1.0 - ri) / (1.0 - a * ri)
}

#[test]
fn wet_road_is_darker_and_reflects_the_sky_with_water_fresnel() {
    let dry = road_rows(&road_scene(None, 64));
    let wet = road_rows(&road_scene(Some((1.0, 0.0)), 64));
    assert!(dry.len() >= 8, "{dry:?}");
    let lambert = sky_integral(|_| 1.0);
    let rest_integral = sky_integral(|mu| 1.0 - f_water(mu));
    for (&(cos_o, l_dry), &(_, l_wet)) in dry.iter().zip(&wet) {
        // Dry: albedo · ∫L cos/π.
        let e_dry = ALBEDO * lambert;
        assert!(
            (l_dry - e_dry).abs() < 0.02 * e_dry,
            "dry {l_dry} vs {e_dry}"
        );
        // Wet: the film's Fresnel reflection of the sky in the mirror
        // direction, plus the soaked base seen through the film twice.
        let spec = f_water(cos_o) * sky(cos_o);
        let rest = (1.0 - f_water(cos_o)) * soaked(ALBEDO) * rest_integral;
        let e_wet = spec + rest;
        eprintln!("cosθo {cos_o:.3}: dry {l_dry:.4} wet {l_wet:.4} = {spec:.4} + {rest:.4}");
        // Within a few %; the first row, 3.6° from grazing, loses a little
        // more to the film's residual roughness (Smith masking).
        let tol = if cos_o >= 0.07 { 0.04 } else { 0.08 };
        assert!(
            (l_wet - e_wet).abs() < tol * e_wet,
            "wet {l_wet} vs {e_wet}"
        );
        // The diffuse part alone is much darker than the dry road.
        assert!(rest < 0.6 * l_dry);
    }
    // Near grazing the reflected horizon makes the wet road brighter.
    assert!(wet[0].1 > 2.0 * dry[0].1, "{:?} vs {:?}", wet[0], dry[0]);
    // Looking down at 60° it is much darker: soaked albedo, little Fresnel.
    let mean = |r: &Rendered| {
        let img = &r.out.images[0].rgb;
        img.iter().map(|c| c.y as f64).sum::<f64>() / img.len() as f64
    };
    let (dry, wet) = (
        mean(&road_scene_pitched(None, 16, 60.0)),
        mean(&road_scene_pitched(Some((1.0, 0.0)), 16, 60.0)),
    );
    assert!(wet < 0.7 * dry && wet > 0.4 * dry, "wet {wet} dry {dry}");
}

#[test]
fn puddle_is_a_smooth_water_mirror_over_the_soaked_base() {
    let r = road_scene(Some((0.6, 1.0)), 256);
    let rest_integral = sky_integral(|mu| 1.0 - f_water(mu));
    for (cos_o, l) in road_rows(&r) {
        let e =
            f_water(cos_o) * sky(cos_o) + (1.0 - f_water(cos_o)) * soaked(ALBEDO) * rest_integral;
        assert!((l - e).abs() < 0.03 * e, "cosθo {cos_o}: {l} vs {e}");
    }
}

#[test]
fn ground_truth_geometry_is_bit_identical_with_and_without_wetness() {
    let (dry, wet) = (road_scene(None, 0), road_scene(Some((0.9, 0.4)), 0));
    let bits = |v: &[f64]| v.iter().map(|z| z.to_bits()).collect::<Vec<u64>>();
    let (a, b) = (&dry.out.left, &wet.out.left);
    assert_eq!(bits(&a.depth_z), bits(&b.depth_z));
    assert_eq!(a.normal_world, b.normal_world);
    assert_eq!(a.semantic, b.semantic);
    assert_eq!(a.instance, b.instance);
    assert_eq!(dry.out.baselines, wet.out.baselines);
    let without_mirror = |m: &[u8]| m.iter().map(|x| x & !mask_bits::MIRROR).collect::<Vec<_>>();
    assert_eq!(without_mirror(&a.mask), without_mirror(&b.mask));
    assert!(a.mask.iter().all(|m| m & mask_bits::MIRROR == 0));
}

/// Whether the GT pixel (i, j) of `cam` lies on a puddle by the world-space
/// mask (None when within 1e-3 of the threshold, where f32 rounding of the
/// hit point may decide either way).
fn puddle_by_world_mask(
    r: &Rendered,
    cam: &RenderCamera,
    depth: f64,
    i: u32,
    j: u32,
) -> Option<bool> {
    let w = r.scene.wetness.as_ref().unwrap();
    let p = r.scene.origin_world + cam.center + cam.dir(i as f64 + 0.5, j as f64 + 0.5) * depth;
    let n = w.puddle_noise(p.x, p.y);
    ((n - w.threshold).abs() > 1e-3).then_some(n >= w.threshold)
}

#[test]
fn mirror_bit_marks_puddles_only_and_agrees_between_views() {
    let r = road_scene(Some((0.9, 0.4)), 0);
    let left = RenderCamera::new(&r.rig.left, r.scene.origin_world);
    let right = RenderCamera::new(&r.rig.right(0), r.scene.origin_world);
    let gt_r = view_gt(&r.scene, &r.accel, &right, true);
    let gt_l = &r.out.left;
    let f = r.rig.left.intrinsics.f_px;
    let (mut puddles, mut dry_road, mut agree) = (0, 0, 0);
    for j in 0..H {
        for i in 0..W {
            let k = (j * W + i) as usize;
            let mirror = gt_l.mask[k] & mask_bits::MIRROR != 0;
            if gt_l.semantic[k] != 1 {
                assert!(!mirror, "non-road pixel ({i}, {j}) has the mirror bit");
                continue;
            }
            let z = gt_l.depth_z[k];
            let Some(expect) = puddle_by_world_mask(&r, &left, z, i, j) else {
                continue;
            };
            assert_eq!(mirror, expect, "pixel ({i}, {j})");
            if expect {
                puddles += 1;
            } else {
                dry_road += 1;
            }
            // The same world point in the right view carries the same bit.
            let x_r = i as f64 + 0.5 - f * 0.54 / z;
            if x_r < 0.5 || r.out.baselines[0].occlusion[k] != 0 {
                continue;
            }
            // The right pixel containing the point (its own centre sees a
            // point within a pixel's footprint of it).
            let ir = (x_r.floor() as u32).min(W - 1);
            let kr = (j * W + ir) as usize;
            if gt_r.semantic[kr] != 1 {
                continue;
            }
            let Some(expect_r) = puddle_by_world_mask(&r, &right, gt_r.depth_z[kr], ir, j) else {
                continue;
            };
            assert_eq!(gt_r.mask[kr] & mask_bits::MIRROR != 0, expect_r);
            agree += usize::from(expect_r == expect);
        }
    }
    assert!(
        puddles > 20 && dry_road > 20,
        "{puddles} puddle, {dry_road} dry"
    );
    assert!(agree > 20, "{agree}");
}

#[test]
fn weather_presets_wet_only_humid_and_storm() {
    for w in Weather::ALL {
        let p = draw_params(w, 4);
        let mut desc = scene_from_toml(&format!(
            "{}[[light]]\nkind = \"point\"\nposition = [0.0, 0.0, 5.0]\nintensity = [1.0, 1.0, 1.0]\n",
            camera_block(8, 8, [0.0, 0.0, 1.0])
        ))
        .desc;
        apply(&mut desc, &p);
        match (w, &desc.wetness) {
            (Weather::Humid | Weather::Storm, Some(wet)) => {
                assert_eq!(wet.wetness, p.wetness);
                assert!((0.0..=0.25).contains(&wet.puddle_cover), "{wet:?}");
                if w == Weather::Storm {
                    assert!(wet.puddle_cover >= 0.15, "{wet:?}");
                }
                // Written back and read again it is the same section.
                let back: parallax::scene::SceneDesc = toml::from_str(&desc.to_toml()).unwrap();
                assert_eq!(back.wetness.as_ref(), Some(wet));
            }
            (Weather::Humid | Weather::Storm, None) => panic!("{w}: dry"),
            (_, wet) => assert!(wet.is_none(), "{w}: {wet:?}"),
        }
    }
}

#[test]
fn coated_material_builds_a_coat_and_rejects_two_bases() {
    let scene = |body: &str| {
        let text = format!(
            "{}[sky]\nkind = \"constant\"\nle = [1.0, 1.0, 1.0]\n[[material]]\nname = \"paint\"\nkind = \"coated\"\n{body}\n[[object]]\nkind = \"quad\"\nsize = [2.0, 2.0]\nmaterial = \"paint\"\n",
            camera_block(8, 8, [-3.0, 0.0, 1.0])
        );
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/inline.toml");
        parallax::scene::parse_scene_str(&text, &path)
    };
    let loaded = scene("albedo = [0.5, 0.02, 0.02]\ncoat_roughness = 0.1").expect("diffuse base");
    let built = parallax::scene::build_scene(&loaded, glam::DVec3::ZERO).unwrap();
    let m = &built.materials[0];
    assert_eq!(m.mask, 0, "clear coat is not a mirror in the mask");
    match m.bsdf {
        shaders_cpu::bsdf::Bsdf::Coated { base, eta, alpha } => {
            assert_eq!(eta, 1.5);
            assert!((alpha - 0.01).abs() < 1e-7);
            assert!(matches!(base, shaders_cpu::bsdf::CoatBase::Lambert { .. }));
        }
        other => panic!("{other:?}"),
    }
    let metal = scene("preset = \"aluminium\"\nbase_roughness = 0.4").expect("metal base");
    let built = parallax::scene::build_scene(&metal, glam::DVec3::ZERO).unwrap();
    assert!(matches!(
        built.materials[0].bsdf,
        shaders_cpu::bsdf::Bsdf::Coated {
            base: shaders_cpu::bsdf::CoatBase::Conductor { .. },
            ..
        }
    ));
    for bad in [
        "albedo = [0.5, 0.5, 0.5]\npreset = \"gold\"",
        "",
        "albedo = [0.5, 0.5, 0.5]\ncoat_ior = 1.0",
        "albedo = [1.5, 0.5, 0.5]",
    ] {
        let err = scene(bad).expect_err(bad).to_string();
        assert!(err.contains("material[0]"), "{bad}: {err}");
    }
}
