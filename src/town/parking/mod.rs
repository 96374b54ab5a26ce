//! Parked cars (`parking_density`) in the parking lanes of a town that
//! has them (`parking_lane_m`, see `lane`), else in lay-bys: bays cut into the road-side
//! part of the sidewalk, at road level behind a kerb of their own, in runs
//! of 6 m bays between the street trees, lamps, signs and fixtures that
//! stand there, never near a junction (its corners, crosswalks and stop
//! lines), a bus shelter, the roundabout, a bridge or a loop corner. Each
//! bay holds a seeded, parallel-parked car with probability
//! `parking_density` (`cars`); the sidewalk, kerb and bay surface are
//! rebuilt round the runs (`layby`).
//!
//! A bay is as deep as the sidewalk allows while its kerb stays clear of
//! the walkers' inner lane (`walkers`: the lanes lie ±0.45 m about the
//! sidewalk's middle line, 0.1 m towards the block) by a person's half
//! width, and at most 2.3 m; the town description must leave at least
//! 2.15 m, room for a sedan (`min_sidewalk_m`). Driving lanes end at the
//! road edge, so a parked car (mirrors included) stays beyond it.

pub mod cars;
pub mod lane;
pub mod layby;

use crate::scene::desc::{ObjectDesc, ShapeDesc};
use crate::town::underpass::Underpass;

use super::desc::{RoadStyle, TownDesc};
use super::layout::{Layout, Rect};
use super::roads::Axis;

pub use cars::parked_cars;
pub use layby::cut_laybys;

/// Length of one bay along the kerb, metres.
pub const BAY_LEN_M: f64 = 6.0;
/// Width of a bay's own kerb (between bay and sidewalk), metres.
pub const KERB_M: f64 = 0.15;
/// Shallowest bay (a sedan fits, mirrors included) and deepest, metres.
pub const DEPTH_M: (f64, f64) = (2.15, 2.3);
/// Half the width of the widest walker (shoulders, swinging arms and
/// hands, a bag), metres: 0.34 m measured over every look and phase.
pub const WALKER_HALF_M: f64 = 0.35;
/// Clearance round a furniture item standing in the bay zone, metres.
const ITEM_CLEAR_M: f64 = 0.8;
/// Clearance round a tree (its pit is 1.2 m square), metres.
const TREE_CLEAR_M: f64 = 1.3;
/// Kerb length kept free for a bus either side of a shelter, metres.
const BUS_STOP_M: f64 = 12.0;

/// Distance of the walkers' inner lane from the road edge for a sidewalk
/// `sw` wide (`walkers`: lanes at sw/2 + 0.1 ± 0.45 from the road edge).
pub fn walker_inner_m(sw: f64) -> f64 {
    sw / 2.0 + 0.1 - 0.45
}

/// Depth of the bays of a sidewalk `sw` wide: as deep as the walkers'
/// inner lane allows, at most `DEPTH_M.1`.
pub fn bay_depth_m(sw: f64) -> f64 {
    (walker_inner_m(sw) - WALKER_HALF_M - KERB_M).min(DEPTH_M.1)
}

/// Narrowest sidewalk that takes a bay `DEPTH_M.0` deep, metres.
pub fn min_sidewalk_m() -> f64 {
    2.0 * (DEPTH_M.0 + KERB_M + WALKER_HALF_M + 0.45 - 0.1)
}

/// Checks `parking_density` of `desc`: in [0, 1]; above 0 only in a level
/// grid town with sidewalks wide enough for bays.
pub fn validate(desc: &TownDesc) -> Result<(), String> {
    let d = desc.parking_density;
    if !(0.0..=1.0).contains(&d) {
        return Err(format!("parking_density: must be in [0, 1], got {d}"));
    }
    // A parking lane (checked by `lane::validate`) takes the cars instead.
    if d == 0.0 || desc.parking_lane_m > 0.0 {
        return Ok(());
    }
    let plain = desc.sidewalks
        && desc.road_style == RoadStyle::Grid
        && desc.road_grade_m == 0.0
        && !desc.ramps
        && !desc.overpass;
    if !plain {
        return Err(format!(
            "parking_density: lay-bys need a level grid town with sidewalks and no ramps \
             (road_style = \"grid\", sidewalks = true, road_grade_m = 0, ramps = false); \
             got road_style = {:?}, sidewalks = {}, road_grade_m = {}, ramps = {}",
            desc.road_style, desc.sidewalks, desc.road_grade_m, desc.ramps
        ));
    }
    let need = min_sidewalk_m();
    if desc.sidewalk_width_m < need - 1e-9 {
        return Err(format!(
            "parking_density: a lay-by {} m deep and its kerb must stay clear of the \
             walkers' lane, which needs sidewalk_width_m ≥ {need:.2}, got {}",
            DEPTH_M.0, desc.sidewalk_width_m
        ));
    }
    Ok(())
}

