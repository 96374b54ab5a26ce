//! Hills around towns (`town::terrain`): exactly flat on roads and blocks,
//! continuous, deterministic per seed, reaching the configured height, with
//! a finite mesh and hill trees standing on the ground (on the hills plus
//! the town's ground field when it has one); bad keys are named.

use std::path::Path;

use parallax::scene::desc::ShapeDesc;
use parallax::town::layout::Layout;
use parallax::town::terrain::{Terrain, FLAT_M, GROUND_Z, TERRAIN_NAME};
use parallax::town::{load_town_frame, parse_town_str, CameraConfig, TownDesc};

use crate::common;
use common::towns::town;

fn hills(seed: u64) -> (TownDesc, Layout, Terrain) {
    let desc = town("town04");
    let l = Layout::new(&desc);
    let t = Terrain::new(&desc, &l, seed).expect("town04 has hills");
    (desc, l, t)
}

/// Points on a regular lattice over `r`, `n` per side.
fn lattice(min: [f64; 2], max: [f64; 2], n: usize) -> impl Iterator<Item = [f64; 2]> {
    (0..=n).flat_map(move |j| {
        (0..=n).map(move |i| {
            let (u, v) = (i as f64 / n as f64, j as f64 / n as f64);
            [
                min[0] + u * (max[0] - min[0]),
                min[1] + v * (max[1] - min[1]),
            ]
        })
    })
}

#[test]
fn terrain_is_exactly_flat_on_roads_blocks_and_their_margin() {
    let (_, l, t) = hills(3);
    let mut rects = l.road_rects();
    for j in 0..l.ny {
        for i in 0..l.nx {
            rects.push(l.block_interior(i, j));
        }
    }
    let b = l.bounds();
    rects.push(b);
    for r in &rects {
        for p in lattice(r.min, r.max, 40) {
            assert_eq!(t.height_m(p[0], p[1]), 0.0, "height at {p:?} in {r:?}");
        }
    }
    // Just inside the flat margin around the town it is still 0.
    let m = FLAT_M - 0.01;
    for p in lattice([b.min[0], b.min[1] - m], [b.max[0], b.min[1] - m], 200) {
        assert_eq!(t.height_m(p[0], p[1]), 0.0, "height at {p:?}");
    }
}

#[test]
fn terrain_is_continuous_without_steps() {
    let (_, l, t) = hills(3);
    let b = l.bounds();
    // Scan lines across the blend into the hills on every side: a 0.25 m
    // step never changes the height by more than a 1:1 slope would.
    let h = 0.25;
    let lines = [
        ([b.min[0] - 400.0, 250.0], [1.0, 0.0]),
        ([b.max[0], 100.0], [1.0, 0.0]),
        ([300.0, b.min[1] - 400.0], [0.0, 1.0]),
        ([700.0, b.max[1]], [0.0, 1.0]),
    ];
    let mut rose = 0.0f64;
    for (start, dir) in lines {
        let mut prev = t.height_m(start[0], start[1]);
        for k in 1..=(400.0 / h) as usize {
            let s = k as f64 * h;
            let z = t.height_m(start[0] + dir[0] * s, start[1] + dir[1] * s);
            assert!((z - prev).abs() <= h, "step {} at {start:?}+{s}", z - prev);
            rose = rose.max(z);
            prev = z;
        }
    }
    assert!(
        rose > 10.0,
        "the scans never left the flat ground: max {rose}"
    );
}

#[test]
fn terrain_is_deterministic_per_seed() {
    let (a, b, c) = (hills(3).2, hills(3).2, hills(4).2);
    let ma = a.mesh();
    let mb = b.mesh();
    assert_eq!(ma.positions, mb.positions);
    assert_eq!(ma.triangles, mb.triangles);
    let p = [-200.0, -200.0];
    assert_ne!(a.height_m(p[0], p[1]), c.height_m(p[0], p[1]));
}

