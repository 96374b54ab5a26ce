//! Street furniture and street trees: trees and street lights along the
//! sidewalks, traffic lights at every cross junction (one per approach, on
//! its right-hand corner: `signals::junction_sites`), stop signs where y-roads meet the outer x-roads
//! (T junctions), and a few information signs. Nothing stands in the clear
//! zone of a highway ramp site.
//!
//! Headings follow the prefabs of `props.rs`: a street light's arm reaches
//! along local −y, a traffic light's along local +y, signs and signal heads
//! face local −x.

use crate::scene::desc::ObjectDesc;

use super::desc::TownDesc;
use super::layout::{Layout, Rect, STUB_M};
use super::parts::{class, instance, turned_quad};
use super::ramps::RampSite;
use super::rng::{tag, Rng};
use super::signals;
use super::vegetation::{self, Planting};

/// Every street tree, light, signal and sign of the town, clear of the
/// ramp `sites` (`ramps::ramp_sites`).
pub fn furniture_objects(
    desc: &TownDesc,
    l: &Layout,
    sites: &[RampSite],
    seed: u64,
) -> Vec<ObjectDesc> {
    let mut out = street_lines(desc, l, seed);
    // No trees or signs on bridges.
    if let Some(band) = l.river_band() {
        out.retain(|o| {
            let on_bridge = o
                .transform
                .translate
                .is_some_and(|t| t[1] > band.min[1] && t[1] < band.max[1]);
            !on_bridge || o.semantic.as_deref() == Some("pole")
        });
    }
    let zones: Vec<_> = sites.iter().map(|r| r.clear_zone()).collect();
    let reach = 2.0 * vegetation::max_reach_m();
    out.retain(|o| {
        let t = o.transform.translate.unwrap_or_default();
        let at = Rect::centered([t[0], t[1]], [0.0, 0.0]);
        // A tree's crown reaches out from its foot.
        let crown = Rect::centered([t[0], t[1]], [reach, reach]);
        let tree = o.semantic.as_deref() == Some("vegetation");
        !zones
            .iter()
            .any(|z| z.contains(&at, 0.0) || (tree && z.overlaps(&crown)))
    });
    junction_signs(l, &mut out);
    out
}

/// Street lights, trees and signs along both sides of every x-road (stubs
/// included), then every y-road, from one random stream.
fn street_lines(desc: &TownDesc, l: &Layout, seed: u64) -> Vec<ObjectDesc> {
    let mut out = Vec::new();
    let (p, hw) = (l.pitch_m, l.road_w_m / 2.0);
    let mut r = Rng::new(&[seed, tag::FURNITURE]);
    let trees = Planting::new(desc, seed);
    // Per side of the road: (start, end along the road, world position of
    // (along, side)).
    for j in 0..=l.ny {
        let y = j as f64 * p;
        for side in [-1.0, 1.0] {
            let place = |a: f64, off: f64| [a, y + side * (hw + off), l.walk_z()];
            // Street-light arm over the road: north side heading 0 (arm −y).
            let lamp_heading = if side > 0.0 { 0.0 } else { 180.0 };
            let span = (-STUB_M, l.len_x() + STUB_M);
            line(&trees, l, &mut r, span, place, lamp_heading, &mut out);
        }
    }
    for i in 0..=l.nx {
        let x = i as f64 * p;
        for side in [-1.0, 1.0] {
            let place = |a: f64, off: f64| [x + side * (hw + off), a, l.walk_z()];
            // East side (side > 0): arm towards −x, heading 270.
            let lamp_heading = if side > 0.0 { 270.0 } else { 90.0 };
            let span = (0.0, l.len_y());
            line(&trees, l, &mut r, span, place, lamp_heading, &mut out);
        }
    }
    out
}

/// Stop signs at the T junctions of the outer x-roads and traffic lights
/// (lamps dark) at signalled junctions.
fn junction_signs(l: &Layout, out: &mut Vec<ObjectDesc>) {
    let (tl, ts) = (class("traffic_light"), class("traffic_sign"));
    let p = l.pitch_m;
    let c = l.road_w_m / 2.0 + 0.5;
    for j in 0..=l.ny {
        for i in 0..=l.nx {
            let (x, y) = (i as f64 * p, j as f64 * p);
            if j == 0 {
                // Southbound traffic arrives at the T from the north.
                out.push(instance(
                    "stop_sign",
                    [x - c, y + c, l.walk_z()],
                    270.0,
                    &[],
                    ts,
                ));
            } else if j == l.ny {
                out.push(instance(
                    "stop_sign",
                    [x + c, y - c, l.walk_z()],
                    90.0,
                    &[],
                    ts,
                ));
            } else if signals::has_signals(l, i, j) {
                // Lamps dark: `signals::set_lamps` lights them per frame.
                for s in signals::junction_sites(l, i, j) {
                    out.push(instance(signals::PREFAB, s.at, s.heading_deg, &[], tl));
                }
            }
        }
    }
}

