//! Direct lighting from local lights against closed forms (max depth 1, so
//! only next-event estimation and, for the area light, its MIS partner — BSDF
//! rays that hit the emitter — contribute):
//! - a point light: L = ρ/π · I·cosθ/d²;
//! - an emissive quad: L = ρ/π · E with E from Lambert's polygon formula,
//!   E = L_e/2 · Σ_k angle(u_k, u_k+1) · n·normalize(u_k × u_k+1), alone or
//!   with a brighter emitter under the plane that the light tree must not
//!   offer the plane's points (nor count in the MIS weights of BSDF rays);
//! - an emissive box, one light of twelve triangles (one-sided, facing
//!   out): E is the polygon formula summed over the faces that face the
//!   point.
//!
//! A camera 3 m up looks straight down on a Lambert plane; interior plane pixels
//! are compared by the mean of rendered/expected (within 1%, z-score ≤ 4).

use crate::common;

use common::{mean_stderr, render, scene_from_toml, Rendered};
use glam::DVec3;
use parallax::accel::Backend;

const RHO: f64 = 0.5;

fn scene(lights: &str) -> String {
    format!(
        "[camera]\nwidth = 96\nheight = 72\nhfov_deg = 60.0\nbaselines_cm = [10.0]\nposition = [0.0, 0.0, 3.0]\npitch_deg = 90.0\n\
[render]\nspp = 128\nmax_depth = 1\nseed = 21\nfilter_indirect = false\n\
[[material]]\nname = \"m\"\nkind = \"diffuse\"\nalbedo = [{RHO:?}, {RHO:?}, {RHO:?}]\n\
[[object]]\nkind = \"quad\"\nsize = [100.0, 100.0]\nmaterial = \"m\"\ninstance = 3\n{lights}"
    )
}

/// Ratios rendered/expected over plane pixels whose 3×3 neighbourhood is plane.
fn ratios(r: &Rendered, expected: impl Fn(DVec3) -> f64) -> Vec<f64> {
    let (w, h) = (r.out.left.width as usize, r.out.left.height as usize);
    let cam = &r.rig.left;
    let mut v = Vec::new();
    for j in 1..h - 1 {
        for i in 1..w - 1 {
            if !(0..9).all(|n| r.out.left.instance[(j + n / 3 - 1) * w + i + n % 3 - 1] == 3) {
                continue;
            }
            let k = j * w + i;
            let x = cam.center_world
                + cam.pixel_center_dir_world(i as u32, j as u32) * r.out.left.depth_z[k];
            let e = expected(x);
            if e > 1e-3 {
                v.push(r.out.images[0].rgb[k].y as f64 / e);
            }
        }
    }
    v
}

fn check(v: &[f64]) {
    let (mean, se) = mean_stderr(v);
    eprintln!("n = {}, mean ratio {mean:.5} ± {se:.5}", v.len());
    assert!(v.len() > 1000);
    assert!((mean - 1.0).abs() <= 0.01, "mean ratio {mean}");
    assert!(
        (mean - 1.0).abs() <= 4.0 * se + 1e-3,
        "z-score {}",
        (mean - 1.0).abs() / se
    );
}

#[test]
fn point_light_irradiance_matches_inverse_square_law() {
    let (p, i_w) = (DVec3::new(0.3, -0.2, 2.0), 20.0);
    let text = scene(&format!(
        "[[light]]\nkind = \"point\"\nposition = [{:?}, {:?}, {:?}]\nintensity = [{i_w:?}, {i_w:?}, {i_w:?}]\n",
        p.x, p.y, p.z
    ));
    let r = render(&scene_from_toml(&text), Backend::default_backend(), 128);
    check(&ratios(&r, |x| {
        let d = p - x;
        RHO / std::f64::consts::PI * i_w * (d.z / d.length()) / d.length_squared()
    }));
}

/// A 1 m square emitter at `c` facing down, radiance `le`.
fn lamp_above(c: DVec3, le: f64) -> String {
    format!(
        "[[material]]\nname = \"lamp\"\nkind = \"emissive\"\nradiance = [{le:?}, {le:?}, {le:?}]\n\
[[object]]\nkind = \"quad\"\nsize = [1.0, 1.0]\nmaterial = \"lamp\"\ninstance = 9\ntransform = {{ translate = [{:?}, {:?}, {:?}], rotate_deg = [180.0, 0.0, 0.0] }}\n",
        c.x, c.y, c.z
    )
}

