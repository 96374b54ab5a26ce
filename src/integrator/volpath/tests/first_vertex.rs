//! The camera sample's split at a first surface vertex seen through fog:
//! a glossy one hands all its light but the suns' next-event part to the
//! direct filter, a glass one its reflection to the reflection filter,
//! each with its exact albedo weight; a Lambertian one its sky
//! next-event estimate to the direct filter and all that follows to the
//! indirect one, also where it is seen through a pane of glass.

use glam::{Vec2, Vec3};
use shaders_cpu::bsdf::Bsdf;

use super::{built, mean_var, sample_stream, SCENE, SKY};
use crate::accel::{Accel, Ray};
use crate::integrator::path::LiSample;
use crate::integrator::volpath::Strategies;
use crate::integrator::Shading;

#[test]
fn glossy_first_vertex_hands_its_light_but_the_suns_to_direct_light_in_fog() {
    // Paint on the ground under the fog slab, seen through the split
    // camera segment: every sample meets the paint with throughput Tr of
    // the camera segment (passing, or as the split's surface part), so
    // rho_direct is exactly Tr·(base + 0.04), and all the light after the
    // paint is l_direct but the sun's next-event estimate, kept as traced:
    // the sample is its fog part, l_direct and that sun part, which is
    // never negative and vanishes with the sun.
    let base = Vec3::new(0.5, 0.1, 0.1);
    let paint = SCENE.replace(
        "kind = \"diffuse\"\nalbedo = [0.3, 0.3, 0.3]",
        "kind = \"coated\"\nalbedo = [0.5, 0.1, 0.1]\ncoat_roughness = 0.3",
    );
    assert_ne!(paint, SCENE, "the ground's material was not replaced");
    let (lit, sun_lit) = glossy_paint_split(&format!("{paint}{SKY}"), base);
    assert!(lit.min_element() > 0.0, "{lit}");
    assert!(sun_lit.min_element() > 0.0, "{sun_lit}");
    let dark_src = format!("{}{SKY}", strip_sun(&paint));
    let (sky_lit, no_sun) = glossy_paint_split(&dark_src, base);
    assert!(sky_lit.min_element() > 0.0, "{sky_lit}");
    assert!(
        no_sun.abs().max_element() <= 1e-4 * sky_lit.max_element(),
        "a sun part {no_sun} without a sun"
    );
}

/// The scene without its sun.
fn strip_sun(src: &str) -> String {
    let start = src.find("[[light]]").expect("a sun");
    let end = src.find("[medium]").expect("a medium");
    format!("{}{}", &src[..start], &src[end..])
}

/// Camera samples of the paint in `src` (ground albedo `base` under a
/// clear coat): checks each sample's split and returns the sums of the
/// light handed to the direct filter and of the sun part left as traced.
fn glossy_paint_split(src: &str, base: Vec3) -> (Vec3, Vec3) {
    let rho_want = (base + Vec3::splat(0.04)) * ground_tr();
    let (mut reflected, mut sun) = (Vec3::ZERO, Vec3::ZERO);
    ground_samples(src, 3, 2048, |k, s| {
        let dn = s.denoise;
        assert!(dn.glossy, "sample {k}: not split at the paint");
        assert!(
            (dn.rho_direct - rho_want).abs().max_element() <= 1e-5,
            "sample {k}: rho_direct {} vs {rho_want}",
            dn.rho_direct
        );
        assert_eq!((dn.l_surf, dn.rho), (Vec3::ZERO, Vec3::ZERO));
        let rest = rest_after(k, s, dn.l_fog + dn.l_direct);
        reflected += dn.l_direct;
        sun += rest;
    });
    (reflected, sun)
}

/// The camera ray of [`ground_samples`]: from 1.5 m up, down to the ground.
const GROUND_O: Vec3 = Vec3::new(0.0, 0.0, 1.5);

