//! Rain streak appearance: the rain mask covers the fraction of pixels that
//! drop density × projected streak area predicts (Poisson, per pixel-centre
//! ray), its connected components stand vertical for a level camera; the
//! splatted opacity equals the per-pixel grid walk (`Rain::opacity`) and
//! does not depend on the thread count; every pixel is the opacity blend of
//! its path-traced radiance and one drop radiance per frame, and the streak
//! gain brightens near streaks only.

use crate::common;

use common::{camera_block, render, scene_from_toml, Rendered};
use parallax::accel::Backend;
use parallax::integrator::rain::{rain_opacity, MASK_MIN_OPACITY};
use parallax::integrator::{frame_rain, RenderCamera};
use parallax::scene::mask_bits;
use shaders_cpu::medium::{
    marshall_palmer_count, marshall_palmer_lambda, Rain, MAX_DROP_DIAMETER_MM,
};

const SEED: u64 = 5;
/// Radius of the rain volume, metres.
const EXTENT_M: f64 = 40.0;

/// A rig 1.65 m over a ground quad of albedo `ground`, pitched up by
/// `up_deg`, under a constant white sky, with `[rain]` at `rate` mm/h,
/// 1/60 s, streak opacity × `gain`; `spp` 0: ground truth only.
fn rainy(size: (u32, u32), rate: f64, gain: f64, ground: f64, up_deg: f64, spp: u32) -> Rendered {
    let text = format!(
        "{}pitch_deg = {:?}\n[render]\nspp = {}\nmax_depth = 3\nseed = {SEED}\n\
         [sky]\nkind = \"constant\"\nle = [1.0, 1.0, 1.0]\n\
         [[material]]\nname = \"g\"\nkind = \"diffuse\"\nalbedo = [{ground:?}, {ground:?}, {ground:?}]\n\
         [[object]]\nkind = \"quad\"\nsize = [20000.0, 20000.0]\nmaterial = \"g\"\n\
         [rain]\nrate_mm_per_h = {rate:?}\nshutter_s = {:?}\nextent_m = {EXTENT_M:?}\nstreak_gain = {gain:?}\n",
        camera_block(size.0, size.1, [0.0, 0.0, 1.65]),
        -up_deg,
        spp.max(1),
        1.0 / 60.0
    );
    let mut loaded = scene_from_toml(&text);
    loaded.desc.camera.baselines_cm = vec![54.0];
    render(&loaded, Backend::default_backend(), spp)
}

fn is_rain(m: u8) -> bool {
    m & mask_bits::RAIN != 0
}

#[test]
fn mean_opacity_is_the_drops_cross_section_along_the_ray() {
    // A streak's coverage w times its projected area is the drop's disc
    // πr², whatever the pixel size, so Σw along a ray has the mean
    // n·E[πr²]·length; the opacity 1 − Π(1 − w) lies between
    // Σw·(1 − small) and −ln(1 − α) = Σ −ln(1 − w) ≥ Σw.
    let (w, h) = (200u32, 112u32);
    let (rate, d0) = (50.0, 2.5);
    let r = rainy((w, h), rate, 1.0, 0.5, 0.0, 0);
    let rain = frame_rain(&r.scene, SEED, 0, r.rig.left.intrinsics.f_px).expect("rain");
    let cam = RenderCamera::new(&r.rig.left, r.scene.origin_world);
    let alpha = rain_opacity(&r.scene, &rain, &cam, &r.out.left.depth_z);
    let n = marshall_palmer_count(rate, d0);
    let lambda = marshall_palmer_lambda(rate);
    // E[πr²] over diameters on [d0, 6 mm] ∝ e^{−ΛD} (midpoint rule).
    let bins = 256;
    let step = (MAX_DROP_DIAMETER_MM - d0) / bins as f64;
    let (mut area, mut norm) = (0.0, 0.0);
    for k in 0..bins {
        let d_mm = d0 + (k as f64 + 0.5) * step;
        let wgt = (-lambda * d_mm).exp();
        area += wgt * std::f64::consts::PI * (0.5e-3 * d_mm).powi(2);
        norm += wgt;
    }
    let cross_section = n * area / norm;
    let (mut expected, mut mean_alpha, mut mean_depth) = (0.0, 0.0, 0.0);
    for (k, &a) in alpha.iter().enumerate() {
        let d = cam.dir((k % w as usize) as f64 + 0.5, (k / w as usize) as f64 + 0.5);
        let t_ground = r.out.left.depth_z[k] * d.length();
        expected += cross_section * t_ground.min(EXTENT_M);
        mean_alpha += a as f64;
        mean_depth += -(1.0 - a as f64).ln();
    }
    let px = alpha.len() as f64;
    let (expected, mean_alpha, mean_depth) = (expected / px, mean_alpha / px, mean_depth / px);
    eprintln!("mean opacity {mean_alpha:.5}, −ln(1−α) {mean_depth:.5}, expected Σw {expected:.5}");
    assert!(expected > 0.005, "set-up: {expected}");
    assert!(
        mean_alpha > 0.95 * expected && mean_depth < 1.05 * expected,
        "α {mean_alpha}, −ln(1−α) {mean_depth} vs Σw {expected}"
    );
    let masked = r.out.left.mask.iter().filter(|&&m| is_rain(m)).count();
    let over = alpha.iter().filter(|&&a| a >= MASK_MIN_OPACITY).count();
    assert_eq!(masked, over, "mask bit ⇔ opacity ≥ 1 %");
}

