//! The indirect-light filter (`[render] filter_indirect`, on by default in
//! scenes without a medium): the light a Lambertian first surface reflects
//! beyond its own next-event estimates is filtered in image space as a
//! ratio to the surface's albedo. Sunlit open ground under a gradient sky
//! has the closed form ρ·(E·sin(elevation)/π + ∫L·cos/π) (the sky's
//! integral by quadrature of its own radiance function): the filtered image
//! converges to it with several times less per-pixel error, keeps a
//! checker's albedo steps exact, keeps the image mean beside a sunlit wall,
//! is the plain per-sample estimate bit for bit when off and its filtered
//! form when on, and never touches the ground truth.

use crate::common;

use common::{
    aux, checker_ground, ground_tile_pixels, mean_stderr, rebuild_left, render_inline, Rendered,
};
use glam::Vec3;
use parallax::accel::Backend;
use parallax::denoise::{denoise_guided, denoise_view, DepthGuide, ViewInputs, Widths};
use parallax::film::Film;
use parallax::integrator::RenderCamera;
use parallax::scene::Scene;

const W: u32 = 48;
const H: u32 = 32;
/// Sun irradiance (W·m⁻², every channel) and elevation. With a sun in the
/// scene the sky is reached by BSDF sampling only, so all its light on the
/// ground is the filtered part; its gradient (bright horizon, dim zenith)
/// makes that part noisy.
const E_SUN: f64 = 3.0;
const ELEVATION_DEG: f64 = 30.0;
const SKY: &str = "[sky]\nkind = \"gradient\"\nzenith = [0.2, 0.2, 0.2]\n\
    horizon = [2.0, 2.0, 2.0]\nground = [0.0, 0.0, 0.0]\n";

/// The open ground's radiance per unit albedo (green): the sun's
/// E·sin(e)/π plus the sky's cosine-weighted mean, 2∫L(e)·sin e·cos e de
/// over elevation e (the sky depends on elevation only), midpoint rule.
fn radiance_per_albedo(scene: &Scene) -> f64 {
    let n = 20_000;
    let de = std::f64::consts::FRAC_PI_2 / n as f64;
    let sky: f64 = (0..n)
        .map(|k| {
            let e = (k as f64 + 0.5) * de;
            let l = scene
                .sky
                .le(Vec3::new(e.cos() as f32, 0.0, e.sin() as f32))
                .y as f64;
            2.0 * l * e.sin() * e.cos() * de
        })
        .sum();
    E_SUN * ELEVATION_DEG.to_radians().sin() / std::f64::consts::PI + sky
}

/// The checker ground of albedos `albedo` (`common::checker_ground`) under
/// the sun and sky, plus `extra` objects.
fn ground_body(albedo: [f64; 2], extra: &str) -> String {
    format!(
        "{SKY}[[light]]\nkind = \"sun\"\nelevation_deg = {ELEVATION_DEG:?}\nazimuth_deg = 150.0\n\
         irradiance = [{E_SUN:?}, {E_SUN:?}, {E_SUN:?}]\n{}{extra}",
        checker_ground(albedo)
    )
}

/// A sunlit wall beside the ground (x from 6 m to 30 m at y = 5 m, 4 m
/// high): indirect light on the ground, and its shadow.
const WALL: &str = "[[material]]\nname = \"wall\"\nkind = \"diffuse\"\nalbedo = [0.7, 0.7, 0.7]\n\
    [[object]]\nkind = \"box\"\nsize = [24.0, 0.3, 4.0]\nmaterial = \"wall\"\n\
    transform = { translate = [18.0, 5.0, 2.0] }\n";

/// `body` rendered at `spp` with seed `seed`, the filter on or off.
fn render_body(body: &str, spp: u32, seed: u64, filter: bool, backend: Backend) -> Rendered {
    let key = if filter {
        ""
    } else {
        "filter_indirect = false\n"
    };
    render_inline(body, (W, H), (spp, seed, 5), key, backend)
}

/// Near ground pixels of the left view (depth_z < 12 m, where a pixel
/// spans under 2 m of ground) as (index, tile parity): those whose 4
/// neighbours' centres lie on the same tile, so every sample of the pixel
/// lands on that tile.
fn ground_pixels(r: &Rendered) -> Vec<(usize, i64)> {
    ground_tile_pixels(r, 12.0, |t| t)
        .into_iter()
        .map(|(k, (ix, iy))| (k, (ix + iy).rem_euclid(2)))
        .collect()
}

