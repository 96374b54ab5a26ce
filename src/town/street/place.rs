//! Placement of the street furniture that comes in runs or clusters:
//! utility-pole lines with a wire span between neighbouring poles,
//! sidewalk fixtures (benches, bins, shelters, hydrants, meters,
//! bollards), guard-rail runs and billboards along highways, and palisade
//! fences round parks. World frame: z up, metres; headings in degrees
//! counter-clockwise from +x, as `parts::instance` takes them.

use crate::scene::desc::{ObjectDesc, ShapeDesc};
use crate::town::desc::TownDesc;
use crate::town::layout::{Layout, Rect};
use crate::town::overpass::Overpass;
use crate::town::parts::{class, instance};
use crate::town::ramps::RampSite;
use crate::town::rng::{tag, Rng};

pub use super::barriers::WIRE_SPAN_M;
use super::barriers::{FARM_FENCE_M, GUARD_RAILS, PALISADE_M};
use super::names::SLOGANS;
use super::StreetStyle;

/// Stream word of the highway runs (after `furniture`'s own words).
const HIGHWAY: u64 = 3;

/// The prefab an instance object places, if it is one.
pub fn prefab_of(o: &ObjectDesc) -> Option<&str> {
    match &o.shape {
        ShapeDesc::Instance { prefab, .. } => Some(prefab),
        _ => None,
    }
}

/// Utility poles every `WIRE_SPAN_M` from `a0` to `a1` along a road
/// (world position `at(a)`, the road's +along direction `heading`), none
/// where `blocked`; a wire span from each pole to the next one when both
/// stand.
pub fn pole_line(
    a0: f64,
    a1: f64,
    at: &dyn Fn(f64) -> [f64; 3],
    heading: f64,
    blocked: &dyn Fn(f64) -> bool,
    out: &mut Vec<ObjectDesc>,
) {
    let mut a = a0;
    while a < a1 {
        if !blocked(a) {
            out.push(instance("utility_pole", at(a), heading, &[], class("pole")));
            let b = a + WIRE_SPAN_M;
            if b < a1 && !blocked(b) {
                out.push(instance("wire_span", at(a), heading, &[], class("static")));
            }
        }
        a += WIRE_SPAN_M;
    }
}

/// Fixtures along one sidewalk from `a0` to `a1`: every 18–40 m a bench
/// (with a bin), in cities sometimes a bus shelter or a row of parking
/// meters, else a hydrant, bollards or a bin; only where `free(a, half
/// length)`. `place(a, off)` is the world position `off` m behind the
/// kerb; `facing` the heading that turns local −x to the road.
#[allow(clippy::too_many_arguments)]
pub fn sidewalk_fixtures(
    l: &Layout,
    style: StreetStyle,
    r: &mut Rng,
    (a0, a1): (f64, f64),
    place: &dyn Fn(f64, f64) -> [f64; 3],
    facing: f64,
    free: &dyn Fn(f64, f64) -> bool,
    out: &mut Vec<ObjectDesc>,
) {
    let sw = l.sidewalk_m;
    let st = class("static");
    let city = style == StreetStyle::City;
    let mut a = a0 + r.range(8.0, 30.0);
    while a < a1 {
        let u = r.f64();
        let bin = if city { "bin_box" } else { "bin_round" };
        // The along-road axis of a fixture is its local y: a heading of
        // `facing` lays it along the kerb.
        let dir = |a: f64| place(a, 0.0);
        let step = {
            let (p, q) = (dir(0.0), dir(1.0));
            [q[0] - p[0], q[1] - p[1]]
        };
        let shift = |at: [f64; 3], d: f64| [at[0] + step[0] * d, at[1] + step[1] * d, at[2]];
        if city && u < 0.15 && sw >= 3.0 && free(a, 2.2) {
            out.push(instance(
                "bus_shelter",
                place(a, sw - 0.95),
                facing,
                &[],
                st,
            ));
            out.push(instance(
                bin,
                shift(place(a, sw - 0.4), 2.8),
                facing,
                &[],
                st,
            ));
        } else if u < 0.45 && free(a, 1.6) {
            let bench = if r.chance(0.6) {
                "bench_wood"
            } else {
                "bench_steel"
            };
            out.push(instance(bench, place(a, sw - 0.45), facing, &[], st));
            out.push(instance(
                bin,
                shift(place(a, sw - 0.4), 1.4),
                facing,
                &[],
                st,
            ));
        } else if u < 0.6 && free(a, 0.5) {
            out.push(instance("hydrant", place(a, 0.45), facing, &[], st));
        } else if city && u < 0.8 && free(a, 9.5) {
            for k in 0..4 {
                let at = shift(place(a, 0.45), -9.0 + 6.0 * k as f64);
                out.push(instance("parking_meter", at, facing, &[], st));
            }
        } else if u < 0.9 && free(a, 2.0) {
            let b = if city {
                "bollard_steel"
            } else {
                "bollard_concrete"
            };
            for k in 0..3 {
                let at = shift(place(a, 0.35), -1.3 + 1.3 * k as f64);
                out.push(instance(b, at, facing, &[], st));
            }
        } else if free(a, 0.5) {
            out.push(instance(bin, place(a, 0.5), facing, &[], st));
        }
        a += r.range(18.0, 40.0);
    }
}

