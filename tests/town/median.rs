//! The divided highways of `highway` towns (town04, town06): the median
//! barrier stands on every outer road's centreline with the New Jersey
//! profile, through the T junctions and round the curved corners but not
//! across the square corners' junctions; it is a closed solid; no ego drive
//! and no background route crosses it.

use std::f64::consts::FRAC_PI_2;

use glam::DVec3;
use parallax::scene::desc::ShapeDesc;
use parallax::town::grade::Grade;
use parallax::town::layout::{Layout, STUB_M};
use parallax::town::rng::Rng;
use parallax::town::roads::median::{median_meshes, MEDIAN_NAME};
use parallax::town::routes::drive::{links, DrivePath};
use parallax::town::routes::{routes, RouteKind, Turns};
use parallax::town::StaticTown;

use crate::common::towns::town;

/// The barrier's New Jersey section, written out here: foot half-width,
/// reveal height, the slope break, the top half-width and height, and
/// how deep the foot is sunk (metres).
const FOOT: f64 = 0.305;
const REVEAL: f64 = 0.075;
const BREAK: (f64, f64) = (0.1265, 0.33);
const TOP: (f64, f64) = (0.076, 0.81);
const SINK: f64 = 0.05;

/// Triangles of the barrier mesh of a level layout.
fn triangles(l: &Layout) -> Vec<[DVec3; 3]> {
    let m = median_meshes(l);
    assert_eq!(m.len(), 1);
    let ShapeDesc::Mesh {
        positions,
        triangles,
        ..
    } = &m[0].shape
    else {
        panic!("the barrier is not a mesh")
    };
    triangles
        .iter()
        .map(|t| t.map(|i| DVec3::from_array(positions[i as usize])))
        .collect()
}

/// Highest point of the mesh above (x, y), if any (a ray straight down).
fn top_z(tris: &[[DVec3; 3]], x: f64, y: f64) -> Option<f64> {
    let mut best: Option<f64> = None;
    for [a, b, c] in tris {
        // Barycentric coordinates of (x, y) in the triangle's plan.
        let d = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
        if d.abs() < 1e-12 {
            continue; // a vertical face
        }
        let u = ((x - a.x) * (c.y - a.y) - (c.x - a.x) * (y - a.y)) / d;
        let v = ((b.x - a.x) * (y - a.y) - (x - a.x) * (b.y - a.y)) / d;
        if u < -1e-12 || v < -1e-12 || u + v > 1.0 + 1e-12 {
            continue;
        }
        let z = a.z + u * (b.z - a.z) + v * (c.z - a.z);
        best = Some(best.map_or(z, |m: f64| m.max(z)));
    }
    best
}

/// Where the barrier must stand, from the layout's numbers: straights as
/// (from, to) and arcs as (centre, θ0) quarter circles of the loop radius.
struct Expected {
    lines: Vec<([f64; 2], [f64; 2])>,
    arcs: Vec<([f64; 2], f64)>,
    r: f64,
}

fn expected(l: &Layout) -> Expected {
    let (p, hw, r) = (l.pitch_m, l.road_w_m / 2.0, l.loop_radius_m);
    let (lx, ly) = (l.nx as f64 * p, l.ny as f64 * p);
    let mut lines = Vec::new();
    let mut arcs = Vec::new();
    for y in [0.0, ly] {
        if r > 0.0 {
            lines.push(([r, y], [lx - r, y]));
        } else {
            // Stubs, the straight between the corner junctions' boxes.
            lines.push(([-STUB_M, y], [-hw, y]));
            lines.push(([hw, y], [lx - hw, y]));
            lines.push(([lx + hw, y], [lx + STUB_M, y]));
        }
    }
    for x in [0.0, lx] {
        let (a, b) = if r > 0.0 { (r, ly - r) } else { (hw, ly - hw) };
        lines.push(([x, a], [x, b]));
    }
    if r > 0.0 {
        // Centres R in from the corners; each arc faces its corner.
        arcs.push(([r, r], 2.0 * FRAC_PI_2));
        arcs.push(([lx - r, r], 3.0 * FRAC_PI_2));
        arcs.push(([r, ly - r], FRAC_PI_2));
        arcs.push(([lx - r, ly - r], 0.0));
    }
    Expected { lines, arcs, r }
}

impl Expected {
    /// Distance in plan from the nearest barrier centreline, metres.
    fn distance(&self, q: [f64; 2]) -> f64 {
        let mut d = f64::INFINITY;
        for (a, b) in &self.lines {
            let ab = [b[0] - a[0], b[1] - a[1]];
            let len2 = ab[0] * ab[0] + ab[1] * ab[1];
            let t = (((q[0] - a[0]) * ab[0] + (q[1] - a[1]) * ab[1]) / len2).clamp(0.0, 1.0);
            let c = [a[0] + t * ab[0], a[1] + t * ab[1]];
            d = d.min((q[0] - c[0]).hypot(q[1] - c[1]));
        }
        for (c, t0) in &self.arcs {
            let ang = (q[1] - c[1]).atan2(q[0] - c[0]);
            let rel = (ang - t0).rem_euclid(4.0 * FRAC_PI_2);
            if rel <= FRAC_PI_2 {
                d = d.min(((q[0] - c[0]).hypot(q[1] - c[1]) - self.r).abs());
            }
        }
        d
    }
}