/// Sample `k`'s light `s.l` less the parts handed to the filters
/// (`handed`): what stays as traced, never negative (to rounding).
fn rest_after(k: u32, s: &LiSample, handed: Vec3) -> Vec3 {
    let rest = s.l - handed;
    assert!(
        rest.min_element() >= -1e-4 * (1.0 + s.l.max_element()),
        "sample {k}: l {} = handed over {handed} + as traced {rest}",
        s.l
    );
    rest
}

/// The direction of [`ground_samples`]' camera ray.
fn ground_d() -> Vec3 {
    Vec3::new(1.0, 0.2, -0.4).normalize()
}

/// Tr of the homogeneous σ_t = 0.05/m over [`ground_samples`]' ray's drop
/// to the ground (z = 0).
fn ground_tr() -> f32 {
    (-0.05 * GROUND_O.z / -ground_d().z).exp()
}

/// Calls `f` with each of `n` camera samples (stream seed `seed`) along
/// one ray to the ground of `src`, the camera segment split.
fn ground_samples(src: &str, seed: u64, n: u32, mut f: impl FnMut(u32, &LiSample)) {
    let (scene, accel) = built(src);
    let shading = Shading::new(&scene, &accel);
    let ctx = shading.context(4);
    let split = Strategies {
        split_first: true,
        ..Strategies::default()
    };
    let mut rays = 0;
    for k in 0..n {
        let mut stream = sample_stream(seed, k);
        let ray = Ray::new(GROUND_O, ground_d());
        let s = ctx.trace(
            ray,
            accel.intersect(&ray),
            &mut stream,
            &mut rays,
            split,
            None,
        );
        f(k, &s);
    }
}

#[test]
fn glass_first_vertex_hands_its_reflection_to_the_reflection_filter_in_fog() {
    // A smooth glass floor under the fog slab, seen through the split camera
    // segment: every sample meets the glass with throughput Tr, so rho_refl
    // is exactly Tr·R(cos θ); the reflected samples' light after the glass
    // is l_refl, whose mean over rho_refl's must be the radiance along the
    // mirrored ray, estimated independently by tracing that ray itself.
    let glass = SCENE.replace(
        "kind = \"diffuse\"\nalbedo = [0.3, 0.3, 0.3]",
        "kind = \"dielectric\"\nior = 1.5\nroughness = 0.0\ntint = [1.0, 1.0, 1.0]",
    );
    assert_ne!(glass, SCENE, "the ground's material was not replaced");
    let d = ground_d();
    let t_hit = GROUND_O.z / -d.z;
    let tr = (-0.05 * t_hit).exp();
    let r = shaders_cpu::bsdf::fresnel::fr_dielectric(-d.z, 1.5);
    let n = 16384;
    let mut refl = Vec::new();
    ground_samples(&glass, 3, n, |k, s| {
        let dn = s.denoise;
        assert!(
            (dn.rho_refl - Vec3::splat(tr * r)).abs().max_element() <= 1e-5,
            "sample {k}: rho_refl {} vs Tr·R {}",
            dn.rho_refl,
            tr * r
        );
        // The rest is what refracted: never negative.
        rest_after(k, s, dn.l_fog + dn.l_refl);
        refl.push(dn.l_refl.y as f64 / (tr * r) as f64);
    });
    // The mirrored ray from the glass, traced plainly with the scattering
    // events the reflected samples have left (the glass took one).
    let (scene, accel) = built(&glass);
    let shading = Shading::new(&scene, &accel);
    let ctx_after = shading.context(3);
    let mut rays = 0;
    let p = GROUND_O + d * t_hit + Vec3::Z * 1e-3;
    let d_mirror = Vec3::new(d.x, d.y, -d.z);
    let mirrored: Vec<f64> = (0..n)
        .map(|k| {
            let mut stream = sample_stream(5, k);
            let ray = Ray::new(p, d_mirror);
            let hit = accel.intersect(&ray);
            let s = ctx_after.trace(
                ray,
                hit,
                &mut stream,
                &mut rays,
                Strategies::default(),
                None,
            );
            s.l.y as f64
        })
        .collect();
    let (m_refl, v_refl) = mean_var(&refl);
    let (m_mirror, v_mirror) = mean_var(&mirrored);
    let se = ((v_refl + v_mirror) / n as f64).sqrt();
    eprintln!("l_refl / rho_refl {m_refl:.4} vs mirrored ray {m_mirror:.4} ± {se:.4}");
    assert!(m_mirror > 0.0);
    assert!(
        (m_refl - m_mirror).abs() < 4.0 * se,
        "{m_refl} vs {m_mirror} ± {se}"
    );
}