/// Irradiance at plane point `x` (normal +z) from a polygon of radiance
/// `le` wholly above its horizon (Lambert's polygon formula).
fn polygon_irradiance(corners: &[DVec3], le: f64, x: DVec3) -> f64 {
    let u: Vec<DVec3> = corners.iter().map(|v| (*v - x).normalize()).collect();
    let k = u.len();
    (0..k)
        .map(|i| {
            let (a, b) = (u[i], u[(i + 1) % k]);
            a.dot(b).clamp(-1.0, 1.0).acos() * a.cross(b).normalize().z
        })
        .sum::<f64>()
        .abs()
        * le
        / 2.0
}

/// ρ/π · E at plane point `x` under [`lamp_above`].
fn lamp_above_radiance(c: DVec3, le: f64, x: DVec3) -> f64 {
    let corners = [
        c + DVec3::new(-0.5, -0.5, 0.0),
        c + DVec3::new(0.5, -0.5, 0.0),
        c + DVec3::new(0.5, 0.5, 0.0),
        c + DVec3::new(-0.5, 0.5, 0.0),
    ];
    RHO / std::f64::consts::PI * polygon_irradiance(&corners, le, x)
}

#[test]
fn emissive_quad_irradiance_matches_lambert_polygon_formula() {
    // A 1 m square at 2 m, facing down, radiance 10.
    let (c, le) = (DVec3::new(0.4, 0.3, 2.0), 10.0);
    let r = render(
        &scene_from_toml(&scene(&lamp_above(c, le))),
        Backend::default_backend(),
        128,
    );
    check(&ratios(&r, |x| lamp_above_radiance(c, le, x)));
}

#[test]
fn quad_light_seen_past_a_brighter_one_below_the_plane_matches_the_closed_form() {
    // The lamp above plus a far brighter 4 m square 0.5 m under the plane,
    // facing up at its underside: the light tree gives the plane's points
    // (receiver normal +z) the lamp only, but without the normal it would
    // give the square ~99 % of its choices. A BSDF ray that hits the lamp
    // weighs itself against light sampling with the lamp's pmf; taken
    // without the receiver's normal, that pmf is ~1 % of the one light
    // sampling used, and the two MIS weights sum to nearly 2 where the
    // BSDF ray would have carried weight.
    let (c, le) = (DVec3::new(0.4, 0.3, 2.0), 10.0);
    let below = "[[material]]\nname = \"under\"\nkind = \"emissive\"\nradiance = [50.0, 50.0, 50.0]\n\
[[object]]\nkind = \"quad\"\nsize = [4.0, 4.0]\nmaterial = \"under\"\ninstance = 8\ntransform = { translate = [0.0, 0.0, -0.5] }\n";
    let text = scene(&(lamp_above(c, le) + below));
    let r = render(&scene_from_toml(&text), Backend::default_backend(), 128);
    check(&ratios(&r, |x| lamp_above_radiance(c, le, x)));
}

