//! Parking lanes (`parking_lane_m`): a strip at road level on each side of
//! every road, between the outer driving lane's edge and the kerb (the
//! road is wider by the two strips; the driving lanes keep their place
//! about the centreline, the kerb and everything beyond it move out).
//! Its bays are 6 m long, in runs between the junction areas (corners,
//! crosswalks, stop lines), away from bus stops, bridges, the roundabout
//! and the underpass's cut and deck; a solid white edge line (`roads`)
//! separates the strip from the driving lane and short white ticks mark
//! the bays' ends. The cars themselves are the lay-bys' (`cars`).

use crate::scene::desc::ObjectDesc;

use super::super::desc::{RoadStyle, TownDesc};
use super::super::layout::Layout;
use super::super::parts::{class, slab};
use super::super::roads::Axis;
use super::super::roundabout::arm_start_m;
use super::{min_sidewalk_m, section_bays, Bay, Zone, BAY_LEN_M, DEPTH_M};

/// Range of `parking_lane_m`, metres: from the narrowest strip that takes
/// a sedan with its mirrors (as the shallowest lay-by) to a wide one.
pub const LANE_RANGE_M: (f64, f64) = (DEPTH_M.0, 2.6);
/// Free road beyond a junction's edge: its crosswalk (to 3.5 m), its stop
/// line (4.0–4.2 m) and 0.8 m, metres.
pub const JUNCTION_CLEAR_M: f64 = 5.0;
/// Free road beyond the ring's arm start: the set-back crosswalk (6 +
/// 3.5 m) and 1 m, metres.
const RING_CLEAR_M: f64 = 10.5;
/// Bay end ticks: width, and how far they reach into the strip past the
/// edge line, metres.
const TICK_W_M: f64 = 0.1;
const TICK_M: f64 = 0.5;
/// The edge line's outer side from the driving lane's edge (`roads`:
/// a 0.15 m line centred 0.25 m inside the lane), metres.
const EDGE_LINE_OUT_M: f64 = -0.175;
/// Paint: bottom and top, metres (as the road markings).
const PAINT_Z: (f64, f64) = (0.0, 0.008);

/// Checks `parking_lane_m`: 0, or in `LANE_RANGE_M` in a level grid or
/// organic town with sidewalks too narrow for lay-bys.
pub fn validate(desc: &TownDesc) -> Result<(), String> {
    let w = desc.parking_lane_m;
    if w == 0.0 {
        return Ok(());
    }
    let (lo, hi) = LANE_RANGE_M;
    if !(w.is_finite() && (lo..=hi).contains(&w)) {
        return Err(format!(
            "parking_lane_m: must be 0 or in [{lo}, {hi}], got {w}"
        ));
    }
    let plain = desc.sidewalks
        && desc.road_style != RoadStyle::Highway
        && desc.road_grade_m == 0.0
        && !desc.ramps
        && !desc.overpass;
    if !plain {
        return Err(format!(
            "parking_lane_m: a parking lane needs a level grid or organic town with sidewalks \
             (road_style = \"grid\" or \"organic\", sidewalks = true, road_grade_m = 0, no ramps \
             or overpass); got road_style = {:?}, sidewalks = {}, road_grade_m = {}, ramps = {}",
            desc.road_style, desc.sidewalks, desc.road_grade_m, desc.ramps
        ));
    }
    let layby = min_sidewalk_m();
    if desc.sidewalk_width_m >= layby - 1e-9 {
        return Err(format!(
            "parking_lane_m: a town has a parking lane or lay-bys, not both: sidewalks \
             ≥ {layby:.2} m take lay-bys (parking_density alone), got sidewalk_width_m = {}",
            desc.sidewalk_width_m
        ));
    }
    Ok(())
}

/// Every bay of the parking lanes of the town of `desc`: both sides of
/// every road section between junction areas, off the bus stops among
/// the road-side `furniture`. None without a lane or cars for it.
pub fn lane_bays(desc: &TownDesc, l: &Layout, furniture: &[ObjectDesc]) -> Vec<Bay> {
    if desc.parking_lane_m <= 0.0 || desc.parking_density <= 0.0 || !l.sidewalks {
        return Vec::new();
    }
    let p = l.pitch_m;
    let keep = l.road_w_m / 2.0 + JUNCTION_CLEAR_M;
    let ring_keep = keep.max(arm_start_m(l) + RING_CLEAR_M);
    // How far a section keeps from grid node (i, j) at its end.
    let keep_at = |i: usize, j: usize| {
        if l.roundabout == Some((i, j)) {
            ring_keep
        } else {
            keep
        }
    };
    let mut out = Vec::new();
    for (axis, road, side, k) in super::road_sections(l) {
        let (n0, n1) = match axis {
            Axis::X => ((k, road), (k + 1, road)),
            Axis::Y => ((road, k), (road, k + 1)),
        };
        let sec = Bay {
            axis,
            road,
            c: road as f64 * p,
            side,
            along: (
                k as f64 * p + keep_at(n0.0, n0.1),
                (k + 1) as f64 * p - keep_at(n1.0, n1.1),
            ),
            hw: l.drive_hw(),
            depth: l.parking_m,
        };
        section_bays(l, &sec, furniture, Zone::Lane, &mut out);
    }
    out
}

/// Short white ticks at both ends of every bay, from the edge line into
/// the strip (class `road_line`).
pub fn bay_marks(bays: &[Bay]) -> Vec<ObjectDesc> {
    let mut out = Vec::new();
    for r in super::layby::runs(bays) {
        let n = ((r.along.1 - r.along.0) / BAY_LEN_M).round() as usize;
        for k in 0..=n {
            let a = r.along.0 + k as f64 * BAY_LEN_M;
            let across = (r.hw + EDGE_LINE_OUT_M, r.hw + TICK_M);
            let t = r.strip((a - TICK_W_M / 2.0, a + TICK_W_M / 2.0), across);
            out.push(slab(
                t.min,
                t.max,
                PAINT_Z.0,
                PAINT_Z.1,
                "paint_white_road",
                class("road_line"),
            ));
        }
    }
    out
}
