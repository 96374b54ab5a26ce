//! Organic towns (`road_style = "organic"`, town07): the bent town builds
//! and validates, its roads lie where the warp takes the level roads, its
//! vehicles stay on the bent roads and never overlap over a long horizon
//! (frames 0–400 and 20 000–20 100, exact rectangle test in the bent
//! world), their speed stays within the warp's stretch of the speed limit,
//! and everything is deterministic and seeded.

use parallax::scene::desc::ShapeDesc;
use parallax::town::layout::{Layout, Rect};
use parallax::town::organic::{Warp, MAX_SHEAR};
use parallax::town::{frame_at, load_town_frame, static_objects, CameraConfig, TownFrame};

use crate::common;
use common::towns::{town, town_file};

/// Largest stretch of a length along a street (module header of `organic`).
fn max_stretch() -> f64 {
    let s = MAX_SHEAR;
    ((1.0 + s * s).powi(2) + s * s).sqrt()
}

/// Whether the two vehicles' rectangles overlap (separating axes of both).
fn overlap(a: &[[f64; 2]; 4], b: &[[f64; 2]; 4]) -> bool {
    for poly in [a, b] {
        for k in 0..4 {
            let (p, q) = (poly[k], poly[(k + 1) % 4]);
            let n = [q[1] - p[1], p[0] - q[0]];
            let span = |v: &[[f64; 2]; 4]| {
                let d: Vec<f64> = v.iter().map(|c| c[0] * n[0] + c[1] * n[1]).collect();
                (
                    d.iter().copied().fold(f64::MAX, f64::min),
                    d.iter().copied().fold(f64::MIN, f64::max),
                )
            };
            let ((a0, a1), (b0, b1)) = (span(a), span(b));
            if a1 <= b0 + 1e-9 || b1 <= a0 + 1e-9 {
                return false;
            }
        }
    }
    true
}

fn check_frame(f: &TownFrame, w: &Warp, roads: &[Rect]) {
    let all: Vec<_> = std::iter::once(&f.ego).chain(&f.vehicles).collect();
    for (i, a) in all.iter().enumerate() {
        for b in &all[i + 1..] {
            assert!(
                !overlap(&a.corners(), &b.corners()),
                "frame {}: vehicles {} and {} overlap",
                f.frame,
                a.id,
                b.id
            );
        }
        // Every bent corner, carried back to the level grid, lies on a road.
        for c in a.corners() {
            let l = w.unmap(c);
            let at = Rect::centered(l, [0.0, 0.0]);
            assert!(
                roads.iter().any(|r| r.contains(&at, 1e-6)),
                "frame {}: vehicle {} leaves the bent road at {c:?} (level {l:?})",
                f.frame,
                a.id
            );
        }
    }
}

#[test]
fn organic_vehicles_stay_on_the_bent_roads_and_never_overlap() {
    let desc = town("town07");
    let w = Warp::new(&desc, 11).expect("town07 is organic");
    let roads = Layout::new(&desc).road_rects();
    let v_max = desc.speed_kmh / 3.6 / desc.fps;
    let (mut fastest, mut worst, mut bent): (f64, f64, usize) = (0.0, 0.0, 0);
    for range in [0..400u64, 20_000..20_100] {
        let mut prev: Option<TownFrame> = None;
        for k in range {
            let f = frame_at(&desc, 11, k);
            check_frame(&f, &w, &roads);
            let Some(p) = &prev else {
                prev = Some(f);
                continue;
            };
            let pairs = f.vehicles.iter().zip(&p.vehicles);
            for (a, b) in pairs.filter(|(a, b)| a.id == b.id) {
                let d = [a.position[0] - b.position[0], a.position[1] - b.position[1]];
                let step = d[0].hypot(d[1]);
                fastest = fastest.max(step);
                if step < 0.5 * v_max {
                    continue;
                }
                // A moving vehicle faces where it goes: the chord between
                // two frames runs along the mean of its two headings (exact
                // on a circular arc), independently of how W turns headings.
                let turn = (a.heading_deg - b.heading_deg + 540.0).rem_euclid(360.0) - 180.0;
                let mean = b.heading_deg + turn / 2.0;
                let chord = d[1].atan2(d[0]).to_degrees();
                let off = (chord - mean + 540.0).rem_euclid(360.0) - 180.0;
                worst = worst.max(off.abs());
                // Off the grid's four directions on a straight: bent.
                let grid = (a.heading_deg.rem_euclid(90.0) + 45.0).rem_euclid(90.0) - 45.0;
                bent += usize::from(turn.abs() < 1.0 && grid.abs() > 2.0);
            }
            prev = Some(f);
        }
    }
    assert!(
        fastest <= v_max * max_stretch() + 1e-9,
        "{fastest} > {v_max}"
    );
    assert!(fastest > 0.9 * v_max, "{fastest}");
    assert!(worst < 1.0, "a vehicle moves {worst}° off its heading");
    assert!(bent > 100, "only {bent} vehicle steps on bent straights");
}