#[test]
fn hills_reach_the_configured_amplitude_and_mesh_is_finite() {
    let (desc, _, t) = hills(11);
    let m = t.mesh();
    assert!(!m.triangles.is_empty());
    assert!(
        m.triangles.len() < 2_000_000,
        "{} triangles",
        m.triangles.len()
    );
    assert_eq!(m.normals.len(), m.positions.len());
    let mut top = f64::NEG_INFINITY;
    for (p, n) in m.positions.iter().zip(&m.normals) {
        assert!(p.is_finite() && n.is_finite(), "vertex {p} normal {n}");
        assert!((n.length() - 1.0).abs() < 1e-9 && n.z > 0.0, "normal {n}");
        assert!(p.z >= GROUND_Z && p.z <= desc.hills_m + GROUND_Z + 1e-9);
        // The vertex lies on the height function.
        assert!((p.z - GROUND_Z - t.height_m(p.x, p.y)).abs() < 1e-9);
        top = top.max(p.z - GROUND_Z);
    }
    assert!((top - desc.hills_m).abs() < 1e-9, "highest vertex {top}");
    // Triangles face up (counter-clockwise from above).
    for tri in m.triangles.iter().step_by(97) {
        let [a, b, c] = tri.map(|i| m.positions[i as usize]);
        assert!((b - a).cross(c - a).z > 0.0);
    }
}

#[test]
fn flat_towns_have_no_terrain_and_bad_hill_keys_are_named() {
    let desc = town("town01");
    assert_eq!(desc.hills_m, 0.0);
    assert!(Terrain::new(&desc, &Layout::new(&desc), 0).is_none());
    let text =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/town04.toml"))
            .unwrap();
    for (key, bad) in [("hills_m", "-5.0"), ("hill_wavelength_m", "10.0")] {
        let edited: String = text
            .lines()
            .map(|line| {
                if line.starts_with(&format!("{key} =")) {
                    format!("{key} = {bad}\n")
                } else {
                    format!("{line}\n")
                }
            })
            .collect();
        let e = parse_town_str(&edited, Path::new("t.toml")).unwrap_err();
        assert!(e.contains(key), "{e}");
    }
}

#[test]
fn hill_trees_stand_on_the_terrain_and_the_frame_carries_the_mesh() {
    let (desc, l, t) = hills(5);
    let b = l.bounds();
    let objects = parallax::town::static_objects(&desc, 5);
    // Town04 also rolls (`road_grade_m`): the hills ride its ground field.
    let field = parallax::town::grade::Grade::new(&desc, 5);
    let mut on_hills = 0;
    for o in &objects {
        let p = o.transform.translate.unwrap_or_default();
        let outside = p[0] < b.min[0] || p[0] > b.max[0] || p[1] < b.min[1] || p[1] > b.max[1];
        if o.semantic.as_deref() == Some("vegetation") && outside {
            let base = field.map_or(0.0, |g| g.height_m(p[0], p[1]));
            let ground = t.height_m(p[0], p[1]) + GROUND_Z + base;
            assert!((p[2] - (ground - 0.15)).abs() < 1e-9, "tree at {p:?}");
            on_hills += 1;
        }
    }
    assert!(on_hills > 100, "only {on_hills} hill trees");
    let loaded = load_town_frame(&desc, 5, 0, CameraConfig::Normal, Path::new("t.toml")).unwrap();
    let hill = loaded
        .desc
        .objects
        .iter()
        .find(|o| o.name.as_deref() == Some(TERRAIN_NAME))
        .expect("the frame carries the terrain mesh");
    let ShapeDesc::Mesh { triangles, .. } = &hill.shape else {
        panic!("terrain is not an inline mesh")
    };
    assert_eq!(triangles, &t.mesh().triangles);
    assert_eq!(hill.semantic.as_deref(), Some("terrain"));
    assert_eq!(hill.material.as_deref(), Some("ground"));
}