#[test]
fn emissive_box_irradiance_sums_the_polygon_formula_over_its_faces_facing_the_point() {
    // A 0.6 × 0.4 × 0.3 m box of radiance 10 centred 1.5 m up: most plane
    // points see its bottom and one or two sides, each triangle emitting
    // outwards only. Its twelve triangles are one light; a draw among them
    // that ignored which face the point sees, or a BSDF ray's MIS weight
    // without the draw's pmf, moves the mean.
    let (c, size, le) = (DVec3::new(0.3, -0.2, 1.5), DVec3::new(0.6, 0.4, 0.3), 10.0);
    let text = scene(&format!(
        "[[material]]\nname = \"lamp\"\nkind = \"emissive\"\nradiance = [{le:?}, {le:?}, {le:?}]\n\
[[object]]\nkind = \"box\"\nsize = [{:?}, {:?}, {:?}]\nmaterial = \"lamp\"\ninstance = 9\ntransform = {{ translate = [{:?}, {:?}, {:?}] }}\n",
        size.x, size.y, size.z, c.x, c.y, c.z
    ));
    let r = render(&scene_from_toml(&text), Backend::default_backend(), 128);
    let h = size / 2.0;
    // Per axis and sign: the face's four corners in order around it.
    let faces: Vec<(DVec3, [DVec3; 4])> = (0..3)
        .flat_map(|axis| [-1.0, 1.0].map(move |s| (axis, s)))
        .map(|(axis, s)| {
            let n = DVec3::from({
                let mut a = [0.0; 3];
                a[axis] = s;
                a
            });
            let (e1, e2) = (
                DVec3::from({
                    let mut a = [0.0; 3];
                    a[(axis + 1) % 3] = 1.0;
                    a
                }),
                DVec3::from({
                    let mut a = [0.0; 3];
                    a[(axis + 2) % 3] = 1.0;
                    a
                }),
            );
            let f = c + n * h;
            let corner = |a: f64, b: f64| f + e1 * h * a + e2 * h * b;
            (
                n,
                [
                    corner(-1.0, -1.0),
                    corner(1.0, -1.0),
                    corner(1.0, 1.0),
                    corner(-1.0, 1.0),
                ],
            )
        })
        .collect();
    check(&ratios(&r, |x| {
        let e: f64 = faces
            .iter()
            .filter(|(n, corners)| n.dot(x - corners[0]) > 0.0)
            .map(|(_, corners)| polygon_irradiance(corners, le, x))
            .sum();
        RHO / std::f64::consts::PI * e
    }));
}

/// A light: position, intensity, and for a spot (axis, cos inner, cos outer).
type TestLight = (DVec3, f64, Option<(DVec3, f64, f64)>);

#[test]
fn many_point_and_spot_lights_sum_their_inverse_square_laws() {
    // Twelve lights (no sun or sky: local lights are all the light, so NEE
    // resamples them from eight candidates): points and spots aimed off
    // the vertical, whose falloff edges cross the plane's pixels.
    let lights: Vec<TestLight> = (0..12)
        .map(|k| {
            let a = k as f64 * 2.399;
            let p = DVec3::new(1.5 * a.cos(), 1.2 * a.sin(), 1.0 + 0.15 * k as f64);
            let i = 2.0 + 3.0 * (k % 4) as f64;
            let spot = (k % 3 == 0).then(|| {
                let dir = DVec3::new(0.3 * a.sin(), -0.3 * a.cos(), -1.0).normalize();
                (dir, 25f64.to_radians().cos(), 50f64.to_radians().cos())
            });
            (p, i, spot)
        })
        .collect();
    let text = scene(
        &lights
            .iter()
            .map(|(p, i, spot)| match spot {
                None => format!(
                    "[[light]]\nkind = \"point\"\nposition = [{:?}, {:?}, {:?}]\nintensity = [{i:?}, {i:?}, {i:?}]\n",
                    p.x, p.y, p.z
                ),
                Some((d, _, _)) => format!(
                    "[[light]]\nkind = \"spot\"\nposition = [{:?}, {:?}, {:?}]\ndirection = [{:?}, {:?}, {:?}]\nintensity = [{i:?}, {i:?}, {i:?}]\ninner_deg = 25.0\nouter_deg = 50.0\n",
                    p.x, p.y, p.z, d.x, d.y, d.z
                ),
            })
            .collect::<String>(),
    );
    let r = render(&scene_from_toml(&text), Backend::default_backend(), 64);
    check(&ratios(&r, |x| {
        lights
            .iter()
            .map(|(p, i, spot)| {
                let d = *p - x;
                let falloff = spot.map_or(1.0, |(dir, cos_in, cos_out)| {
                    // Smoothstep between the outer and inner cone cosines.
                    let c = -(d.normalize()).dot(dir);
                    let t = ((c - cos_out) / (cos_in - cos_out)).clamp(0.0, 1.0);
                    t * t * (3.0 - 2.0 * t)
                });
                RHO / std::f64::consts::PI * i * falloff * (d.z / d.length()) / d.length_squared()
            })
            .sum()
    }));
}