/// `[lo, hi]` minus the `cuts` (each `[c0, c1]`), as sorted intervals.
fn minus(lo: f64, hi: f64, mut cuts: Vec<(f64, f64)>) -> Vec<(f64, f64)> {
    cuts.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut out = Vec::new();
    let mut start = lo;
    for (c0, c1) in cuts {
        if c0 > start {
            out.push((start, c0.min(hi)));
        }
        start = start.max(c1);
    }
    if start < hi {
        out.push((start, hi));
    }
    out.retain(|(a, b)| b > a);
    out
}

/// Guard-rail units (`barriers::GUARD_RAILS`, longest first) filling
/// `[x0, x1]` along x at `y`, beam towards the road: north of it (`side`
/// = +1) the units run along +x (heading 0), south of it along −x (180).
fn rail_run(x0: f64, x1: f64, y: f64, side: f64, out: &mut Vec<ObjectDesc>) {
    let g = class("guard_rail");
    let mut x = x0;
    for (name, len) in GUARD_RAILS {
        while x + len <= x1 + 1e-9 {
            let (at, heading) = if side > 0.0 {
                (x, 0.0)
            } else {
                (x + len, 180.0)
            };
            out.push(instance(name, [at, y, 0.0], heading, &[], g));
            x += len;
        }
    }
}

/// Highway towns: guard rails along both sides of the outer x-roads
/// (the highways) at the outer edge of the shoulder, broken at junctions,
/// ramp sites and the overpass, and billboards on their outer sides
/// (beyond the ramps) every 150–300 m.
pub fn highway_runs(
    desc: &TownDesc,
    l: &Layout,
    style: StreetStyle,
    sites: &[RampSite],
    seed: u64,
) -> Vec<ObjectDesc> {
    let mut out = Vec::new();
    if !matches!(style, StreetStyle::Highway | StreetStyle::Country) {
        return out;
    }
    let mut r = Rng::new(&[seed, tag::FURNITURE, HIGHWAY]);
    let hw = l.road_w_m / 2.0;
    let keep = hw + l.sidewalk_m + 2.0;
    let overpass = Overpass::new(desc, l).map(|o| o.clear_zone());
    for (j, outer) in [(0, -1.0), (l.ny, 1.0)] {
        let y = j as f64 * l.pitch_m;
        let road = l.x_road(j);
        let (lo, hi) = (road.min[0], road.max[0]);
        for side in [-1.0, 1.0] {
            if style != StreetStyle::Highway {
                break;
            }
            let y_rail = y + side * (hw + l.sidewalk_m - 0.5);
            let mut cuts: Vec<(f64, f64)> = (0..=l.nx)
                .map(|i| i as f64 * l.pitch_m)
                .map(|x| (x - keep, x + keep))
                .collect();
            let zones = sites.iter().map(RampSite::clear_zone).chain(overpass);
            for z in zones {
                if y_rail > z.min[1] - 1.0 && y_rail < z.max[1] + 1.0 {
                    cuts.push((z.min[0], z.max[0]));
                }
            }
            for (a, b) in minus(lo, hi, cuts) {
                rail_run(a, b, y_rail, side, &mut out);
            }
        }
        // Billboards beyond the ramp sites (or the shoulder), facing the road.
        let beyond = sites
            .iter()
            .filter(|s| s.side == outer)
            .map(|s| (s.clear_zone().max[1] - s.clear_zone().min[1]) + 4.0)
            .fold(l.sidewalk_m + 5.0, f64::max);
        let mut a = lo + r.range(40.0, 150.0);
        while a < hi - 20.0 {
            let m = a.rem_euclid(l.pitch_m);
            let clear = m > keep + 10.0 && m < l.pitch_m - keep - 10.0;
            if clear && r.chance(0.7) {
                let k = r.index(SLOGANS.len());
                let at = [a, y + outer * (hw + beyond), 0.0];
                let heading = if outer > 0.0 { 90.0 } else { 270.0 };
                out.push(instance(
                    &format!("billboard_{k}"),
                    at,
                    heading,
                    &[],
                    class("static"),
                ));
            }
            a += r.range(150.0, 300.0);
        }
    }
    out
}

