//! The roundabout of a town (town03): a ring road around a raised central
//! island with grass, a mound and trees, lane markings on the ring (edge
//! lines, a dashed divider), curbs and a sidewalk ring between the four
//! approach arms. The arms end where their kerbs meet the ring and carry a
//! dashed yield line there (see `roads`).
//!
//! The block loops with a corner here drive a quarter of the ring each
//! (`routes::ring_turn`: lane k of the road on ring lane k), so routes
//! still share no surface. The ring asphalt is quads turned about z, the
//! markings, curbs, sidewalk and island rim are world meshes (bent vertex
//! by vertex in an organic town); road surfaces stay exactly at z = 0 (the
//! GT tests rely on it).

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use glam::DVec3;

use crate::scene::desc::ObjectDesc;
use crate::scene::mesh::{self, LocalMesh};

use super::layout::Layout;
use super::parts::{class, turned_quad, world_mesh, Label};
use super::vegetation::{self, Plant, Species};

/// Distance from the roundabout centre at which each approach arm's
/// straight road ends (its kerbs meet the ring's outer kerb), metres.
pub fn arm_start_m(l: &Layout) -> f64 {
    let (_, r_out) = l.roundabout_radii();
    let hw = l.road_w_m / 2.0;
    (r_out * r_out - hw * hw).sqrt()
}

/// Half-angle (radians) of each arm's opening in the ring's outer kerb:
/// the arm's kerb lines y = ±hw meet that circle there.
fn opening_half_angle(l: &Layout) -> f64 {
    let (_, r_out) = l.roundabout_radii();
    (l.road_w_m / 2.0 / r_out).asin()
}

/// Angular intervals [θ0, θ1] (radians) of a circle: the whole circle, or
/// the four arcs between the arm openings of half-angle `open`.
fn arcs(open: Option<f64>) -> Vec<(f64, f64)> {
    match open {
        None => vec![(0.0, 2.0 * PI)],
        Some(a) => (0..4)
            .map(|q| {
                let t = q as f64 * FRAC_PI_2;
                (t + a, t + FRAC_PI_2 - a)
            })
            .collect(),
    }
}

/// The annulus r0..r1 between heights z over the given arcs as one world
/// mesh, its vertices about `piece_m` apart at r1; with `dash`, only every
/// other piece at half length (a dashed line). A mesh, not chord boxes, so
/// that an organic town's warp bends it smoothly vertex by vertex.
#[allow(clippy::too_many_arguments)]
fn ring(
    c: [f64; 2],
    r: (f64, f64),
    z: (f64, f64),
    open: Option<f64>,
    piece_m: f64,
    dash: bool,
    mat: &str,
    l: Label,
    out: &mut Vec<ObjectDesc>,
) {
    let mut m = LocalMesh::default();
    for (t0, t1) in arcs(open) {
        let n = ((t1 - t0) * r.1 / piece_m).ceil().max(1.0) as usize;
        let dt = (t1 - t0) / n as f64;
        if dash {
            for k in (0..n).step_by(2) {
                let t = t0 + (k as f64 + 0.5) * dt;
                band(&mut m, c, r, z, &[t - dt / 4.0, t + dt / 4.0]);
            }
        } else {
            let phis: Vec<f64> = (0..=n).map(|k| t0 + k as f64 * dt).collect();
            band(&mut m, c, r, z, &phis);
        }
    }
    out.push(world_mesh(m, mat, l));
}

/// Appends a curved box about `c` between radii r0..r1 and heights z0..z1
/// over the increasing angles `phis` (radians): top, inner and outer walls
/// and end walls unless it closes a full turn; no floor (every ring piece
/// stands on or in the ground). Counter-clockwise seen from outside.
fn band(m: &mut LocalMesh, c: [f64; 2], (r0, r1): (f64, f64), (z0, z1): (f64, f64), phis: &[f64]) {
    let base = m.positions.len() as u32;
    for &t in phis {
        let (s, co) = t.sin_cos();
        for (r, z) in [(r0, z0), (r1, z0), (r0, z1), (r1, z1)] {
            m.positions.push(DVec3::new(c[0] + r * co, c[1] + r * s, z));
        }
    }
    // Vertex v of angle k: 0 inner bottom, 1 outer bottom, 2 inner top, 3 outer top.
    let at = |k: usize, v: u32| base + 4 * k as u32 + v;
    for k in 0..phis.len() - 1 {
        let (a, b) = (k, k + 1);
        m.triangles.push([at(a, 2), at(a, 3), at(b, 3)]);
        m.triangles.push([at(a, 2), at(b, 3), at(b, 2)]);
        if z1 > z0 {
            m.triangles.push([at(a, 1), at(b, 1), at(b, 3)]);
            m.triangles.push([at(a, 1), at(b, 3), at(a, 3)]);
            m.triangles.push([at(a, 0), at(b, 2), at(b, 0)]);
            m.triangles.push([at(a, 0), at(a, 2), at(b, 2)]);
        }
    }
    let closed = phis[phis.len() - 1] - phis[0] >= TAU - 1e-9;
    if z1 > z0 && !closed {
        let e = phis.len() - 1;
        m.triangles.push([at(0, 0), at(0, 1), at(0, 3)]);
        m.triangles.push([at(0, 0), at(0, 3), at(0, 2)]);
        m.triangles.push([at(e, 0), at(e, 3), at(e, 1)]);
        m.triangles.push([at(e, 0), at(e, 2), at(e, 3)]);
    }
}