/// Height of the profile at half-width |o| (below the top: on its faces).
fn profile_z(o: f64) -> f64 {
    let o = o.abs();
    if o <= TOP.0 {
        TOP.1
    } else if o <= BREAK.0 {
        BREAK.1 + (BREAK.0 - o) / (BREAK.0 - TOP.0) * (TOP.1 - BREAK.1)
    } else {
        REVEAL + (FOOT - o) / (FOOT - BREAK.0) * (BREAK.1 - REVEAL)
    }
}

#[test]
fn median_barrier_stands_on_every_highway_centreline_with_the_jersey_profile() {
    for name in ["town04", "town06"] {
        let l = Layout::new(&town(name));
        let tris = triangles(&l);
        let e = expected(&l);
        let mut checked = 0;
        for (a, b) in &e.lines {
            let len = (b[0] - a[0]).hypot(b[1] - a[1]);
            let u = [(b[0] - a[0]) / len, (b[1] - a[1]) / len];
            let n = [-u[1], u[0]];
            let mut s = 0.37;
            while s < len - 0.37 {
                for o in [0.0, 0.05, -0.1, 0.2, -0.28] {
                    let q = [a[0] + s * u[0] + o * n[0], a[1] + s * u[1] + o * n[1]];
                    let z = top_z(&tris, q[0], q[1]).expect("barrier missing");
                    assert!(
                        (z - profile_z(o)).abs() < 1e-9,
                        "{name} at {q:?} (offset {o}): z {z}, want {}",
                        profile_z(o)
                    );
                    checked += 1;
                }
                // Nothing beyond the foot.
                let q = [a[0] + s * u[0] + 0.32 * n[0], a[1] + s * u[1] + 0.32 * n[1]];
                assert_eq!(top_z(&tris, q[0], q[1]), None, "{name} at {q:?}");
                s += 7.3;
            }
        }
        for (c, t0) in &e.arcs {
            for k in 1..20 {
                let t = t0 + FRAC_PI_2 * k as f64 / 20.0;
                let q = [c[0] + e.r * t.cos(), c[1] + e.r * t.sin()];
                let z = top_z(&tris, q[0], q[1]).expect("barrier missing on the curve");
                assert!((z - TOP.1).abs() < 1e-9, "{name} curve at {q:?}: {z}");
                let out = [c[0] + (e.r + 0.4) * t.cos(), c[1] + (e.r + 0.4) * t.sin()];
                assert_eq!(top_z(&tris, out[0], out[1]), None);
            }
        }
        assert!(checked > 1000, "{name}: {checked}");
        // Through the T junctions where town streets meet the highway (its
        // centre); none on the town's own streets.
        let p = l.pitch_m;
        assert!(top_z(&tris, p, 0.0).is_some(), "{name}: T junction (1, 0)");
        assert!(top_z(&tris, p, l.ny as f64 * p).is_some());
        assert_eq!(top_z(&tris, p, p / 2.0), None, "{name}: y-road 1");
        if l.ny > 1 {
            assert!(top_z(&tris, 0.0, p).is_some(), "{name}: T junction (0, 1)");
            assert_eq!(top_z(&tris, p / 2.0, p), None, "{name}: x-road 1");
        }
        // The square corners' junctions are open (the ring turns there).
        if l.loop_radius_m == 0.0 {
            assert_eq!(top_z(&tris, 0.0, 0.0), None, "{name}: corner (0, 0)");
            let lx = l.nx as f64 * p;
            assert_eq!(top_z(&tris, lx, l.ny as f64 * p), None);
        }
    }
}