#[test]
fn organic_town_builds_bent_roads_and_is_deterministic() {
    let desc = town("town07");
    let w = Warp::new(&desc, 3).unwrap();
    let loaded = load_town_frame(&desc, 3, 0, CameraConfig::Normal, &town_file("town07"))
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(loaded.triangle_estimate > 0);
    let objects = static_objects(&desc, 3);
    assert_eq!(objects, static_objects(&desc, 3));
    assert_ne!(objects, static_objects(&desc, 4));
    assert_eq!(frame_at(&desc, 3, 77), frame_at(&desc, 3, 77));
    // Every road vertex carried back lies on the level road grid (the
    // asphalt's own rectangles, within the bend's cut error).
    let roads = Layout::new(&desc).road_rects();
    let mut vertices = 0;
    for o in objects
        .iter()
        .filter(|o| o.semantic.as_deref() == Some("road"))
    {
        let ShapeDesc::Mesh { positions, .. } = &o.shape else {
            panic!("a long road piece was not bent: {o:?}")
        };
        for p in positions {
            let at = Rect::centered(w.unmap([p[0], p[1]]), [0.0, 0.0]);
            assert!(roads.iter().any(|r| r.contains(&at, 1e-6)), "{p:?}");
            vertices += 1;
        }
    }
    assert!(vertices > 500, "{vertices}");
}

#[test]
fn organic_towns_refuse_ramps_and_overpass_by_name() {
    let text = std::fs::read_to_string(town_file("town07")).unwrap();
    let bad = format!("{text}\nramps = true\n");
    let err = parallax::town::parse_town_str(&bad, std::path::Path::new("t.toml")).unwrap_err();
    assert!(
        err.starts_with("t.toml: road_style: \"organic\"") && err.contains("ramps = true"),
        "{err}"
    );
}

/// Radius of the circle through three points, metres (∞ on a line).
fn circumradius(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    let d = |p: [f64; 2], q: [f64; 2]| (p[0] - q[0]).hypot(p[1] - q[1]);
    let cross = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    d(a, b) * d(b, c) * d(c, a) / (2.0 * cross.abs())
}

