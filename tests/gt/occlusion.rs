//! The occlusion mask against a brute-force f64 check on analytic boxes
//! (GROUND_TRUTH.md "Occlusion"): a left pixel is occluded for baseline B if its
//! surface point X leaves the right image (x − d < 0) or the segment C_R → X
//! enters a box before X.

use crate::common;

use common::{level_right_centre, render, scene_from_toml, DEFAULT_BASELINES_M};
use glam::DVec3;
use parallax::accel::Backend;

/// First entry parameter of segment p + t·d (t in (0, tmax)) into a box.
fn enters(p: DVec3, d: DVec3, lo: DVec3, hi: DVec3, tmax: f64) -> bool {
    let (mut t0, mut t1) = (0.0f64, tmax);
    for a in 0..3 {
        let (ta, tb) = ((lo[a] - p[a]) / d[a], (hi[a] - p[a]) / d[a]);
        t0 = t0.max(ta.min(tb));
        t1 = t1.min(ta.max(tb));
    }
    t0 <= t1
}

/// The boxes scene sets no `baselines_cm`: every default one is rendered.
const BASELINES_M: [f64; 5] = DEFAULT_BASELINES_M;

/// The boxes scene's left camera: level at (0, 0, 1.65) looking along +x.
const C_LEFT: DVec3 = DVec3::new(0.0, 0.0, 1.65);

#[test]
fn occlusion_mask_matches_brute_force() {
    let (w, h) = (640u32, 360u32);
    let r = render(
        &scene_from_toml(&common::boxes::boxes_scene(w, h)),
        Backend::default_backend(),
        0,
    );
    // 60° horizontal field of view over 640 px; the level ray through (u, v)
    // has camera-z component 1: (1, −(u − cx)/f, −(v − cy)/f) in the world.
    let f = 320.0 / 30f64.to_radians().tan();
    assert!((r.rig.left.intrinsics.f_px - f).abs() <= 1e-9 * f);
    let dir = |i: u32, j: u32| {
        DVec3::new(
            1.0,
            -((i as f64 + 0.5) - 320.0) / f,
            -((j as f64 + 0.5) - 180.0) / f,
        )
    };
    let boxes: Vec<(DVec3, DVec3)> = common::boxes::BOXES
        .iter()
        .map(|(c, s)| {
            let (c, hs) = (DVec3::from_array(*c), DVec3::from_array(*s) * 0.5);
            (c - hs, c + hs)
        })
        .collect();
    assert_eq!(r.rig.left.center_world, C_LEFT);
    assert_eq!(r.out.baselines.len(), BASELINES_M.len(), "baseline count");
    for (b, (gt, bm)) in r.out.baselines.iter().zip(BASELINES_M).enumerate() {
        assert!(
            (gt.baseline_m - bm).abs() < 1e-12,
            "baseline {b}: {} m, expected {bm} m",
            gt.baseline_m
        );
        let c_r = level_right_centre(C_LEFT, bm);
        let got = r.rig.right(b).center_world;
        assert!(
            (got - c_r).length() <= 1e-12,
            "right centre {b}: {got} vs C_L + B·x_L = {c_r}"
        );
        let (mut mismatches, mut occluded) = (0usize, 0usize);
        for j in 0..h {
            for i in 0..w {
                let k = (j * w + i) as usize;
                let z = r.out.left.depth_z[k];
                let d_left = dir(i, j);
                if common::boxes::grazes_box_edge(C_LEFT, d_left) {
                    continue;
                }
                let expect = if !z.is_finite() {
                    false
                } else {
                    let x = i as f64 + 0.5;
                    let p = C_LEFT + d_left * z;
                    x - f * bm / z < 0.0
                        || boxes
                            .iter()
                            .any(|(lo, hi)| enters(c_r, p - c_r, *lo, *hi, 1.0 - 1e-4))
                };
                occluded += expect as usize;
                if expect != (gt.occlusion[k] == 255) {
                    mismatches += 1;
                }
            }
        }
        eprintln!(
            "B = {} m: {occluded} occluded, {mismatches} mismatches",
            gt.baseline_m
        );
        assert!(occluded > 100, "the scene must produce occlusions");
        assert!(
            mismatches <= (w * h) as usize / 10_000,
            "{mismatches} mismatches"
        );
    }
}

/// On an unobstructed road plane the only occlusion is leaving the right image,
/// decided with the stored (f32) disparity: a point landing exactly on the
/// right image's left edge (x − d = 0) is visible. At 400×226 with B = 0.54 m,
/// pixel (4, 125) has Z = 1.5 m and d = 4.5 = x exactly.
#[test]
fn occlusion_agrees_with_the_stored_disparity_at_the_image_edge() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/scenes/analytic/road_plane.toml"
    );
    let mut loaded = parallax::scene::load_scene(std::path::Path::new(path)).unwrap();
    loaded.desc.camera.width = 400;
    loaded.desc.camera.height = 226;
    loaded.desc.camera.baselines_cm = vec![54.0];
    let r = render(&loaded, Backend::default_backend(), 0);
    let gt = &r.out.baselines[0];
    let w = 400usize;
    let mut edge_ties = 0;
    for (k, &occ) in gt.occlusion.iter().enumerate() {
        let x = (k % w) as f64 + 0.5;
        let d = gt.disparity_left[k] as f64;
        let outside = r.out.left.depth_z[k].is_finite() && x - d < 0.0;
        edge_ties += (r.out.left.depth_z[k].is_finite() && x == d) as usize;
        assert_eq!(
            occ == 255,
            outside,
            "pixel {k}: occlusion {occ}, x {x}, d {d}"
        );
    }
    assert!(
        edge_ties > 0,
        "the scene should have pixels with x − d = 0 exactly"
    );
}