/// Kerb railings at every junction of a town with sidewalks: at each
/// corner, a `railing_run` 0.3 m behind the kerb of both roads, from 4 m
/// past the junction's edge (beyond the crosswalk) outwards; none along a
/// road that ends at the junction (the outer x-roads' T junctions).
pub fn corner_railings(l: &Layout, out: &mut Vec<ObjectDesc>) {
    if !l.sidewalks {
        return;
    }
    let hw = l.road_w_m / 2.0;
    let (from, kerb) = (hw + 4.0, hw + 0.3);
    let f = class("fence");
    for j in 0..=l.ny {
        for i in 0..=l.nx {
            let (x, y) = (i as f64 * l.pitch_m, j as f64 * l.pitch_m);
            for (sx, sy) in [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)] {
                // Along the x-road, then along the y-road where it goes on.
                let hx = if sx > 0.0 { 0.0 } else { 180.0 };
                out.push(instance(
                    "railing_run",
                    [x + sx * from, y + sy * kerb, l.walk_z()],
                    hx,
                    &[],
                    f,
                ));
                let ends = (j == 0 && sy < 0.0) || (j == l.ny && sy > 0.0);
                if !ends {
                    let hy = if sy > 0.0 { 90.0 } else { 270.0 };
                    let at = [x + sx * kerb, y + sy * from, l.walk_z()];
                    out.push(instance("railing_run", at, hy, &[], f));
                }
            }
        }
    }
}

/// Fences of the park and field blocks among `blocks`: palisades round
/// every park lawn (`park_fences`) and farm fences round every field.
pub fn enclosures(blocks: &[ObjectDesc]) -> Vec<ObjectDesc> {
    let mut out = park_fences(blocks);
    out.extend(field_fences(blocks));
    out
}

/// Farm fences on the west, north and east sides of every ploughed field
/// among `blocks` (its repeated ridges of material `crop`), 1 m outside
/// the ridges; the south side has its hedge.
fn field_fences(blocks: &[ObjectDesc]) -> Vec<ObjectDesc> {
    let mut out = Vec::new();
    for o in blocks {
        let (Some("crop"), ShapeDesc::Box { size }) = (o.material.as_deref(), &o.shape) else {
            continue;
        };
        let c = o.transform.translate.unwrap_or_default();
        let rows = o.repeat.first().map_or(1, |r| r.count);
        let pitch = o.repeat.first().map_or(0.0, |r| r.offset[1]);
        let (x0, x1) = (c[0] - size[0] / 2.0 - 1.0, c[0] + size[0] / 2.0 + 1.0);
        let y0 = c[1] - size[1] / 2.0 - 0.5;
        let y1 = c[1] + size[1] / 2.0 + (rows - 1) as f64 * pitch + 1.0;
        // (start, direction, length, heading): rails on each run's −y
        // side, that is inside the field.
        let runs = [
            ([x0, y0], [0.0, 1.0], y1 - y0, 90.0),
            ([x1, y1], [0.0, -1.0], y1 - y0, 270.0),
            ([x0, y1], [1.0, 0.0], x1 - x0, 0.0),
        ];
        for (p, d, len, heading) in runs {
            let n = (len / FARM_FENCE_M).floor() as usize;
            for k in 0..n {
                let s = k as f64 * FARM_FENCE_M;
                let at = [p[0] + d[0] * s, p[1] + d[1] * s, 0.0];
                out.push(instance("fence_farm", at, heading, &[], class("fence")));
            }
        }
    }
    out
}