/// 4-connected components of the rain mask: (rows spanned, columns spanned).
fn components(mask: &[u8], w: usize, h: usize) -> Vec<(usize, usize)> {
    let mut seen = vec![false; mask.len()];
    let mut out = Vec::new();
    for start in 0..mask.len() {
        if seen[start] || !is_rain(mask[start]) {
            continue;
        }
        let (mut stack, mut rows, mut cols) = (vec![start], (h, 0), (w, 0));
        seen[start] = true;
        while let Some(k) = stack.pop() {
            let (i, j) = (k % w, k / w);
            rows = (rows.0.min(j), rows.1.max(j));
            cols = (cols.0.min(i), cols.1.max(i));
            let nb = [
                (i > 0).then(|| k - 1),
                (i + 1 < w).then(|| k + 1),
                (j > 0).then(|| k - w),
                (j + 1 < h).then(|| k + w),
            ];
            for q in nb.into_iter().flatten() {
                if !seen[q] && is_rain(mask[q]) {
                    seen[q] = true;
                    stack.push(q);
                }
            }
        }
        out.push((rows.1 - rows.0 + 1, cols.1 - cols.0 + 1));
    }
    out
}

#[test]
fn rain_mask_streaks_stand_vertical_for_a_level_camera() {
    let (w, h) = (320u32, 180u32);
    let r = rainy((w, h), 50.0, 1.0, 0.5, 0.0, 0);
    let comps: Vec<_> = components(&r.out.left.mask, w as usize, h as usize)
        .into_iter()
        .filter(|&(rows, cols)| rows * cols >= 3)
        .collect();
    let tall = comps
        .iter()
        .filter(|&&(rows, cols)| rows >= 2 * cols)
        .count();
    let (rows, cols) = comps.iter().fold((0, 0), |(a, b), &(r, c)| (a + r, b + c));
    eprintln!(
        "{} components, {tall} at least twice as tall as wide, rows {rows} cols {cols}",
        comps.len()
    );
    assert!(comps.len() > 30, "only {} streaks", comps.len());
    assert!(tall * 10 >= comps.len() * 8, "{tall} of {}", comps.len());
    assert!(2 * rows >= 5 * cols, "rows {rows} vs cols {cols}");
}

/// Opacity of every left pixel by the per-pixel grid walk.
fn walked_opacity(r: &Rendered, rain: &Rain) -> Vec<f64> {
    let cam = RenderCamera::new(&r.rig.left, r.scene.origin_world);
    let o = r.scene.origin_world + cam.center;
    let w = cam.intrinsics.width as usize;
    (0..r.out.left.depth_z.len())
        .map(|k| {
            let dir = cam.dir((k % w) as f64 + 0.5, (k / w) as f64 + 0.5);
            let len = dir.length();
            rain.opacity(o, dir / len, r.out.left.depth_z[k] * len)
        })
        .collect()
}

#[test]
fn splatted_opacity_equals_the_grid_walk_on_any_thread_count() {
    let (w, h) = (128u32, 72u32);
    let r = rainy((w, h), 80.0, 4.0, 0.5, 10.0, 0);
    let rain = frame_rain(&r.scene, SEED, 0, r.rig.left.intrinsics.f_px).expect("rain");
    let cam = RenderCamera::new(&r.rig.left, r.scene.origin_world);
    let on = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("pool")
            .install(|| rain_opacity(&r.scene, &rain, &cam, &r.out.left.depth_z))
    };
    let (one, two) = (on(1), on(2));
    assert_eq!(
        one.iter().map(|a| a.to_bits()).collect::<Vec<_>>(),
        two.iter().map(|a| a.to_bits()).collect::<Vec<_>>()
    );
    let walked = walked_opacity(&r, &rain);
    let rainy_px = walked.iter().filter(|&&a| a > 0.0).count();
    let worst = one
        .iter()
        .zip(&walked)
        .map(|(&a, &b)| (a as f64 - b).abs())
        .fold(0.0, f64::max);
    eprintln!("{rainy_px} pixels with rain, worst |splat − walk| {worst:e}");
    assert!(rainy_px > 500, "only {rainy_px} pixels with rain");
    assert!(worst < 1e-6, "splat and walk differ by {worst}");
}