/// Green channel of the left image at pixel `k`.
fn green(r: &Rendered, k: usize) -> f64 {
    r.out.images[0].rgb[k].y as f64
}

#[test]
fn open_ground_converges_to_its_closed_form_with_less_error() {
    // Plain grey ground: every ground pixel's expected value is
    // 0.5 · radiance_per_albedo. Mean squared error over ground pixels and two
    // seeds at 16 spp, and the mean of each image over those pixels.
    let body = ground_body([0.5, 0.5], "");
    let want = 0.5 * radiance_per_albedo(&render_body(&body, 0, 1, true, Backend::Bvh).scene);
    let stats = |filter: bool| {
        let (mut se, mut sum, mut n) = (0.0, 0.0, 0);
        for seed in [1, 2] {
            let r = render_body(&body, 16, seed, filter, Backend::default_backend());
            for (k, _) in ground_pixels(&r) {
                let v = green(&r, k);
                se += (v - want).powi(2);
                sum += v;
                n += 1;
            }
        }
        (se / n as f64, sum / n as f64, n)
    };
    let ((mse_on, mean_on, n), (mse_off, mean_off, _)) = (stats(true), stats(false));
    eprintln!(
        "{n} ground pixels, want {want:.4}: filtered mean {mean_on:.4} MSE {mse_on:.2e}, \
         plain mean {mean_off:.4} MSE {mse_off:.2e}, ratio {:.1}",
        mse_off / mse_on
    );
    assert!(n > 300, "{n}");
    assert!((mean_on / want - 1.0).abs() < 0.01, "{mean_on} vs {want}");
    assert!((mean_off / want - 1.0).abs() < 0.01, "{mean_off} vs {want}");
    // About 12× when written.
    assert!(mse_on * 4.0 < mse_off, "{mse_on} vs {mse_off}");
}

#[test]
fn checker_albedo_steps_stay_exact_under_the_filter() {
    // The filter divides by the albedo before it averages and multiplies
    // after, so each tile keeps its own ρ · radiance_per_albedo: a filter of the
    // radiance itself would carry bright tiles' light onto dark ones.
    let albedo = [0.8, 0.1];
    let r = render_body(
        &ground_body(albedo, ""),
        32,
        3,
        true,
        Backend::default_backend(),
    );
    let ground = ground_pixels(&r);
    for parity in [0, 1] {
        let v: Vec<f64> = ground
            .iter()
            .filter(|g| g.1 == parity)
            .map(|g| green(&r, g.0))
            .collect();
        let (mean, se) = mean_stderr(&v);
        // Tile parity 0 is material m0 (the checker's (ix + iy) parity).
        let want = albedo[parity as usize] * radiance_per_albedo(&r.scene);
        eprintln!(
            "parity {parity}: {} pixels, mean {mean:.4} ± {se:.1e}, want {want:.4}",
            v.len()
        );
        assert!(v.len() > 100);
        assert!(
            (mean / want - 1.0).abs() < 0.01,
            "parity {parity}: {mean} vs {want}"
        );
    }
}

#[test]
fn filtered_mean_equals_unfiltered_mean_beside_a_sunlit_wall() {
    // Same streams on and off, so per-pixel differences are paired: the
    // filter moves indirect light and sky light between pixels (across the
    // wall's shadow edge too) but must keep their sum.
    let body = ground_body([0.5, 0.5], WALL);
    let on = render_body(&body, 16, 5, true, Backend::default_backend());
    let off = render_body(&body, 16, 5, false, Backend::default_backend());
    let n = (W * H) as usize;
    let diffs: Vec<f64> = (0..n).map(|k| green(&on, k) - green(&off, k)).collect();
    let (bias, se) = mean_stderr(&diffs);
    let (m_off, _) = mean_stderr(&(0..n).map(|k| green(&off, k)).collect::<Vec<_>>());
    eprintln!("mean plain {m_off:.4}, filtered − plain {bias:.2e} ± {se:.1e}");
    assert!(bias.abs() < 0.005 * m_off, "{bias} of {m_off}");
    assert!(bias.abs() < 4.0 * se, "{bias} ± {se}");
}

