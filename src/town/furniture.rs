//! Street furniture and street trees, placed as prefab instances of
//! `street` in the town's `StreetStyle`: trees, street lights (and, where
//! the style has them, utility poles with overhead wires) along the
//! sidewalks or shoulders, printed signs (speed limits, crossings, no
//! entry, direction signs), benches, bins, bus shelters, hydrants, parking
//! meters and bollards on sidewalks; at junctions traffic lights (one per
//! approach, on its right-hand corner: `signals::junction_sites`; mast
//! arms on two-lane roads), stop signs where y-roads meet the outer
//! x-roads (T junctions), give-way signs at the roundabout and a
//! street-name post; guard rails, billboards and park fences come from
//! `street::place`. Nothing stands in the clear zone of a highway ramp
//! site.
//!
//! Headings follow the prefabs: a lamp's arm reaches along local −y, a
//! traffic light's along local +y, signs, signal heads and fixtures face
//! local −x. An item of two classes (a sign's post and face, a signal's
//! pole and heads) is two instances at one anchor, each of one class.

use crate::scene::desc::ObjectDesc;

use super::desc::TownDesc;
use super::layout::{Layout, Rect, STUB_M};
use super::parts::{class, instance, turned_quad};
use super::ramps::RampSite;
use super::rng::{tag, Rng};
use super::signals;
use super::street::lights::{signal_pole, SIGNAL_MAST};
use super::street::names::{speed_limit, PLACES, STREET_NAME_COUNT};
use super::street::signs::{direction_prefab, name_plate_prefab, speed_prefab, POSTS};
use super::street::{place, StreetStyle};
use super::vegetation::{self, Planting};

/// Stream word of the furniture placed besides lamps, trees and signs (a
/// stream of its own, so the older draws keep their values).
const FIXTURES: u64 = 1;