/// Palisade fences round every park lawn among `blocks` (the quads of
/// material `lawn`), 0.3 m inside its edge, with a 3 m gate in the middle
/// of each side.
fn park_fences(blocks: &[ObjectDesc]) -> Vec<ObjectDesc> {
    let mut out = Vec::new();
    for o in blocks {
        let (Some("lawn"), ShapeDesc::Quad { size }) = (o.material.as_deref(), &o.shape) else {
            continue;
        };
        let c = o.transform.translate.unwrap_or_default();
        let lawn = Rect::centered([c[0], c[1]], *size);
        let (min, max) = (
            [lawn.min[0] + 0.3, lawn.min[1] + 0.3],
            [lawn.max[0] - 0.3, lawn.max[1] - 0.3],
        );
        // Counter-clockwise: (start corner, direction, length, heading).
        let sides = [
            (min, [1.0, 0.0], max[0] - min[0], 0.0),
            ([max[0], min[1]], [0.0, 1.0], max[1] - min[1], 90.0),
            (max, [-1.0, 0.0], max[0] - min[0], 180.0),
            ([min[0], max[1]], [0.0, -1.0], max[1] - min[1], 270.0),
        ];
        for (p, d, len, heading) in sides {
            let n = (len / PALISADE_M).floor() as usize;
            let gate = (len / 2.0 - 1.5, len / 2.0 + 1.5);
            for k in 0..n {
                let s = k as f64 * PALISADE_M;
                if s + PALISADE_M > gate.0 && s < gate.1 {
                    continue;
                }
                let at = [p[0] + d[0] * s, p[1] + d[1] * s, c[2].max(0.0)];
                out.push(instance("fence_palisade", at, heading, &[], class("fence")));
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn intervals_minus_cuts() {
        let got = minus(0.0, 100.0, vec![(90.0, 120.0), (-5.0, 10.0), (40.0, 50.0)]);
        assert_eq!(got, vec![(10.0, 40.0), (50.0, 90.0)]);
        assert_eq!(minus(0.0, 10.0, vec![]), vec![(0.0, 10.0)]);
        assert!(minus(0.0, 10.0, vec![(-1.0, 11.0)]).is_empty());
    }

    #[test]
    fn rail_runs_cover_the_interval_with_long_units_first() {
        let mut out = Vec::new();
        rail_run(10.0, 50.0, 3.0, 1.0, &mut out);
        // 40 m: one 32 m unit, two 4 m units, anchored at their west ends.
        let got: Vec<(&str, f64)> = out
            .iter()
            .map(|o| (prefab_of(o).unwrap(), o.transform.translate.unwrap()[0]))
            .collect();
        assert_eq!(
            got,
            vec![
                ("guard_rail_32", 10.0),
                ("guard_rail_4", 42.0),
                ("guard_rail_4", 46.0)
            ]
        );
        // South of the road the units run west from their east ends.
        out.clear();
        rail_run(10.0, 17.0, -3.0, -1.0, &mut out);
        assert_eq!(out.len(), 1);
        assert_eq!(out[0].transform.translate.unwrap()[0], 14.0);
        assert_eq!(out[0].transform.rotate_deg, Some([0.0, 0.0, 180.0]));
    }
}