#[test]
fn ground_seen_through_glass_is_split_behind_the_glass() {
    // Tinted glass lying on the ground under a sunless sky: the ground
    // beneath gets sky light only through the glass (its shadow rays stop
    // there). Its pixels' split vertex is that ground, behind the glass, for
    // the samples the glass refracts (at least half here); the bare ground's
    // is the ground itself. Filtering keeps the glass pixels' mean (same
    // streams on and off).
    let glass = "[[material]]\nname = \"tinted\"\nkind = \"dielectric\"\nior = 1.5\n\
        roughness = 0.0\ntint = [0.5, 0.5, 0.5]\n\
        [[object]]\nkind = \"box\"\nsize = [3.0, 4.0, 0.02]\nmaterial = \"tinted\"\n\
        transform = { translate = [3.5, 0.0, 0.01] }\n";
    let sky = "[sky]\nkind = \"gradient\"\nzenith = [0.5, 0.5, 0.5]\n\
        horizon = [2.0, 2.0, 2.0]\nground = [0.0, 0.0, 0.0]\n";
    let body = format!("{sky}{}{glass}", checker_ground([0.5, 0.5]));
    let on = render_body(&body, 16, 3, true, Backend::Bvh);
    let off = render_body(&body, 16, 3, false, Backend::Bvh);
    let (_, layer) = rebuild_left(&on, 16, 3, 5);
    let sees_glass = |k: usize| on.out.left.mask[k] & parallax::scene::mask_bits::TRANSPARENT != 0;
    let n = (W * H) as usize;
    let under: Vec<usize> = (0..n).filter(|&k| sees_glass(k)).collect();
    assert!(under.len() > 60, "{} pixels see the glass", under.len());
    let (w, h) = (W as usize, H as usize);
    // How many of a pixel's 3×3 neighbourhood see the glass: jittered
    // samples of a pixel at the glass's edge hit either side of it.
    let glass_around = |k: usize| {
        let (i, j) = (k % w, k / w);
        (j.saturating_sub(1)..(j + 2).min(h))
            .flat_map(|jj| (i.saturating_sub(1)..(i + 2).min(w)).map(move |ii| jj * w + ii))
            .filter(|&kk| sees_glass(kk))
            .count()
    };
    let mut inside = 0;
    for k in 0..n {
        let (behind, rho) = (layer.behind_delta[k], layer.rho[k].y);
        match glass_around(k) {
            9 => {
                inside += 1;
                assert!(behind >= 0.5 && rho > 0.0, "pixel {k}: {behind}, rho {rho}");
            }
            0 => assert_eq!(behind, 0.0, "pixel {k}"),
            _ => {}
        }
    }
    assert!(inside > 30, "{inside} pixels inside the glass");
    let diffs: Vec<f64> = under
        .iter()
        .map(|&k| green(&on, k) - green(&off, k))
        .collect();
    let (bias, se) = mean_stderr(&diffs);
    let (m_off, _) = mean_stderr(&under.iter().map(|&k| green(&off, k)).collect::<Vec<_>>());
    eprintln!(
        "{} glass pixels: plain {m_off:.4}, filtered − plain {bias:.2e} ± {se:.1e}",
        under.len()
    );
    assert!(bias.abs() < 0.02 * m_off, "{bias} of {m_off}");
    assert!(bias.abs() < 4.0 * se, "{bias} ± {se}");
}

#[test]
fn light_behind_glass_is_filtered_apart_from_light_beside_it() {
    // One flat surface (depth 10 m, one normal) whose left half is seen
    // through glass (every sample split behind it) with light per unit
    // albedo 0.2, its right half directly with 1. Filtered, each half keeps
    // its own level up to the seam: mixed, the pixels beside the seam
    // would move toward the other's.
    let (w, h) = (32, 16);
    let mut layer = ViewInputs::new(w, h);
    let rho = Vec3::splat(0.5);
    layer.rho.fill(rho);
    for k in 0..w * h {
        let through = k % w < w / 2;
        layer.behind_delta[k] = if through { 1.0 } else { 0.0 };
        layer.l_surf[k] = rho * if through { 0.2 } else { 1.0 };
    }
    let (before, film) = filter_flat_surface(&layer);
    for (k, (a, b)) in before.rgb.iter().zip(&film.rgb).enumerate() {
        assert!(
            (a.y - b.y).abs() <= 1e-5 * a.y,
            "pixel {k}: {} -> {}",
            a.y,
            b.y
        );
    }
}