#[test]
fn lambertian_first_vertex_splits_its_light_as_without_fog() {
    // The diffuse ground under the fog slab, with a wall beside it, seen
    // through the split camera segment: rho = rho_direct = Tr·albedo
    // exactly; the sample is its fog part, x1's sky next-event estimate
    // (l_direct), all that follows (l_surf: fog light, the sky reached by
    // the bounce, the wall's light) and the sun's next-event part, which
    // is never negative and vanishes with the sun.
    let wall = "[[object]]\nkind = \"box\"\nsize = [10.0, 0.2, 4.0]\nmaterial = \"ground\"\n\
                transform = { translate = [3.6, -3.0, 2.0] }\n";
    let src = format!("{SCENE}{wall}{SKY}");
    let (direct, surf, sun_lit) = lambertian_split(&src);
    assert!(direct.min_element() > 0.0 && surf.min_element() > 0.0);
    let (_, surf_no_wall, _) = lambertian_split(&format!("{SCENE}{SKY}"));
    assert!(
        (surf - surf_no_wall).abs().max_element() > 0.01 * surf.max_element(),
        "the wall (its light, the sky it hides) is in the indirect light: {surf} vs {surf_no_wall} without it"
    );
    assert!(sun_lit.min_element() > 0.0, "{sun_lit}");
    let (sky_direct, sky_surf, no_sun) = lambertian_split(&strip_sun(&src));
    assert!(sky_direct.min_element() > 0.0 && sky_surf.min_element() > 0.0);
    assert!(
        no_sun.abs().max_element() <= 1e-4 * (sky_direct + sky_surf).max_element(),
        "light {no_sun} left out of the split without a sun"
    );
}

/// Camera samples of the diffuse ground in `src`: checks each sample's
/// split and returns the sums of its direct light, its indirect light and
/// the sun part left as traced.
fn lambertian_split(src: &str) -> (Vec3, Vec3, Vec3) {
    let rho_want = Vec3::splat(0.3) * ground_tr();
    let (mut direct, mut surf, mut sun) = (Vec3::ZERO, Vec3::ZERO, Vec3::ZERO);
    ground_samples(src, 5, 2048, |k, s| {
        let dn = s.denoise;
        assert!(!dn.glossy, "sample {k}: split as glossy");
        for rho in [dn.rho, dn.rho_direct] {
            assert!(
                (rho - rho_want).abs().max_element() <= 1e-5,
                "sample {k}: rho {rho} vs {rho_want}"
            );
        }
        let rest = rest_after(k, s, dn.l_fog + dn.l_direct + dn.l_surf);
        direct += dn.l_direct;
        surf += dn.l_surf;
        sun += rest;
    });
    (direct, surf, sun)
}