/// Every street tree, light, signal, sign and fixture of the town, clear
/// of the ramp `sites` (`ramps::ramp_sites`), with fences round the parks
/// among the `blocks` objects (`buildings::block_objects`).
pub fn furniture_objects(
    desc: &TownDesc,
    l: &Layout,
    sites: &[RampSite],
    seed: u64,
    blocks: &[ObjectDesc],
) -> Vec<ObjectDesc> {
    let style = StreetStyle::of(desc);
    let mut out = street_lines(desc, l, seed);
    out.extend(place::highway_runs(desc, l, style, sites, seed));
    out.extend(place::enclosures(blocks));
    place::corner_railings(l, &mut out);
    // Nothing but street lights on bridges.
    if let Some(band) = l.river_band() {
        out.retain(|o| {
            let on_bridge = o
                .transform
                .translate
                .is_some_and(|t| t[1] > band.min[1] && t[1] < band.max[1]);
            !on_bridge || place::prefab_of(o) == Some(style.lamp())
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
    junction_signs(l, seed, &mut out);
    out.extend(sites.iter().flat_map(RampSite::guard_rail_objects));
    out
}

/// One side of one road: where its furniture goes.
struct Side<'a> {
    /// (along, offset from the road edge) → world position on the walk.
    place: &'a dyn Fn(f64, f64) -> [f64; 3],
    /// Heading of a street light (arm over the road).
    lamp_heading: f64,
    /// Heading of the road's +along direction (0 or 90).
    run_heading: f64,
    /// Along-road coordinate of a world position.
    along: &'a dyn Fn([f64; 3]) -> f64,
}

/// Street lights, trees, signs and fixtures along both sides of every
/// x-road (stubs included), then every y-road, from one random stream
/// (lamps, trees, signs) and a second one (the rest).
fn street_lines(desc: &TownDesc, l: &Layout, seed: u64) -> Vec<ObjectDesc> {
    let mut out = Vec::new();
    let (p, hw) = (l.pitch_m, l.road_w_m / 2.0);
    let mut r = Rng::new(&[seed, tag::FURNITURE]);
    let trees = Planting::new(desc, seed);
    // Per side of the road: (start, end along the road, world position of
    // (along, side)).
    let mut fx = Rng::new(&[seed, tag::FURNITURE, FIXTURES]);
    for j in 0..=l.ny {
        let y = j as f64 * p;
        for side in [-1.0, 1.0] {
            let place = |a: f64, off: f64| [a, y + side * (hw + off), l.walk_z()];
            // Street-light arm over the road: north side heading 0 (arm −y).
            let s = Side {
                place: &place,
                lamp_heading: if side > 0.0 { 0.0 } else { 180.0 },
                run_heading: 0.0,
                along: &|t| t[0],
            };
            let span = (-STUB_M, l.len_x() + STUB_M);
            line(desc, &trees, l, (&mut r, &mut fx), span, &s, &mut out);
        }
    }
    for i in 0..=l.nx {
        let x = i as f64 * p;
        for side in [-1.0, 1.0] {
            let place = |a: f64, off: f64| [x + side * (hw + off), a, l.walk_z()];
            // East side (side > 0): arm towards −x, heading 270.
            let s = Side {
                place: &place,
                lamp_heading: if side > 0.0 { 270.0 } else { 90.0 },
                run_heading: 90.0,
                along: &|t| t[1],
            };
            let span = (0.0, l.len_y());
            line(desc, &trees, l, (&mut r, &mut fx), span, &s, &mut out);
        }
    }
    out
}

/// A sign: its post and its face, two instances at one anchor.
fn sign(face: &str, post: &str, at: [f64; 3], heading: f64, out: &mut Vec<ObjectDesc>) {
    out.push(instance(post, at, heading, &[], class("pole")));
    out.push(instance(face, at, heading, &[], class("traffic_sign")));
}

/// Stop signs at the T junctions of the outer x-roads, traffic lights
/// (lamps dark) at signalled junctions, a street-name post at every
/// junction and give-way signs on the roundabout's approaches.
fn junction_signs(l: &Layout, seed: u64, out: &mut Vec<ObjectDesc>) {
    let tl = class("traffic_light");
    let p = l.pitch_m;
    let c = l.road_w_m / 2.0 + 0.5;
    // Each road's name from the pool, shuffled per town.
    let mut r = Rng::new(&[seed, tag::FURNITURE, FIXTURES + 1]);
    let mut pool: Vec<usize> = (0..STREET_NAME_COUNT).collect();
    for k in (1..pool.len()).rev() {
        pool.swap(k, r.index(k + 1));
    }
    let name_at = |k: usize| name_plate_prefab(pool[k % STREET_NAME_COUNT]);
    let heads = if l.lanes >= 2 {
        SIGNAL_MAST
    } else {
        signals::PREFAB
    };
    let corner = l.road_w_m / 2.0
        + if l.sidewalks {
            l.sidewalk_m - 0.5
        } else {
            l.sidewalk_m + 1.0
        };
    for j in 0..=l.ny {
        for i in 0..=l.nx {
            let (x, y) = (i as f64 * p, j as f64 * p);
            let z = l.walk_z();
            if j == 0 {
                // Southbound traffic arrives at the T from the north.
                sign("sign_stop", POSTS[0], [x - c, y + c, z], 270.0, out);
            } else if j == l.ny {
                sign("sign_stop", POSTS[0], [x + c, y - c, z], 90.0, out);
            } else if signals::has_signals(l, i, j) {
                // Lamps dark: `signals::set_lamps` lights them per frame.
                for s in signals::junction_sites(l, i, j) {
                    let pole = signal_pole(heads);
                    out.push(instance(&pole, s.at, s.heading_deg, &[], class("pole")));
                    out.push(instance(heads, s.at, s.heading_deg, &[], tl));
                }
            }
            // The name post on the north-east corner: the x-road's plate
            // along x, the y-road's 22 cm lower along y.
            let at = [x + corner, y + corner, z];
            let ts = class("traffic_sign");
            out.push(instance(POSTS[2], at, 0.0, &[], class("pole")));
            out.push(instance(&name_at(j), at, 90.0, &[], ts));
            out.push(instance(
                &name_at(l.ny + 1 + i),
                [at[0], at[1], z - 0.22],
                0.0,
                &[],
                ts,
            ));
        }
    }
    if let Some(ctr) = l.roundabout_center() {
        let d = l.roundabout_clear_m() + 1.5;
        let off = l.road_w_m / 2.0 + 0.3;
        for heading in [0.0f64, 90.0, 180.0, 270.0] {
            let (sn, cs) = heading.to_radians().sin_cos();
            let (dir, right) = ([cs.round(), sn.round()], [sn.round(), -cs.round()]);
            let at = [
                ctr[0] - d * dir[0] + off * right[0],
                ctr[1] - d * dir[1] + off * right[1],
                l.walk_z(),
            ];
            sign("sign_give_way", POSTS[0], at, heading, out);
        }
    }
}

/// Trees, lights, wires, signs and fixtures along one side of one road,
/// skipping the junction areas (every multiple of the pitch).
fn line(
    desc: &TownDesc,
    trees: &Planting,
    l: &Layout,
    (r, fx): (&mut Rng, &mut Rng),
    (a0, a1): (f64, f64),
    side: &Side,
    out: &mut Vec<ObjectDesc>,
) {
    let style = StreetStyle::of(desc);
    let place = side.place;
    let lamp_heading = side.lamp_heading;
    let keep_clear = l.road_w_m / 2.0 + l.sidewalk_m + 6.0;
    let near_junction = |a: f64| {
        let m = a.rem_euclid(l.pitch_m);
        m < keep_clear || m > l.pitch_m - keep_clear
    };
    let on_bridge = |a: f64| {
        let t = place(a, 0.0);
        l.river_band()
            .is_some_and(|b| t[1] > b.min[1] - 3.0 && t[1] < b.max[1] + 3.0)
    };
    let off = 0.6;
    let first = out.len();
    if style.wires() {
        let blocked = |a: f64| near_junction(a) || on_bridge(a);
        let pole_off = if l.sidewalks {
            0.25
        } else {
            l.sidewalk_m + 0.8
        };
        let phase = fx.range(0.0, place::WIRE_SPAN_M);
        place::pole_line(
            a0 + phase,
            a1,
            &|a| place(a, pole_off),
            side.run_heading,
            &blocked,
            out,
        );
    }
    let poles: Vec<f64> = out[first..]
        .iter()
        .map(|o| (side.along)(anchor(o)))
        .collect();
    // Street lights every 30 m, offset per side so the two rows alternate;
    // behind the guard rail on highways, clear of utility poles.
    let lamp_off = if style == StreetStyle::Highway {
        l.sidewalk_m + 0.6
    } else {
        0.35
    };
    let mut lamps = Vec::new();
    let mut a = a0 + r.range(5.0, 30.0);
    while a < a1 {
        if !near_junction(a) && !poles.iter().any(|p| (p - a).abs() < 2.5) {
            out.push(instance(
                style.lamp(),
                place(a, lamp_off),
                lamp_heading,
                &[],
                class("pole"),
            ));
            lamps.push(a);
        }
        a += 30.0;
    }
    if trees.density > 0.0 {
        // On highways the hard shoulder stays clear: trees stand in the
        // verge behind the guard rail's line, in the lamps' row between them,
        // on the town's side (beyond the town the hills have their own).
        let highway = style == StreetStyle::Highway;
        let bounds = l.bounds();
        let in_town = |p: [f64; 3]| bounds.contains(&Rect::centered([p[0], p[1]], [0.0, 0.0]), 0.0);
        let tree_off = if highway {
            l.sidewalk_m + 0.7
        } else {
            off + 0.3
        };
        let spacing = 9.0 / trees.density.max(0.15);
        let mut a = a0 + r.range(2.0, spacing);
        while a < a1 {
            let by_lamp = highway && lamps.iter().any(|p| (p - a).abs() < 4.0);
            let beyond = highway && !in_town(place(a, tree_off));
            if !near_junction(a) && r.chance(0.85) && !by_lamp && !beyond {
                let main = r.chance(0.7);
                let at = place(a, tree_off);
                out.push(trees.street_tree(main, at, r.range(0.0, 360.0)));
                if !trees.verges && !highway {
                    out.push(tree_pit(at, &place));
                }
            }
            a += spacing * r.range(0.8, 1.2);
        }
        if trees.verges {
            verges(l, (a0, a1), keep_clear, &place, off + 0.3, out);
        }
    }
    let sign_off = if style == StreetStyle::Highway {
        l.sidewalk_m + 0.3
    } else {
        0.3
    };
    let mut a = a0 + r.range(20.0, 120.0);
    while a < a1 {
        if !near_junction(a) {
            let (face, post) = road_sign(desc, style, fx);
            sign(&face, post, place(a, sign_off), lamp_heading + 90.0, out);
        }
        a += r.range(80.0, 200.0);
    }
    if l.sidewalks {
        let taken: Vec<f64> = out[first..]
            .iter()
            .map(|o| (side.along)(anchor(o)))
            .collect();
        let free = |a: f64, half: f64| {
            !near_junction(a - half)
                && !near_junction(a + half)
                && !taken.iter().any(|t| (t - a).abs() < half + 1.0)
        };
        place::sidewalk_fixtures(
            l,
            style,
            fx,
            (a0, a1),
            place,
            lamp_heading + 90.0,
            &free,
            out,
        );
    }
}

/// The sign of a roadside slot: a speed limit (from the town's speed),
/// a crossing, a no-entry or a direction sign, by style: (face, post).
fn road_sign(desc: &TownDesc, style: StreetStyle, fx: &mut Rng) -> (String, &'static str) {
    let u = fx.f64();
    let speed = |fx: &mut Rng| (speed_prefab(speed_limit(desc.speed_kmh, fx)), POSTS[0]);
    let direction = |fx: &mut Rng| (direction_prefab(fx.index(PLACES.len())), POSTS[1]);
    match style {
        StreetStyle::City | StreetStyle::SmallTown => match u {
            u if u < 0.4 => speed(fx),
            u if u < 0.65 => ("sign_crossing".to_string(), POSTS[0]),
            u if u < 0.8 => ("sign_no_entry".to_string(), POSTS[0]),
            _ => direction(fx),
        },
        StreetStyle::Highway | StreetStyle::Country => match u {
            u if u < 0.6 => speed(fx),
            u if u < 0.9 => direction(fx),
            _ => ("sign_give_way".to_string(), POSTS[0]),
        },
    }
}

/// The anchor (translation) of an object.
fn anchor(o: &ObjectDesc) -> [f64; 3] {
    o.transform.translate.unwrap_or_default()
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