/// Trees, lights and the odd sign along one side of one road, skipping the
/// junction areas (every multiple of the pitch).
fn line(
    trees: &Planting,
    l: &Layout,
    r: &mut Rng,
    (a0, a1): (f64, f64),
    place: impl Fn(f64, f64) -> [f64; 3],
    lamp_heading: f64,
    out: &mut Vec<ObjectDesc>,
) {
    let keep_clear = l.road_w_m / 2.0 + l.sidewalk_m + 6.0;
    let near_junction = |a: f64| {
        let m = a.rem_euclid(l.pitch_m);
        m < keep_clear || m > l.pitch_m - keep_clear
    };
    let off = 0.6;
    // Street lights every 30 m, offset per side so the two rows alternate.
    let mut a = a0 + r.range(5.0, 30.0);
    while a < a1 {
        if !near_junction(a) {
            out.push(instance(
                "street_light",
                place(a, 0.35),
                lamp_heading,
                &[],
                class("pole"),
            ));
        }
        a += 30.0;
    }
    if trees.density > 0.0 {
        let spacing = 9.0 / trees.density.max(0.15);
        let mut a = a0 + r.range(2.0, spacing);
        while a < a1 {
            if !near_junction(a) && r.chance(0.85) {
                let main = r.chance(0.7);
                let at = place(a, off + 0.3);
                out.push(trees.street_tree(main, at, r.range(0.0, 360.0)));
                if !trees.verges {
                    out.push(tree_pit(at, &place));
                }
            }
            a += spacing * r.range(0.8, 1.2);
        }
        if trees.verges {
            verges(l, (a0, a1), keep_clear, &place, off + 0.3, out);
        }
    }
    let mut a = a0 + r.range(20.0, 120.0);
    while a < a1 {
        if !near_junction(a) {
            out.push(instance(
                "info_sign",
                place(a, 0.3),
                lamp_heading + 90.0,
                &[],
                class("traffic_sign"),
            ));
        }
        a += r.range(80.0, 200.0);
    }
}

/// A square of grass round a street tree's foot (class `terrain`), level
/// with the sidewalk and 5 mm above it, turned with the road.
fn tree_pit(at: [f64; 3], place: &impl Fn(f64, f64) -> [f64; 3]) -> ObjectDesc {
    let (p, q) = (place(0.0, 0.0), place(1.0, 0.0));
    let heading = (q[1] - p[1]).atan2(q[0] - p[0]).to_degrees();
    let c = [at[0], at[1], at[2] + 0.005];
    turned_quad([1.2, 1.2], c, heading, vegetation::VERGE, class("terrain"))
}

/// Grass verges (class `terrain`) along the tree line, `width_centre` from
/// the kerb: one strip per road section between junction areas, none
/// reaching a bridge or the roundabout.
fn verges(
    l: &Layout,
    (a0, a1): (f64, f64),
    keep_clear: f64,
    place: &impl Fn(f64, f64) -> [f64; 3],
    width_centre: f64,
    out: &mut Vec<ObjectDesc>,
) {
    let p = l.pitch_m;
    let (first, last) = ((a0 / p).floor() as i64, (a1 / p).ceil() as i64);
    for k in first..last {
        let s0 = (k as f64 * p + keep_clear).max(a0);
        let s1 = ((k + 1) as f64 * p - keep_clear).min(a1);
        if s1 - s0 < 2.0 {
            continue;
        }
        let (e0, e1) = (place(s0, width_centre), place(s1, width_centre));
        let strip = Rect {
            min: [e0[0].min(e1[0]) - 0.5, e0[1].min(e1[1]) - 0.5],
            max: [e0[0].max(e1[0]) + 0.5, e0[1].max(e1[1]) + 0.5],
        };
        let on_bridge = l
            .river_band()
            .is_some_and(|b| strip.min[1] < b.max[1] && strip.max[1] > b.min[1]);
        if on_bridge || l.near_roundabout(&strip) {
            continue;
        }
        let heading = (e1[1] - e0[1]).atan2(e1[0] - e0[0]).to_degrees();
        let c = [(e0[0] + e1[0]) / 2.0, (e0[1] + e1[1]) / 2.0, e0[2] + 0.005];
        out.push(turned_quad(
            [s1 - s0, 1.0],
            c,
            heading,
            vegetation::VERGE,
            class("terrain"),
        ));
    }
}