/// One parking bay: `BAY_LEN_M` of kerb on one side of one road.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bay {
    /// The road's direction.
    pub axis: Axis,
    /// The road's index (j of an x-road, i of a y-road).
    pub road: usize,
    /// Centreline coordinate (y of an x-road, x of a y-road), metres.
    pub c: f64,
    /// Which side: +1 towards +y (x-roads) or +x (y-roads), −1 the other.
    pub side: f64,
    /// Extent along the road, metres.
    pub along: (f64, f64),
    /// Where the bay starts from the centreline: the road edge (a
    /// lay-by) or the driving lanes' edge (a parking lane), metres.
    pub hw: f64,
    /// Depth from the road edge to the bay's kerb, metres.
    pub depth: f64,
}

impl Bay {
    /// World (x, y) of the point `along` the road and `off` metres from
    /// the road's centreline on the bay's side.
    pub fn world(&self, along: f64, off: f64) -> [f64; 2] {
        let across = self.c + self.side * off;
        match self.axis {
            Axis::X => [along, across],
            Axis::Y => [across, along],
        }
    }

    /// The world rectangle over `along` and offsets (`u0`, `u1`) from the
    /// centreline on the bay's side.
    pub fn strip(&self, (a0, a1): (f64, f64), (u0, u1): (f64, f64)) -> Rect {
        let (p, q) = (self.world(a0, u0), self.world(a1, u1));
        Rect {
            min: [p[0].min(q[0]), p[1].min(q[1])],
            max: [p[0].max(q[0]), p[1].max(q[1])],
        }
    }

    /// The bay's surface in plan: from the road edge to its kerb.
    pub fn rect(&self) -> Rect {
        self.strip(self.along, (self.hw, self.hw + self.depth))
    }

    /// Heading of traffic on the bay's side (right-hand traffic), degrees.
    pub fn heading_deg(&self) -> f64 {
        match (self.axis, self.side > 0.0) {
            (Axis::X, false) => 0.0,
            (Axis::X, true) => 180.0,
            (Axis::Y, true) => 90.0,
            (Axis::Y, false) => 270.0,
        }
    }
}

/// Every bay of the town of `desc`: the parking lanes' (`lane`) if it
/// has them, else the lay-bys' along both sides of every road section
/// between junction areas, in the gaps that the road-side `furniture`
/// leaves. None when `parking_density` is 0.
pub fn bays(desc: &TownDesc, l: &Layout, furniture: &[ObjectDesc]) -> Vec<Bay> {
    if desc.parking_lane_m > 0.0 {
        return lane::lane_bays(desc, l, furniture);
    }
    if desc.parking_density <= 0.0 || !l.sidewalks {
        return Vec::new();
    }
    let (p, hw) = (l.pitch_m, l.road_w_m / 2.0);
    let depth = bay_depth_m(l.sidewalk_m);
    // As `furniture` keeps lamps and trees off the junction areas.
    let keep = hw + l.sidewalk_m + 6.0;
    let mut out = Vec::new();
    for (axis, road, side, k) in road_sections(l) {
        let bay = Bay {
            axis,
            road,
            c: road as f64 * p,
            side,
            along: (k as f64 * p + keep, (k + 1) as f64 * p - keep),
            hw,
            depth,
        };
        section_bays(l, &bay, furniture, Zone::Layby, &mut out);
    }
    out
}

/// Every side of every road section between grid nodes: (axis, road
/// index, side ∓1, section k), x-roads first, then each road's sides in
/// turn, sections in order.
pub(crate) fn road_sections(l: &Layout) -> impl Iterator<Item = (Axis, usize, f64, usize)> {
    let roads = (0..=l.ny)
        .map(|j| (Axis::X, j, l.nx))
        .chain((0..=l.nx).map(|i| (Axis::Y, i, l.ny)))
        .collect::<Vec<_>>();
    roads.into_iter().flat_map(|(axis, road, sections)| {
        [-1.0, 1.0]
            .into_iter()
            .flat_map(move |side| (0..sections).map(move |k| (axis, road, side, k)))
    })
}