/// Every object of the roundabout (none if the town has none): ring
/// asphalt, markings, the outer curb and sidewalk, the central island.
pub fn roundabout_objects(l: &Layout) -> Vec<ObjectDesc> {
    let mut out = Vec::new();
    let Some(c) = l.roundabout_center() else {
        return out;
    };
    let (r_in, r_out) = l.roundabout_radii();
    let open = Some(opening_half_angle(l));
    ring_asphalt(c, (r_in, r_out), &mut out);
    ring_markings(l, c, open, &mut out);
    ring_roadside(l, c, open, &mut out);
    island(c, r_in, &mut out);
    out
}

/// Ring asphalt: radial quads at z = 0 from under the island to under the
/// outer curb.
fn ring_asphalt(c: [f64; 2], (r_in, r_out): (f64, f64), out: &mut Vec<ObjectDesc>) {
    let n = 96;
    let (q0, q1) = (r_in - 0.5, r_out + 0.2);
    let width = 2.0 * q1 * (PI / n as f64).tan();
    for k in 0..n {
        let t = (k as f64 + 0.5) * 2.0 * PI / n as f64;
        let rc = (q0 + q1) / 2.0;
        let at = [c[0] + rc * t.cos(), c[1] + rc * t.sin(), 0.0];
        out.push(turned_quad(
            [q1 - q0, width],
            at,
            t.to_degrees(),
            "asphalt",
            class("road"),
        ));
    }
}

/// Markings: solid edge lines (the outer one open at the arms) and a
/// dashed divider between the ring lanes.
fn ring_markings(l: &Layout, c: [f64; 2], open: Option<f64>, out: &mut Vec<ObjectDesc>) {
    let (r_in, r_out) = l.roundabout_radii();
    let (mark, paint, pz) = (class("road_line"), "paint_white_road", (0.0, 0.008));
    let edge_in = (r_in + 0.25, r_in + 0.4);
    ring(c, edge_in, pz, None, 2.0, false, paint, mark, out);
    let edge_out = (r_out - 0.4, r_out - 0.25);
    ring(c, edge_out, pz, open, 2.0, false, paint, mark, out);
    let lane_w = (r_out - r_in) / l.lanes as f64;
    for k in 1..l.lanes {
        let r = r_in + k as f64 * lane_w;
        ring(
            c,
            (r - 0.06, r + 0.06),
            pz,
            None,
            3.0,
            true,
            paint,
            mark,
            out,
        );
    }
}

/// Outer curb and sidewalk ring between the arms (a gravel shoulder on
/// country roads).
fn ring_roadside(l: &Layout, c: [f64; 2], open: Option<f64>, out: &mut Vec<ObjectDesc>) {
    let (_, r_out) = l.roundabout_radii();
    if l.sidewalks {
        let side = class("sidewalk");
        let (curb, walk) = ((r_out, r_out + 0.25), (r_out + 0.25, r_out + l.sidewalk_m));
        ring(c, curb, (0.0, 0.15), open, 2.0, false, "curb", side, out);
        ring(
            c,
            walk,
            (0.0, 0.14),
            open,
            2.0,
            false,
            "sidewalk",
            side,
            out,
        );
    } else {
        let t = class("terrain");
        let shoulder = (r_out, r_out + l.sidewalk_m);
        ring(
            c,
            shoulder,
            (-0.01, 0.0),
            open,
            2.0,
            false,
            "gravel",
            t,
            out,
        );
    }
}