#[test]
fn filter_off_and_on_are_functions_of_the_samples() {
    // Off must equal the per-sample estimate bit for bit; on must equal the
    // filtered per-sample estimate (BVH backend: its packet query is the
    // single-ray one). Ground truth is the same either way, and the right
    // view is filtered too, guided by its own depth.
    let body = ground_body([0.5, 0.5], WALL);
    let off = render_body(&body, 4, 9, false, Backend::Bvh);
    let on = render_body(&body, 4, 9, true, Backend::Bvh);
    assert!(on.scene.filter_indirect && !off.scene.filter_indirect);
    let (film_off, layer_off) = rebuild_left(&off, 4, 9, 5);
    assert_eq!(
        off.out.images[0], film_off,
        "filter off is the plain estimate"
    );
    assert!(
        layer_off.is_empty(),
        "nothing is split off when the filter is off"
    );
    let (mut film, layer) = rebuild_left(&on, 4, 9, 5);
    assert!(
        layer.l_surf.iter().any(|l| l.y > 0.0) && layer.rho.iter().any(|r| r.y > 0.0),
        "the ground reflects sky light"
    );
    assert_eq!(film, film_off, "the split does not change the samples");
    let cam = RenderCamera::new(&on.rig.left, on.scene.origin_world);
    denoise_view(
        &on.scene,
        &cam,
        &on.out.left.depth_z_f32(),
        &mut film,
        &layer,
        aux(on.out.aov.as_ref().expect("a path-traced frame has AOVs")),
    );
    assert_eq!(on.out.images[0], film, "filter on is the filtered estimate");
    assert_ne!(on.out.images[0], off.out.images[0]);
    assert_ne!(on.out.images[1], off.out.images[1]);
    assert_eq!(on.out.left, off.out.left);
    assert_eq!(on.out.baselines, off.out.baselines);
}

#[test]
fn direct_light_is_split_off_as_direct_light_not_indirect() {
    // Open ground under a point light and a black sky: all its light is
    // its first vertex's next-event estimate, so none of it is split off as
    // indirect (a split taken before the first vertex's shadow rays resolve
    // would blur it with the indirect light's wide filter), and all of it
    // is the direct part (`l_direct`, its own filter, `direct.rs`).
    let body = "[sky]\nkind = \"constant\"\nle = [0.0, 0.0, 0.0]\n\
        [[light]]\nkind = \"point\"\nposition = [10.0, 0.0, 4.0]\nintensity = [400.0, 400.0, 400.0]\n\
        [[material]]\nname = \"grey\"\nkind = \"diffuse\"\nalbedo = [0.5, 0.5, 0.5]\n\
        [[object]]\nkind = \"quad\"\nsize = [200.0, 200.0]\nmaterial = \"grey\"\n";
    let on = render_body(body, 4, 2, true, Backend::Bvh);
    let (film, layer) = rebuild_left(&on, 4, 2, 5);
    assert!(
        layer.rho.iter().any(|r| r.y > 0.0),
        "the ground is Lambertian"
    );
    assert!(layer.l_surf.iter().all(|&l| l == Vec3::ZERO));
    assert!(
        film.rgb.iter().any(|c| c.y > 0.0),
        "the light reaches the ground"
    );
    for (k, (px, d)) in film.rgb.iter().zip(&layer.l_direct).enumerate() {
        assert!(
            (*px - *d).abs().max_element() <= 1e-6 * px.max_element(),
            "pixel {k}: {px} vs {d}"
        );
    }
}

#[test]
fn scenes_with_a_medium_leave_indirect_light_to_the_fog_filter() {
    let fog = "[medium]\nkind = \"homogeneous\"\nsigma_t = 0.01\nalbedo = [0.9, 0.9, 0.9]\nz_max_m = 30.0\n";
    let r = render_body(&ground_body([0.5, 0.5], fog), 0, 1, true, Backend::Bvh);
    assert!(!r.scene.filter_indirect && r.scene.filter_inscatter);
}

/// A flat 32×32 surface (depth 10 m, one normal) whose light per unit
/// albedo is 1 except at the centre pixel, where it is `hot`, filtered by
/// [`filter_flat_surface`]; also returns the centre's index.
fn filter_one_hot_pixel(hot: f32) -> (Film, Film, usize) {
    let (w, h) = (32, 32);
    let centre = 16 * w + 16;
    let mut layer = ViewInputs::new(w, h);
    let rho = Vec3::splat(0.5);
    layer.rho.fill(rho);
    layer.l_surf.fill(rho);
    layer.l_surf[centre] = rho * hot;
    let (before, after) = filter_flat_surface(&layer);
    (before, after, centre)
}

