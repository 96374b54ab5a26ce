//! The organic warp: Jacobian, bounds (near-rotation, lane widths),
//! inverse, headings and the bending of static objects.

use super::bend::{bend_meshes, bend_objects};
use super::*;
use crate::scene::desc::ShapeDesc;
use crate::town::parts::{class, ground_quad, slab};

fn town07() -> TownDesc {
    crate::town::parse_town_str(
        &std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/town07.toml"))
            .unwrap(),
        std::path::Path::new("town07.toml"),
    )
    .unwrap()
}

fn warps() -> Vec<Warp> {
    let d = town07();
    (0..6).map(|s| Warp::new(&d, s).unwrap()).collect()
}

/// Points over a 1.6 × 1.2 km square (a town and its surroundings).
fn points() -> impl Iterator<Item = [f64; 2]> {
    (0..60).flat_map(|i| (0..45).map(move |j| [i as f64 * 27.3 - 400.0, j as f64 * 26.9 - 300.0]))
}

#[test]
fn only_organic_towns_warp_and_the_warp_is_seeded() {
    let mut d = town07();
    let (a, b) = (Warp::new(&d, 1).unwrap(), Warp::new(&d, 2).unwrap());
    assert_ne!(a, b);
    assert_eq!(Warp::new(&d, 1), Some(a));
    d.road_style = RoadStyle::Grid;
    assert_eq!(Warp::new(&d, 1), None);
}

#[test]
fn jacobian_matches_central_differences_and_keeps_area() {
    for w in warps() {
        for p in points() {
            let e = 1e-4;
            let f = |dx: f64, dy: f64| w.map([p[0] + dx, p[1] + dy]);
            let (xp, xm, yp, ym) = (f(e, 0.0), f(-e, 0.0), f(0.0, e), f(0.0, -e));
            let j = w.jacobian(p);
            for r in 0..2 {
                assert!((j[r][0] - (xp[r] - xm[r]) / (2.0 * e)).abs() < 1e-7);
                assert!((j[r][1] - (yp[r] - ym[r]) / (2.0 * e)).abs() < 1e-7);
            }
            // Area kept: the determinant of the map's own differences.
            let d = |a: [f64; 2], b: [f64; 2], r: usize| (a[r] - b[r]) / (2.0 * e);
            let det = d(xp, xm, 0) * d(yp, ym, 1) - d(yp, ym, 0) * d(xp, xm, 1);
            assert!((det - 1.0).abs() < 1e-6, "{det}");
        }
    }
}

#[test]
fn jacobian_stays_near_a_rotation_and_lanes_keep_their_width() {
    let s = MAX_SHEAR;
    // Bounds from the module header for |a′|, |b′| ≤ s.
    let stretch = ((1.0 + s * s).powi(2) + s * s).sqrt();
    let (mut widest_turn, mut narrowest, mut largest): (f64, f64, f64) = (0.0, 1.0, 1.0);
    for w in warps() {
        assert!(w.max_shear() <= s + 1e-12);
        for p in points() {
            let [[a, b], [c, d]] = w.jacobian(p);
            // Singular values of J: √ of the eigenvalues of JᵀJ.
            let (p11, p12, p22) = (a * a + c * c, a * b + c * d, b * b + d * d);
            let (m, r) = (
                (p11 + p22) / 2.0,
                (((p11 - p22) / 2.0).powi(2) + p12 * p12).sqrt(),
            );
            let (hi, lo) = ((m + r).sqrt(), (m - r).sqrt());
            // Near a rotation: J = R·S; S's largest stretch hi peaks where
            // a′ = b′ = ±s: tr JᵀJ = (1 + s²)² + 2s² + 1 = T and hi² =
            // T/2 + √(T²/4 − 1) (≈ 1 + s); lo = 1/hi since det J = 1.
            let t = (1.0 + s * s).powi(2) + 2.0 * s * s + 1.0;
            let bound = (t / 2.0 + (t * t / 4.0 - 1.0).sqrt()).sqrt();
            assert!(bound < 1.17);
            assert!(
                hi <= bound + 1e-12 && (lo * hi - 1.0).abs() < 1e-12,
                "{hi} {lo}"
            );
            largest = largest.max(hi);
            // Widths of x-roads and y-roads: 1 / |J·t| (area kept).
            let wx = 1.0 / a.hypot(c);
            let wy = 1.0 / b.hypot(d);
            assert!(wx >= 1.0 / stretch - 1e-12 && wy >= 1.0 / stretch - 1e-12);
            let widest = (1.0 + s * s).sqrt();
            assert!(wx <= widest + 1e-12 && wy <= widest + 1e-12);
            narrowest = narrowest.min(wx).min(wy);
            assert!(1.0 - 1.0 / stretch < 0.034 && widest < 1.012);
            for h in [0.0, 90.0, 180.0, 270.0] {
                let t = (w.heading_deg(p, h) - h).abs();
                assert!(t <= (s / (1.0 - s * s)).atan().to_degrees() + 1e-9, "{t}");
                widest_turn = widest_turn.max(t);
            }
        }
    }
    // The warp really bends: headings turn by several degrees somewhere.
    assert!(widest_turn > 5.0, "{widest_turn}");
    assert!(narrowest < 0.995 && largest > 1.05, "{narrowest} {largest}");
}