/// Central island of radius `r_in`: a curb drum, a lawn top, a low grass
/// mound, a tree in the middle and four smaller plants round it.
fn island(c: [f64; 2], r_in: f64, out: &mut Vec<ObjectDesc>) {
    // World meshes, so that an organic warp bends the island's rim with
    // the ring's inner edge (a rigid drum would cover the bent inner lane).
    let drum = |r: f64, z: (f64, f64)| {
        let mut m = mesh::cylinder(r, z.1 - z.0, 64, true);
        let at = DVec3::new(c[0], c[1], z.0);
        m.positions.iter_mut().for_each(|p| *p += at);
        m
    };
    out.push(world_mesh(
        drum(r_in, (0.0, 0.15)),
        "curb",
        class("sidewalk"),
    ));
    let lawn = drum(r_in - 0.3, (0.15, 0.25));
    out.push(world_mesh(lawn, "lawn", class("terrain")));
    let mound = super::parts::blob(
        [r_in - 2.5, r_in - 2.5, 0.9],
        [c[0], c[1], 0.25],
        "lawn",
        class("terrain"),
    );
    out.push(mound);
    let centre = Plant::Tree(Species::Plane);
    out.push(vegetation::place(centre, [c[0], c[1], 1.1], 0.0, 0));
    for q in 0..4 {
        let t = (q as f64 + 0.5) * FRAC_PI_2;
        let r = 0.6 * r_in;
        let p = [c[0] + r * t.cos(), c[1] + r * t.sin(), 0.5];
        let plant = if q % 2 == 0 {
            Plant::Tree(Species::Birch)
        } else {
            Plant::Bush
        };
        out.push(vegetation::place(plant, p, 45.0 * q as f64, 0));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::desc::ShapeDesc;

    /// Signed volume enclosed by the triangles with the origin at `o`
    /// (divergence theorem; a missing floor in the plane z = o.z adds 0).
    fn volume(m: &LocalMesh, o: DVec3) -> f64 {
        m.triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| m.positions[i as usize] - o);
                a.dot(b.cross(c)) / 6.0
            })
            .sum()
    }

    #[test]
    fn a_band_is_a_closed_outward_wound_annulus_sector_on_the_ground() {
        let (c, r, z) = ([30.0, -20.0], (10.0, 13.0), (0.0, 0.15));
        let n = 12;
        let phis: Vec<f64> = (0..=n).map(|k| 0.4 + 0.1 * k as f64).collect();
        let mut m = LocalMesh::default();
        band(&mut m, c, r, z, &phis);
        // Polygonal annulus sector: n trapezoids of ½(r1² − r0²)·sin(dφ).
        let want = 0.5 * (r.1 * r.1 - r.0 * r.0) * n as f64 * 0.1f64.sin() * (z.1 - z.0);
        let got = volume(&m, DVec3::new(c[0], c[1], z.0));
        assert!((got - want).abs() < 1e-9 * want, "{got} vs {want}");
        // Every edge off the floor is shared by two triangles in opposite
        // directions (walls and end walls present, consistently wound).
        let mut edges = std::collections::BTreeMap::new();
        for t in &m.triangles {
            for k in 0..3 {
                *edges.entry((t[k], t[(k + 1) % 3])).or_insert(0) += 1;
            }
        }
        for (&(a, b), &count) in &edges {
            let on_floor = [a, b].iter().all(|&i| m.positions[i as usize].z == z.0);
            let back = edges.get(&(b, a)).copied().unwrap_or(0);
            assert_eq!(count, 1, "edge {a}–{b} used {count} times");
            assert!(back == 1 || on_floor, "edge {a}–{b} has no twin");
        }
        // A full turn: no end walls, the same volume law.
        let mut full = LocalMesh::default();
        let phis: Vec<f64> = (0..=64).map(|k| k as f64 * TAU / 64.0).collect();
        band(&mut full, c, r, z, &phis);
        let want = 0.5 * (r.1 * r.1 - r.0 * r.0) * 64.0 * (TAU / 64.0).sin() * (z.1 - z.0);
        let got = volume(&full, DVec3::new(c[0], c[1], z.0));
        assert!((got - want).abs() < 1e-9 * want, "{got} vs {want}");
    }

    #[test]
    fn arcs_leave_four_equal_openings() {
        let a = 0.3;
        let arcs4 = arcs(Some(a));
        assert_eq!(arcs4.len(), 4);
        // Arc q runs counter-clockwise from a past the axis direction q·90°
        // to a before the next one.
        for (q, &(t0, t1)) in arcs4.iter().enumerate() {
            let axis = q as f64 * PI / 2.0;
            assert!((t0 - (axis + a)).abs() < 1e-12, "arc {q} starts at {t0}");
            assert!(
                (t1 - (axis + PI / 2.0 - a)).abs() < 1e-12,
                "arc {q} ends at {t1}"
            );
        }
        // Each opening, from the previous arc's end to this arc's start, is
        // 2a wide and centred on its axis direction (0°, 90°, 180°, 270°).
        for q in 0..4 {
            let prev_end = arcs4[(q + 3) % 4].1 - if q == 0 { 2.0 * PI } else { 0.0 };
            let start = arcs4[q].0;
            assert!((start - prev_end - 2.0 * a).abs() < 1e-12, "opening {q}");
            let centre = (start + prev_end) / 2.0;
            assert!(
                (centre - q as f64 * PI / 2.0).abs() < 1e-12,
                "opening {q} at {centre}"
            );
        }
        let total: f64 = arcs4.iter().map(|(t0, t1)| t1 - t0).sum();
        assert!((total - (2.0 * PI - 8.0 * a)).abs() < 1e-12);
        assert_eq!(arcs(None), vec![(0.0, 2.0 * PI)]);
    }

    #[test]
    fn openings_meet_the_arm_kerbs_on_the_outer_kerb() {
        // With the half-angle roundabout_objects uses, the east opening's
        // edges on the outer kerb lie on the arm's kerb lines y = ±hw, at
        // x = arm_start_m.
        let l = Layout {
            nx: 2,
            ny: 2,
            pitch_m: 100.0,
            road_w_m: 14.0,
            parking_m: 0.0,
            lane_w_m: 3.5,
            lanes: 2,
            sidewalk_m: 2.0,
            sidewalks: true,
            river_row: None,
            roundabout: Some((1, 1)),
            underpass: None,
            loop_radius_m: 0.0,
            median: false,
        };
        // r_out = 10 + 2 · (3.5 + 1) = 19 m, hw = 7 m.
        let (r_out, hw): (f64, f64) = (19.0, 7.0);
        assert_eq!(l.roundabout_radii().1, r_out);
        let arcs4 = arcs(Some(opening_half_angle(&l)));
        let (start, end) = (arcs4[0].0, arcs4[3].1);
        assert!((r_out * start.sin() - hw).abs() < 1e-12);
        assert!((r_out * end.sin() + hw).abs() < 1e-12);
        let x = (19.0f64 * 19.0 - 7.0 * 7.0).sqrt();
        assert!((arm_start_m(&l) - x).abs() < 1e-12);
        assert!((r_out * start.cos() - x).abs() < 1e-12);
    }

    #[test]
    fn the_ring_is_edged_by_curb_and_sidewalk_between_the_arms_and_gravel_in_the_country() {
        let mut l = Layout {
            nx: 2,
            ny: 2,
            pitch_m: 100.0,
            road_w_m: 14.0,
            parking_m: 0.0,
            lane_w_m: 3.5,
            lanes: 2,
            sidewalk_m: 3.0,
            sidewalks: true,
            river_row: None,
            roundabout: Some((1, 1)),
            underpass: None,
            loop_radius_m: 0.0,
            median: false,
        };
        let (c, r_out) = ([100.0, 100.0], 19.0);
        let open = Some(opening_half_angle(&l));
        for (sidewalks, want) in [(true, vec!["curb", "sidewalk"]), (false, vec!["gravel"])] {
            l.sidewalks = sidewalks;
            let mut out = Vec::new();
            ring_roadside(&l, c, open, &mut out);
            let mut kinds: Vec<&str> = out.iter().map(|o| o.material.as_deref().unwrap()).collect();
            kinds.dedup();
            assert_eq!(kinds, want);
            for o in &out {
                let ShapeDesc::Mesh { positions, .. } = &o.shape else {
                    panic!("a ring piece is not a world mesh: {o:?}")
                };
                assert!(o.transform.is_identity());
                for p in positions {
                    let (d, a) = (
                        (p[0] - c[0]).hypot(p[1] - c[1]),
                        (p[1] - c[1]).atan2(p[0] - c[0]),
                    );
                    assert!(d > r_out - 1e-9 && d < r_out + 3.0 + 1e-9, "{d}");
                    // Nothing in an arm's opening (about each axis direction).
                    let off_axis = (a - (a / FRAC_PI_2).round() * FRAC_PI_2).abs();
                    assert!(off_axis > opening_half_angle(&l) - 1e-9, "{a}");
                    assert!((-0.01..=0.15).contains(&p[2]), "{p:?}");
                }
            }
        }
        // The island: curb drum, lawn, mound, then five plants.
        let mut out = Vec::new();
        island(c, 10.0, &mut out);
        let classes: Vec<&str> = out.iter().map(|o| o.semantic.as_deref().unwrap()).collect();
        let veg = "vegetation";
        assert_eq!(
            classes,
            ["sidewalk", "terrain", "terrain", veg, veg, veg, veg, veg]
        );
    }
}