/// The film of a flat surface (depth 10 m, one normal) carrying `layer`'s
/// light on the surface plus 0.25 of direct light, before and after
/// filtering at σ = 4 px.
fn filter_flat_surface(layer: &ViewInputs) -> (Film, Film) {
    let (w, h) = (layer.width, layer.height);
    let mut film = Film::new(w, h);
    for (px, l) in film.rgb.iter_mut().zip(&layer.l_surf) {
        *px = *l + Vec3::splat(0.25);
    }
    let before = film.clone();
    let (depth, opacity, normal) = (vec![10.0; w * h], vec![0.0; w * h], vec![Vec3::Z; w * h]);
    let guide = DepthGuide {
        depth_z: &depth,
        opacity: &opacity,
        normal: &normal,
    };
    let widths = Widths {
        sigma_px: 4.0,
        sigma_opacity: 0.1,
        sigma_depth_rel: 0.3,
        direct_levels: 0,
        surface_sigma_lum: None,
    };
    denoise_guided(&mut film, layer, &guide, &widths);
    (before, film)
}

#[test]
fn a_firefly_takes_its_neighbours_light_and_noise_is_spread() {
    // At 1000× its neighbourhood the centre is a firefly: spread by a
    // σ = 4 px kernel it would light its neighbours by several times their
    // own light. It takes their light per unit albedo, 1, and its light
    // comes back only as the bounded gain (1.1) of the surface light within
    // the light-keeping window (2 px at 32 px wide): 0.25 direct + 0.5 ×
    // 1.1 there, every other pixel as it was. At 3× it is noise and is
    // spread: the centre drops, its neighbours rise.
    let (before, after, centre) = filter_one_hot_pixel(1000.0);
    let near =
        |k: usize| (k % 32).abs_diff(centre % 32) <= 2 && (k / 32).abs_diff(centre / 32) <= 2;
    for (k, (a, b)) in before.rgb.iter().zip(&after.rgb).enumerate() {
        let expect = if near(k) { 0.25 + 0.5 * 1.1 } else { a.y };
        assert!(
            (b.y - expect).abs() <= 1e-5 * expect,
            "pixel {k}: {} -> {}, expected {expect}",
            a.y,
            b.y
        );
    }
    let (before, after, centre_3) = filter_one_hot_pixel(3.0);
    assert_eq!(centre, centre_3);
    assert!(after.rgb[centre].y < 0.9 * before.rgb[centre].y);
    // (+0.9 % when written.)
    assert!(after.rgb[centre + 1].y > 1.005 * before.rgb[centre + 1].y);
}

#[test]
fn light_carried_by_sparse_bright_paths_all_over_a_surface_is_kept() {
    // At night the light between lamps reaches most pixels as rare bright
    // paths: here one pixel in ten holds 30 per unit albedo, the rest 0.1,
    // so 97 % of the light is in what the filter leaves out as fireflies.
    // Many pixels carry it, so it comes back whole (one path's light would
    // stay bounded: `a_firefly_takes_its_neighbours_light…`), and spread:
    // no pixel keeps a speck.
    let (w, h) = (200, 100);
    let mut layer = ViewInputs::new(w, h);
    let rho = Vec3::splat(0.5);
    layer.rho.fill(rho);
    for (k, l) in layer.l_surf.iter_mut().enumerate() {
        let hot = ((k as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15) >> 32).is_multiple_of(10);
        *l = rho * if hot { 30.0 } else { 0.1 };
    }
    let hot_share = layer.l_surf.iter().filter(|l| l.y > 1.0).count() as f64 / (w * h) as f64;
    assert!(
        (hot_share - 0.1).abs() < 0.03,
        "{hot_share} of the pixels hot"
    );
    let (before, after) = filter_flat_surface(&layer);
    let mean = |f: &Film| f.rgb.iter().map(|p| p.y as f64).sum::<f64>() / (w * h) as f64;
    let (traced, kept) = (mean(&before), mean(&after));
    assert!(
        (kept / traced - 1.0).abs() < 0.03,
        "mean {kept} after the filter against {traced} traced"
    );
    for (k, p) in after.rgb.iter().enumerate() {
        assert!(
            p.y > 0.5 * traced as f32 && p.y < 1.5 * traced as f32,
            "pixel {k}: {} (mean {traced})",
            p.y
        );
    }
}