#[test]
fn streets_curve_visibly_with_a_bounded_radius() {
    for w in warps() {
        // The x-road y = 0 over 400 m: its largest sideways deviation from
        // the chord between its ends.
        let ends = [w.map([0.0, 0.0]), w.map([400.0, 0.0])];
        let (dx, dy) = (ends[1][0] - ends[0][0], ends[1][1] - ends[0][1]);
        let len = dx.hypot(dy);
        let off = (0..=400)
            .map(|i| {
                let q = w.map([i as f64, 0.0]);
                ((q[0] - ends[0][0]) * dy - (q[1] - ends[0][1]) * dx).abs() / len
            })
            .fold(0.0, f64::max);
        assert!(off > 2.0, "x-road sags only {off} m");
        // Radius ≥ 1 / max_bend ≥ 280 m (a gentle country curve), checked
        // on the bent road by the turn of its heading per metre.
        assert!(w.max_bend() < 1.0 / 280.0, "{}", w.max_bend());
        for i in 0..400 {
            let turn =
                w.heading_deg([i as f64 + 1.0, 0.0], 0.0) - w.heading_deg([i as f64, 0.0], 0.0);
            let run = {
                let (p, q) = (w.map([i as f64, 0.0]), w.map([i as f64 + 1.0, 0.0]));
                (q[0] - p[0]).hypot(q[1] - p[1])
            };
            assert!(turn.to_radians().abs() / run < 1.0 / 250.0);
        }
    }
}

#[test]
fn inverse_and_heading_round_trip() {
    for w in warps() {
        for p in points() {
            let q = w.unmap(w.map(p));
            assert!((q[0] - p[0]).abs() < 1e-9 && (q[1] - p[1]).abs() < 1e-9);
            for h in [0.0, 37.0, 90.0, 180.0, 270.0, 359.0] {
                let back = w.heading_back_deg(p, w.heading_deg(p, h));
                assert!((back - h).abs() < 1e-9, "{h} → {back}");
            }
        }
    }
}

#[test]
fn bent_pieces_follow_the_warp_and_buildings_stay_rigid() {
    let w = warps()[0];
    let road = ground_quad([0.0, -7.0], [60.0, 7.0], 0.0, "asphalt", class("road"));
    let line = slab(
        [0.0, -0.06],
        [60.0, 0.06],
        0.0,
        0.008,
        "paint",
        class("road_line"),
    );
    let mut house = slab(
        [20.0, 20.0],
        [30.0, 28.0],
        0.0,
        6.0,
        "brick",
        class("building"),
    );
    house.instance = Some(1000);
    let mut roof = slab(
        [21.0, 21.0],
        [29.0, 27.0],
        6.0,
        7.0,
        "tile",
        class("building"),
    );
    roof.instance = Some(1000);
    let out = bend_objects(vec![road, line, house.clone(), roof.clone()], &w, 10.0);
    assert_eq!(out.len(), 4);
    let ShapeDesc::Mesh {
        positions,
        triangles,
        ..
    } = &out[0].shape
    else {
        panic!("road not bent")
    };
    // 60 × 14 m in ≤ 10 m pieces: 6 × 2 cells, every vertex at W(level).
    assert_eq!(triangles.len(), 2 * 6 * 2);
    for p in positions {
        let l = w.unmap([p[0], p[1]]);
        assert!(l[0] > -1e-9 && l[0] < 60.0 + 1e-9 && l[1].abs() < 7.0 + 1e-9);
        let on_grid = |v: f64, step: f64| ((v / step).round() * step - v).abs() < 1e-9;
        assert!(on_grid(l[0], 10.0) && on_grid(l[1], 7.0), "{l:?}");
        assert_eq!(p[2], 0.0);
    }
    // The house's parts keep their distance and relative turn.
    let at = |o: &crate::scene::desc::ObjectDesc| o.transform.translate.unwrap();
    let gap = |a: [f64; 3], b: [f64; 3]| (a[0] - b[0]).hypot(a[1] - b[1]);
    let before = gap(at(&house), at(&roof));
    assert!((gap(at(&out[2]), at(&out[3])) - before).abs() < 1e-9);
    let turn = w.rotation_deg([25.0, 24.0]);
    for o in &out[2..] {
        assert!((o.transform.rotate_deg.unwrap()[2] - turn).abs() < 1e-9);
    }
    let h = at(&out[2]);
    let target = w.map([25.0, 24.0]);
    assert!((h[0] - target[0]).abs() < 1e-9 && (h[1] - target[1]).abs() < 1e-9);
    // Generated meshes: vertices at W, normals of a tilted plane by J⁻ᵀ.
    let mut hill = vec![crate::scene::desc::ObjectDesc {
        shape: ShapeDesc::Mesh {
            positions: vec![[0.0, 0.0, 0.0], [10.0, 0.0, 1.0], [0.0, 10.0, 0.0]],
            normals: vec![[-0.1, 0.0, 1.0]; 3],
            triangles: vec![[0, 1, 2]],
        },
        ..out[0].clone()
    }];
    bend_meshes(&mut hill, &w);
    let ShapeDesc::Mesh {
        positions, normals, ..
    } = &hill[0].shape
    else {
        unreachable!()
    };
    for (p, n) in positions.iter().zip(normals) {
        let l = w.unmap([p[0], p[1]]);
        // The plane z = 0.1·x of the level points: the bent normal is
        // perpendicular to W's image of the plane's tangents.
        let j = w.jacobian(l);
        let tx = [j[0][0], j[1][0], 0.1];
        let ty = [j[0][1], j[1][1], 0.0];
        let dot = |a: [f64; 3], b: &[f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        assert!(dot(tx, n).abs() < 1e-12 && dot(ty, n).abs() < 1e-12);
    }
}