#[test]
fn lambertian_ground_seen_through_glass_is_split_behind_it_in_fog() {
    // A 2 cm pane of smooth glass 0.75 m over the diffuse ground, under the
    // fog slab: a sample that refracts through both faces and crosses the
    // fog below without a scatter splits at the ground, marked as behind
    // delta scatters, with rho = rho_direct = Tr(camera segment) × the two
    // refractions' weights × albedo, exactly. A sample the pane reflects
    // hands that light to the reflection filter and splits nowhere.
    let glass = "[[material]]\nname = \"glass\"\nkind = \"dielectric\"\nior = 1.5\n\
                 roughness = 0.0\ntint = [1.0, 1.0, 1.0]\n";
    let pane = "[[object]]\nkind = \"box\"\nsize = [6.0, 6.0, 0.02]\nmaterial = \"glass\"\n\
                transform = { translate = [2.0, 0.4, 0.75] }\n";
    let src = format!("{SCENE}{glass}{pane}{SKY}");
    let (behind, handed, sun_lit) = through_pane(&src);
    // About (1 − 0.25)² of the samples refract twice (the pane reflects
    // with probability max(R, 0.25)); a few scatter in the fog below it.
    assert!(
        behind > 900,
        "{behind} of 2048 samples split behind the pane"
    );
    assert!(handed.min_element() > 0.0 && sun_lit.min_element() > 0.0);
    let (_, sky_handed, no_sun) = through_pane(&strip_sun(&src));
    assert!(
        no_sun.abs().max_element() <= 1e-4 * sky_handed.max_element(),
        "light {no_sun} of samples split behind the pane left out of the split without a sun"
    );
}

/// Camera samples of the ground in `src` through the pane of
/// [`lambertian_ground_seen_through_glass_is_split_behind_it_in_fog`]:
/// checks each sample's split and returns how many split behind the pane,
/// and over those, the sums of the light handed to the direct and indirect
/// filters and of the sun part left as traced.
fn through_pane(src: &str) -> (u32, Vec3, Vec3) {
    let d = ground_d();
    // The pane's top face, hit first: the camera segment's Tr.
    let tr_top = (-0.05 * (GROUND_O.z - 0.76) / -d.z).exp();
    // The two refractions' weights f·|cos|/pdf, from the BSDF: into the
    // glass at the top face (local z up), out of it at the bottom face
    // (local z down: the ray meets it from inside).
    let pane = Bsdf::Dielectric {
        eta: 1.5,
        alpha: 0.0,
        tint: Vec3::ONE,
    };
    let refract = |wo: Vec3| {
        let t = pane.sample(wo, 0.999, Vec2::ZERO).expect("a refraction");
        assert!(t.wi.z * wo.z < 0.0, "the sample refracted");
        (t.wi, t.f.x * t.wi.z.abs() / t.pdf)
    };
    let (wi, w_in) = refract(-d);
    let (_, w_out) = refract(Vec3::new(-wi.x, -wi.y, wi.z));
    let rho_want = Vec3::splat(0.3 * tr_top * w_in * w_out);
    let (mut behind, mut reflected) = (0, 0);
    let (mut handed, mut sun) = (Vec3::ZERO, Vec3::ZERO);
    ground_samples(src, 7, 2048, |k, s| {
        let dn = s.denoise;
        if dn.rho_refl_hit != Vec3::ZERO {
            reflected += 1;
            assert!(
                !dn.split_behind_delta && dn.rho == Vec3::ZERO,
                "sample {k}: reflected and split"
            );
        } else if dn.rho != Vec3::ZERO {
            behind += 1;
            assert!(
                dn.split_behind_delta,
                "sample {k}: split behind glass, not marked so"
            );
            for rho in [dn.rho, dn.rho_direct] {
                assert!(
                    (rho - rho_want).abs().max_element() <= 1e-5,
                    "sample {k}: rho {rho} vs {rho_want}"
                );
            }
        }
        let rest = rest_after(k, s, dn.l_fog + dn.l_direct + dn.l_surf + dn.l_refl);
        if dn.rho != Vec3::ZERO {
            sun += rest;
            handed += dn.l_direct + dn.l_surf;
        }
    });
    assert!(
        reflected > 300,
        "{reflected} of 2048 samples took the pane's reflection"
    );
    (behind, handed, sun)
}