/// Where a section's bays lie, which decides what furniture cuts them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Zone {
    /// Cut into the sidewalk: every item standing there, and bus stops.
    Layby,
    /// On the road (a parking lane): bus stops only.
    Lane,
}

/// The bays of one road section (`sec.along`), in the gaps between the
/// furniture standing in its bay zone (lay-bys) and the bus stops.
pub(crate) fn section_bays(
    l: &Layout,
    sec: &Bay,
    furniture: &[ObjectDesc],
    kind: Zone,
    out: &mut Vec<Bay>,
) {
    let (a0, a1) = sec.along;
    if a1 - a0 < BAY_LEN_M {
        return;
    }
    let zone = sec.strip(sec.along, (sec.hw, sec.hw + sec.depth + KERB_M + 0.5));
    // From the bay's inner edge to the sidewalk's back.
    let walk = sec.strip(sec.along, (sec.hw, l.road_w_m / 2.0 + l.sidewalk_m));
    let along_of = |p: [f64; 2]| match sec.axis {
        Axis::X => p[0],
        Axis::Y => p[1],
    };
    let mut cuts: Vec<(f64, f64)> = Vec::new();
    for o in furniture {
        let Some(f) = footprint(o) else { continue };
        let (lo, hi) = (along_of(f.min), along_of(f.max));
        if is_prefab(o, "bus_shelter") && walk.overlaps(&f) {
            cuts.push((lo - BUS_STOP_M, hi + BUS_STOP_M));
        } else if kind == Zone::Layby && zone.overlaps(&f) {
            let r = if o.semantic.as_deref() == Some("vegetation") {
                TREE_CLEAR_M
            } else {
                ITEM_CLEAR_M
            };
            cuts.push((lo - r, hi + r));
        }
    }
    cuts.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut start = a0;
    for (c0, c1) in cuts.into_iter().chain([(a1, a1)]) {
        if c0 > start {
            run(l, sec, (start, c0.min(a1)), out);
        }
        start = start.max(c1);
    }
}

/// Whole bays centred in the free stretch `(s0, s1)`, skipping any that
/// would reach the roundabout, a bridge, the underpass's cut or a loop corner.
fn run(l: &Layout, sec: &Bay, (s0, s1): (f64, f64), out: &mut Vec<Bay>) {
    let n = ((s1 - s0) / BAY_LEN_M + 1e-9).floor();
    if n < 1.0 {
        return;
    }
    let first = 0.5 * (s0 + s1) - 0.5 * n * BAY_LEN_M;
    for m in 0..n as usize {
        let a = first + m as f64 * BAY_LEN_M;
        let bay = Bay {
            along: (a, a + BAY_LEN_M),
            ..*sec
        };
        let r = bay.strip(bay.along, (bay.hw, l.road_w_m / 2.0 + l.sidewalk_m));
        let on_bridge = l.river_band().is_some_and(|b| b.overlaps(&r));
        let corner = [r.min, r.max, [r.min[0], r.max[1]], [r.max[0], r.min[1]]]
            .iter()
            .any(|&q| l.in_loop_corner(q));
        let by_cut = Underpass::of(l).is_some_and(|u| u.beside(&r));
        if !on_bridge && !corner && !by_cut && !l.near_roundabout(&r) {
            out.push(bay);
        }
    }
}

/// Whether `o` is an instance of prefab `name`.
fn is_prefab(o: &ObjectDesc, name: &str) -> bool {
    matches!(&o.shape, ShapeDesc::Instance { prefab, .. } if prefab == name)
}

/// Plan footprint of a furniture object: its anchor for an instance (the
/// clearances add the item's size), its turned outline for a box or quad.
pub fn footprint(o: &ObjectDesc) -> Option<Rect> {
    let t = o.transform.translate?;
    let half = match &o.shape {
        ShapeDesc::Box { size } => [size[0] / 2.0, size[1] / 2.0],
        ShapeDesc::Quad { size } => [size[0] / 2.0, size[1] / 2.0],
        _ => [0.0, 0.0],
    };
    let turn = o.transform.rotate_deg.map_or(0.0, |r| r[2].to_radians());
    let (s, c) = turn.sin_cos();
    let ex = [
        (c * half[0]).abs() + (s * half[1]).abs(),
        (s * half[0]).abs() + (c * half[1]).abs(),
    ];
    Some(Rect {
        min: [t[0] - ex[0], t[1] - ex[1]],
        max: [t[0] + ex[0], t[1] + ex[1]],
    })
}

#[cfg(test)]
mod tests;
