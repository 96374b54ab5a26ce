//! A pickup's open load bed. The lower body's loft is whole ahead of the
//! bed and behind the tailgate's inner face; over the bed it keeps only its
//! sides, bottom and rail tops (the top arc between the rails' inner edges
//! is left out), and inner walls, a floor, the cab's back wall and the
//! tailgate's face close the solid round the opening.
//!
//! Every closing piece shares the loft's vertices where they meet it (the
//! rails' inner edges are a section angle of the loft's own grid, and the
//! walls use the loft's x stations), so the body stays watertight.

use std::f64::consts::{PI, TAU};

use super::loft::grid;
use super::spec::Spec;
use crate::scene::mesh::LocalMesh;

/// Where a body's load bed is open, metres (body-frame x, z).
#[derive(Clone, Copy, Debug)]
pub struct Bed {
    /// The front wall (behind the cab).
    pub front_x: f64,
    /// The tailgate's inner face.
    pub tail_x: f64,
    /// The bed floor's height.
    pub floor_z: f64,
    /// The rails' inner edges, in section steps from the side (θ = k · τ /
    /// steps): the top arc between them is open.
    pub rail_steps: usize,
}

/// The lower body of `s` with `bed` open, as pieces sharing their edges:
/// `steps` section steps round the full loft, `per_m` loft stations per metre.
pub fn open_lower_body(s: &Spec, bed: &Bed, steps: usize, per_m: f64) -> Vec<LocalMesh> {
    let hl = s.hl();
    let lower = |x: f64, th: f64| s.lower(x, th);
    let stations = |a: f64, b: f64| (((b - a).abs() * per_m).ceil() as usize).max(2);
    let th_r = bed.rail_steps as f64 * TAU / steps as f64;
    let (xa, xb) = (bed.tail_x, bed.front_x);
    let nb = stations(xa, xb);
    // A whole piece from a tip (the grid's exact first station: a tip's
    // section closes only at exactly ±hl, the plan being a superellipse
    // of high power) to `end`; `flip` keeps the faces pointing out.
    let whole = |tip: f64, end: f64, flip: bool| {
        grid(
            &lower,
            (tip, end, stations(tip, end)),
            (0.0, TAU, steps),
            0.0,
            flip,
        )
    };
    // The rails' inner edges at station x (left: +y).
    let rail = |x: f64| s.lower(x, th_r);
    let wall = |sign: f64| {
        move |x: f64, v: f64| {
            let [_, y, z] = rail(x);
            [x, sign * y, bed.floor_z + (z - bed.floor_z) * v]
        }
    };
    let floor = |x: f64, v: f64| [x, v * rail(x)[1], bed.floor_z];
    // A wall across the body at x: the loft's top arc down to the floor.
    let across = |x: f64| {
        move |th: f64, v: f64| {
            let [_, y, z] = s.lower(x, th);
            [x, y, bed.floor_z + (z - bed.floor_z) * v]
        }
    };
    let arc = (th_r, PI - th_r, steps / 2 - 2 * bed.rail_steps);
    vec![
        whole(hl, xb, false),
        whole(-hl, xa, true),
        // Right rail's inner edge, round the bottom, to the left rail's.
        grid(
            &lower,
            (xa, xb, nb),
            (PI - th_r, TAU + th_r, steps - arc.2),
            0.0,
            true,
        ),
        grid(&wall(1.0), (xa, xb, nb), (0.0, 1.0, 2), 0.0, false),
        grid(&wall(-1.0), (xa, xb, nb), (0.0, 1.0, 2), 0.0, true),
        grid(&floor, (xa, xb, nb), (-1.0, 1.0, 8), 0.0, false),
        grid(&across(xb), arc, (0.0, 1.0, 2), 0.0, false),
        grid(&across(xa), arc, (0.0, 1.0, 2), 0.0, true),
    ]
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;
    use crate::town::vehicles::loft::volume;
    use crate::town::vehicles::spec::spec_of;
    use crate::town::vehicles::BodyKind;

    const STEPS: usize = 40;
    const PER_M: f64 = 16.0;

    fn pickup() -> (Spec, Bed) {
        let s = spec_of(BodyKind::Pickup).unwrap();
        (s, s.bed.expect("the pickup's bed is open"))
    }

    fn total_volume(pieces: &[LocalMesh], shift: DVec3) -> f64 {
        pieces
            .iter()
            .map(|m| {
                let mut m = m.clone();
                m.positions.iter_mut().for_each(|p| *p += shift);
                volume(&m)
            })
            .sum()
    }

    /// The first hit of the ray from `o` along `d` (Möller–Trumbore):
    /// distance and the face's normal as wound.
    fn first_hit(pieces: &[LocalMesh], o: DVec3, d: DVec3) -> Option<(f64, DVec3)> {
        let mut best: Option<(f64, DVec3)> = None;
        for m in pieces {
            for t in &m.triangles {
                let [a, b, c] = t.map(|i| m.positions[i as usize]);
                let (e1, e2) = (b - a, c - a);
                let p = d.cross(e2);
                let det = e1.dot(p);
                if det.abs() < 1e-14 {
                    continue;
                }
                let s = o - a;
                let u = s.dot(p) / det;
                let q = s.cross(e1);
                let v = d.dot(q) / det;
                let dist = e2.dot(q) / det;
                if u < 0.0 || v < 0.0 || u + v > 1.0 || dist <= 0.0 {
                    continue;
                }
                if best.is_none_or(|(b, _)| dist < b) {
                    best = Some((dist, e1.cross(e2).normalize()));
                }
            }
        }
        best
    }

    #[test]
    fn the_open_body_is_a_closed_solid_lacking_exactly_the_bed() {
        let (s, bed) = pickup();
        let pieces = open_lower_body(&s, &bed, STEPS, PER_M);
        let v = total_volume(&pieces, DVec3::ZERO);
        // A closed surface encloses the same volume wherever it stands
        // (a missing wall would move it by 0.5 m³; the loft's own seam at
        // θ = 0 and τ is open by ~5e-5 m, where the section's power of a
        // rounded sine amplifies the rounding).
        let moved = total_volume(&pieces, DVec3::new(3.0, -2.0, 5.0));
        assert!((v - moved).abs() < 1e-3, "{v} vs {moved}: not closed");
        // The cavity, integrated independently over x: the area between
        // the loft's top arc (as tessellated, 12 section steps) and the floor.
        let th_r = bed.rail_steps as f64 * TAU / STEPS as f64;
        let arc_steps = STEPS / 2 - 2 * bed.rail_steps;
        let nx = 4000;
        let dx = (bed.front_x - bed.tail_x) / nx as f64;
        let mut cavity = 0.0;
        for i in 0..nx {
            let x = bed.tail_x + (i as f64 + 0.5) * dx;
            let arc: Vec<[f64; 3]> = (0..=arc_steps)
                .map(|k| s.lower(x, th_r + (PI - 2.0 * th_r) * k as f64 / arc_steps as f64))
                .collect();
            let area: f64 = arc
                .windows(2)
                .map(|w| (w[0][1] - w[1][1]) * ((w[0][2] + w[1][2]) / 2.0 - bed.floor_z))
                .sum();
            cavity += area * dx;
        }
        // The same body closed: the bed's stretch lofted whole.
        let nb = (((bed.front_x - bed.tail_x) * PER_M).ceil() as usize).max(2);
        let bed_whole = grid(
            &|x: f64, th: f64| s.lower(x, th),
            (bed.tail_x, bed.front_x, nb),
            (0.0, TAU, STEPS),
            0.0,
            true,
        );
        let closed = volume(&pieces[0]) + volume(&pieces[1]) + volume(&bed_whole);
        let lost = closed - v;
        assert!(cavity > 0.8, "{cavity} m³: a bed worth the name");
        assert!(
            (lost - cavity).abs() < 0.005 * cavity,
            "lost {lost} m³, cavity {cavity} m³"
        );
    }

    #[test]
    fn a_ray_down_into_the_bed_meets_its_floor_and_one_on_the_cab_its_top() {
        let (s, bed) = pickup();
        let pieces = open_lower_body(&s, &bed, STEPS, PER_M);
        let down = DVec3::NEG_Z;
        let y_r = s.lower(-1.6, bed.rail_steps as f64 * TAU / STEPS as f64)[1];
        for x in [bed.tail_x + 0.05, -1.6, bed.front_x - 0.05] {
            for y in [-0.9 * y_r, 0.0, 0.9 * y_r] {
                let (t, n) = first_hit(&pieces, DVec3::new(x, y, 3.0), down).unwrap();
                assert!(
                    (3.0 - t - bed.floor_z).abs() < 1e-9,
                    "({x}, {y}): {}",
                    3.0 - t
                );
                assert!(n.z > 0.999, "({x}, {y}): floor faces {n}");
            }
        }
        // The rails and the cab's shoulder stand above the floor.
        let (t, _) = first_hit(&pieces, DVec3::new(-1.6, y_r + 0.02, 3.0), down).unwrap();
        assert!(3.0 - t > bed.floor_z + 0.2, "rail at {}", 3.0 - t);
        let (t, n) = first_hit(&pieces, DVec3::new(0.0, 0.0, 3.0), down).unwrap();
        assert!((3.0 - t - s.top_z(0.0)).abs() < 0.01 && n.z > 0.99);
        // Looking back from the cab, the front wall faces the bed.
        let o = DVec3::new(-1.6, 0.0, bed.floor_z + 0.1);
        let (t, n) = first_hit(&pieces, o, DVec3::X).unwrap();
        assert!(
            (o.x + t - bed.front_x).abs() < 1e-9 && n.x < -0.999,
            "{t} {n}"
        );
        let (t, n) = first_hit(&pieces, o, DVec3::NEG_X).unwrap();
        assert!(
            (o.x - t - bed.tail_x).abs() < 1e-9 && n.x > 0.999,
            "{t} {n}"
        );
    }
}