#[test]
fn pixels_blend_the_sky_with_one_drop_radiance() {
    // Looking 30° up, every camera ray escapes to the constant sky of
    // radiance 1: the left view's mean before rain is 1, the drops show
    // 0.94 of it, so a pixel of opacity α must read 1 − 0.06·α.
    let r = rainy((128, 72), 50.0, 4.0, 1.0, 30.0, 2);
    let rain = frame_rain(&r.scene, SEED, 0, r.rig.left.intrinsics.f_px).expect("rain");
    let alpha = walked_opacity(&r, &rain);
    let img = &r.out.images[0].rgb;
    let rain_px = alpha.iter().filter(|&&a| a > 0.01).count();
    let worst = img
        .iter()
        .zip(&alpha)
        .map(|(p, &a)| (p.y as f64 - (1.0 - 0.06 * a)).abs())
        .fold(0.0, f64::max);
    eprintln!("{rain_px} pixels above 1 % opacity, worst {worst:e}");
    assert!(rain_px > 20, "only {rain_px} rain pixels");
    assert!(worst < 1e-5, "worst pixel off by {worst}");
}

#[test]
fn streaks_over_a_black_ground_add_opacity_times_one_drop_radiance() {
    // A black ground pixel holds only the drops in front of it: α·L_drop,
    // one L_drop for the frame (0.94 × the mean radiance before rain ≤ 0.94).
    let (w, h) = (160u32, 90u32);
    let r = rainy((w, h), 80.0, 1.0, 0.0, 0.0, 1);
    let rain = frame_rain(&r.scene, SEED, 0, r.rig.left.intrinsics.f_px).expect("rain");
    let alpha = walked_opacity(&r, &rain);
    let img = &r.out.images[0].rgb;
    // Rows well below the horizon see only ground.
    let ground = (h as usize * 2 / 3 * w as usize)..(w * h) as usize;
    let ratios: Vec<f64> = ground
        .clone()
        .filter(|&k| alpha[k] > 1e-3)
        .map(|k| img[k].y as f64 / alpha[k])
        .collect();
    let clear = ground
        .filter(|&k| alpha[k] == 0.0)
        .map(|k| img[k].y)
        .fold(0.0f32, f32::max);
    let (lo, hi) = ratios
        .iter()
        .fold((f64::MAX, 0.0f64), |(a, b), &x| (a.min(x), b.max(x)));
    eprintln!(
        "{} ground pixels with rain: L_drop in [{lo}, {hi}]",
        ratios.len()
    );
    assert!(
        ratios.len() > 50,
        "only {} rainy ground pixels",
        ratios.len()
    );
    assert_eq!(clear, 0.0, "a ground pixel without rain is not black");
    assert!(hi - lo < 1e-4 * hi, "L_drop varies: [{lo}, {hi}]");
    assert!(hi > 0.2 && hi <= 0.94, "L_drop {hi}");
}

#[test]
fn streak_gain_brightens_near_streaks_and_leaves_dots_physical() {
    let (w, h) = (160u32, 90u32);
    let plain = rainy((w, h), 80.0, 1.0, 0.5, 0.0, 0);
    let gained = rainy((w, h), 80.0, 6.0, 0.5, 0.0, 0);
    let f_px = plain.rig.left.intrinsics.f_px;
    let a = frame_rain(&plain.scene, SEED, 0, f_px).expect("rain");
    let b = frame_rain(&gained.scene, SEED, 0, f_px).expect("rain");
    let cam = RenderCamera::new(&plain.rig.left, plain.scene.origin_world);
    let o = plain.scene.origin_world + cam.center;
    let (mut near, mut far) = (0, 0);
    for k in 0..(w * h) as usize {
        let dir = cam.dir((k % w as usize) as f64 + 0.5, (k / w as usize) as f64 + 0.5);
        let d = dir / dir.length();
        let Some(hit) = a.first_streak(o, d, 0.0, f64::INFINITY, a.min_opacity_coverage()) else {
            continue;
        };
        let (pa, pb) = (a.streak_opacity(&hit), b.streak_opacity(&hit));
        // A streak of L metres at distance t spans L·f/t pixels.
        let len_px = a.fall_speed(2e3 * hit.drop_radius_m) * a.shutter_s * f_px / hit.t_axis;
        if len_px >= 24.0 {
            assert!(
                (pb - (6.0 * pa).min(1.0)).abs() < 1e-12,
                "near: {pa} → {pb}"
            );
            near += 1;
        } else if len_px < 1.0 {
            assert!(pb < pa * (1.0 + 5.0 / 24.0) + 1e-12, "far: {pa} → {pb}");
            far += 1;
        }
    }
    eprintln!("{near} near and {far} far streaks checked");
    assert!(near > 5 && far > 50, "near {near}, far {far}");
}