#[test]
fn median_barrier_is_a_closed_outward_solid_of_the_sections_volume() {
    let l = Layout::new(&town("town06"));
    let tris = triangles(&l);
    // Every directed edge once, and its reverse once: closed and oriented.
    let key = |p: DVec3| p.to_array().map(|c| (c * 1e6).round() as i64);
    let mut edges = std::collections::BTreeMap::new();
    for t in &tris {
        for k in 0..3 {
            *edges.entry((key(t[k]), key(t[(k + 1) % 3]))).or_insert(0) += 1;
        }
    }
    for (&(a, b), &n) in &edges {
        assert_eq!(n, 1, "edge {a:?}-{b:?} used {n} times");
        assert_eq!(edges.get(&(b, a)), Some(&1), "edge {a:?}-{b:?} open");
    }
    // Signed volume (divergence theorem) = section area × total length.
    let vol: f64 = tris.iter().map(|[a, b, c]| a.dot(b.cross(*c)) / 6.0).sum();
    let section = [
        (-FOOT, -SINK),
        (-FOOT, REVEAL),
        (-BREAK.0, BREAK.1),
        (-TOP.0, TOP.1),
        (TOP.0, TOP.1),
        (BREAK.0, BREAK.1),
        (FOOT, REVEAL),
        (FOOT, -SINK),
    ];
    let area: f64 = (0..8)
        .map(|k| {
            let (p, q) = (section[k], section[(k + 1) % 8]);
            p.0 * q.1 - q.0 * p.1
        })
        .sum::<f64>()
        .abs()
        / 2.0;
    let e = expected(&l);
    let length: f64 = e
        .lines
        .iter()
        .map(|(a, b)| (b[0] - a[0]).hypot(b[1] - a[1]))
        .sum();
    assert!(
        (vol - area * length).abs() < 1e-6 * area * length,
        "volume {vol}, want {} (area {area} × {length} m)",
        area * length
    );
}

#[test]
fn a_graded_highway_drapes_its_barrier_onto_the_road() {
    let desc = town("town04");
    let st = StaticTown::new(&desc, 3);
    let g = Grade::new(&desc, 3).expect("town04 is graded");
    let level = &median_meshes(&st.layout)[0];
    let meshes = st.meshes();
    let draped = meshes
        .iter()
        .find(|o| o.name.as_deref() == Some(MEDIAN_NAME))
        .expect("the barrier is among the town's meshes");
    let (ShapeDesc::Mesh { positions: a, .. }, ShapeDesc::Mesh { positions: b, .. }) =
        (&level.shape, &draped.shape)
    else {
        panic!("not meshes")
    };
    assert_eq!(a.len(), b.len());
    for (p, q) in a.iter().zip(b) {
        assert_eq!([p[0], p[1]], [q[0], q[1]]);
        assert!((q[2] - p[2] - g.height_m(p[0], p[1])).abs() < 1e-12);
    }
}

/// Largest half-width of any body on a route, metres (the bus, with margin).
const HALF_BODY_M: f64 = 1.3;

#[test]
fn no_drive_and_no_route_crosses_the_median_barrier() {
    for name in ["town04", "town06"] {
        let l = Layout::new(&town(name));
        let e = expected(&l);
        let turns = Turns::new(l.lane_w_m);
        let clear = FOOT + HALF_BODY_M;
        let n = links(&l).len();
        for start in 0..n {
            let mut path = DrivePath::new(&l, &turns, start, Rng::new(&[7, start as u64]));
            path.reach(4000.0);
            let mut s = 0.0;
            while s < path.length_m() {
                let (q, _) = path.pose(s);
                let d = e.distance(q);
                assert!(
                    d >= clear,
                    "{name} drive from link {start}: {d} m from the barrier at {q:?} (s {s})"
                );
                s += 0.5;
            }
        }
        for r in routes(&l, &turns) {
            if r.kind == RouteKind::Overpass {
                continue; // over the highway on its bridge
            }
            let mut s = 0.0;
            while s < r.length_m() {
                let (q, _) = r.pose(s);
                assert!(e.distance(q) >= clear, "{name} route {:?} at {q:?}", r.kind);
                s += 0.5;
            }
        }
    }
}

#[test]
fn highway_trees_stand_behind_the_rail_line_not_on_the_hard_shoulder() {
    for name in ["town04", "town06"] {
        let desc = town(name);
        let st = StaticTown::new(&desc, 3);
        let l = &st.layout;
        // The guard rails' line: 0.5 m inside the shoulder's outer edge.
        let rail = l.sidewalk_m - 0.5;
        let roads: Vec<_> = (0..=l.ny)
            .map(|j| l.x_road(j))
            .chain((0..=l.nx).map(|i| l.y_road(i)))
            .collect();
        // Distance outside a road rectangle (0 inside it).
        let outside = |r: &parallax::town::layout::Rect, p: [f64; 2]| {
            let dx = (r.min[0] - p[0]).max(p[0] - r.max[0]).max(0.0);
            let dy = (r.min[1] - p[1]).max(p[1] - r.max[1]).max(0.0);
            dx.hypot(dy)
        };
        let mut roadside = 0;
        for o in st.objects() {
            let ShapeDesc::Instance { prefab, .. } = &o.shape else {
                continue;
            };
            if !prefab.starts_with("tree_") {
                continue;
            }
            let t = o.transform.translate.unwrap_or_default();
            let d = roads
                .iter()
                .map(|r| outside(r, [t[0], t[1]]))
                .fold(f64::INFINITY, f64::min);
            assert!(
                d > rail,
                "{name}: {prefab} at {t:?} stands {d:.2} m off the road, on the shoulder (rail at {rail} m)"
            );
            roadside += usize::from(d < l.sidewalk_m + 2.0);
        }
        assert!(roadside > 20, "{name}: only {roadside} roadside trees");
    }
}