/// Town03's roundabout bent by the warp of 300 seeds stays drivable: W of
/// each ring lane's centre circle turns no tighter than `MIN_RADIUS_SHARE`
/// of its level radius (near a point W is about linear, and an ellipse of
/// J's stretch σ ≤ 1.16 has radii ≥ r/σ³ ≈ 0.64 r), and the ring's lanes
/// keep their width within `MIN_WIDTH_SHARE` … 1 / `MIN_WIDTH_SHARE`
/// (J's stretches 1/σ … σ). The ring must bend at all (guard).
#[test]
fn town03_roundabout_stays_round_enough_to_drive_under_every_warp() {
    const MIN_RADIUS_SHARE: f64 = 0.6;
    const MIN_WIDTH_SHARE: f64 = 0.85;
    let desc = town("town03");
    let l = Layout::new(&desc);
    let c = l.roundabout_center().unwrap();
    let (r_in, r_out) = l.roundabout_radii();
    let lane = (r_out - r_in) / l.lanes as f64;
    let n = 720;
    let circle = |w: &Warp, r: f64| -> Vec<[f64; 2]> {
        (0..n)
            .map(|i| {
                let t = i as f64 * std::f64::consts::TAU / n as f64;
                w.map([c[0] + r * t.cos(), c[1] + r * t.sin()])
            })
            .collect()
    };
    let (mut tightest, mut narrowest, mut widest) = (f64::MAX, f64::MAX, 0.0f64);
    for seed in 0..300 {
        let w = Warp::new(&desc, seed).unwrap();
        for k in 0..l.lanes {
            let r = r_in + (k as f64 + 0.5) * lane;
            let p = circle(&w, r);
            for i in 0..n {
                let rc = circumradius(p[(i + n - 1) % n], p[i], p[(i + 1) % n]);
                tightest = tightest.min(rc / r);
            }
        }
        // Lane width: from each point of one bent lane edge to the nearest
        // point of the next (its neighbours within ±0.3 rad).
        for k in 0..l.lanes {
            let (a, b) = (r_in + k as f64 * lane, r_in + (k + 1) as f64 * lane);
            let (pa, pb) = (circle(&w, a), circle(&w, b));
            for (i, q) in pa.iter().enumerate() {
                let near = (i + n - 40..i + n + 40)
                    .map(|j| {
                        let p = pb[j % n];
                        (p[0] - q[0]).hypot(p[1] - q[1])
                    })
                    .fold(f64::MAX, f64::min);
                narrowest = narrowest.min(near / lane);
                widest = widest.max(near / lane);
            }
        }
    }
    println!(
        "town03 ring over 300 warps: tightest lane radius {tightest:.3} r, \
         lane width {narrowest:.3} … {widest:.3} of {lane} m"
    );
    assert!(tightest >= MIN_RADIUS_SHARE, "{tightest}");
    assert!(tightest < 0.8, "the ring never bends: {tightest}");
    assert!(narrowest >= MIN_WIDTH_SHARE, "{narrowest}");
    assert!(widest <= 1.0 / MIN_WIDTH_SHARE, "{widest}");
}

/// Town03's ring curbs (island drum and outer kerb) and island lawn are
/// bent vertex by vertex: carried back by W⁻¹, every vertex lies on one of
/// their level circles (a rigid drum would leave the bent ring's inner
/// edge and cover the inner lane where W squeezes the ring).
#[test]
fn town03_ring_curbs_and_island_follow_the_warp_vertex_by_vertex() {
    let desc = town("town03");
    let l = Layout::new(&desc);
    let c = l.roundabout_center().unwrap();
    let (r_in, r_out) = l.roundabout_radii();
    for seed in [0, 5] {
        let w = Warp::new(&desc, seed).unwrap();
        let (mut curb, mut lawn) = (0, 0);
        for o in static_objects(&desc, seed) {
            let ShapeDesc::Mesh { positions, .. } = &o.shape else {
                continue;
            };
            let radii: Vec<f64> = positions
                .iter()
                .map(|p| {
                    let q = w.unmap([p[0], p[1]]);
                    (q[0] - c[0]).hypot(q[1] - c[1])
                })
                .collect();
            if radii.iter().any(|&r| r > r_out + 10.0) {
                continue;
            }
            let (want, count) = match o.material.as_deref() {
                Some("curb") => (vec![0.0, r_in, r_out, r_out + 0.25], &mut curb),
                Some("lawn") => (vec![0.0, r_in - 0.3], &mut lawn),
                _ => continue,
            };
            for r in radii {
                assert!(
                    want.iter().any(|v| (r - v).abs() < 1e-6),
                    "seed {seed}: a {:?} vertex at level radius {r}",
                    o.material
                );
                *count += 1;
            }
        }
        // The drum (2 · 64 side and 2 · 65 cap vertices) and the kerb arcs;
        // the lawn's drum.
        assert!(curb > 258 && lawn == 258, "seed {seed}: {curb} {lawn}");
    }
}
