//! How much of a town's lanes a set of drives passes.
//!
//! Drivable lane length: every lane of every directed link (one direction
//! of a road between adjacent junctions), from junction edge to junction
//! edge: a plain junction's interior is the square of the road's half
//! width about its centre; the roundabout's reaches to its arms'
//! keep-clear start (the ring itself is junction interior); a curved loop
//! corner counts as interior up to its tangent points, so the curve is
//! excluded. Stubs past the town edge are no lanes. Each lane piece is cut
//! into cells of `CELL_M`; a cell is covered once the ego's centre has
//! been inside its lane band (`w` wide beside the lane's line), heading
//! its way (within 45°), in some frame.

use std::collections::BTreeSet;

use super::ego::{ego_motion, turns_by};
use crate::town::desc::TownDesc;
use crate::town::layout::Layout;
use crate::town::roundabout::arm_start_m;
use crate::town::routes::drive::links;

/// Length of one coverage cell along a lane, metres.
pub const CELL_M: f64 = 5.0;

/// Coverage of a set of drives.
#[derive(Clone, Debug, PartialEq)]
pub struct Coverage {
    /// Drivable lane length of the town, metres.
    pub lane_m: f64,
    /// Length of the covered cells, metres.
    pub covered_m: f64,
    /// Drives measured.
    pub drives: u64,
    /// Distinct ego trajectories among the drives (positions at every
    /// 10th frame compared bit for bit).
    pub distinct_drives: u64,
    /// Junction turns per drive, on average.
    pub turns_per_drive: f64,
}

impl Coverage {
    /// Covered fraction of the lane length.
    pub fn fraction(&self) -> f64 {
        self.covered_m / self.lane_m
    }
}

/// One lane piece: the link, the lane, where along the link it starts,
/// and its cell count.
struct Piece {
    from: [f64; 2],
    dir: [f64; 2],
    lane: u32,
    start_m: f64,
    cells: usize,
    cell_m: f64,
}

/// Distance from a junction's centre to its edge along a road.
fn edge_m(l: &Layout, i: usize, j: usize) -> f64 {
    if l.loop_corner_at(i, j) {
        l.loop_radius_m
    } else if l.roundabout == Some((i, j)) {
        arm_start_m(l)
    } else {
        l.road_w_m / 2.0
    }
}

fn pieces(l: &Layout) -> Vec<Piece> {
    let mut out = Vec::new();
    for ((i, j), d) in links(l) {
        let u = [[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]][d];
        let to = (
            (i as f64 + u[0]).round() as usize,
            (j as f64 + u[1]).round() as usize,
        );
        let a = edge_m(l, i, j);
        let len = l.pitch_m - a - edge_m(l, to.0, to.1);
        if len <= 0.0 {
            continue;
        }
        let cells = (len / CELL_M).ceil() as usize;
        for lane in 0..l.lanes {
            out.push(Piece {
                from: [i as f64 * l.pitch_m, j as f64 * l.pitch_m],
                dir: u,
                lane,
                start_m: a,
                cells,
                cell_m: len / cells as f64,
            });
        }
    }
    out
}

/// Coverage of drives `drives` of `frames` town frames each.
pub fn coverage(desc: &TownDesc, seed: u64, drives: std::ops::Range<u64>, frames: u64) -> Coverage {
    let l = Layout::new(desc);
    let ps = pieces(&l);
    let w = l.lane_w_m;
    let mut covered = BTreeSet::new();
    let mut trajectories = BTreeSet::new();
    let mut turns = 0usize;
    for drive in drives.clone() {
        let mut seen = Vec::new();
        for k in 0..frames {
            let e = ego_motion(desc, seed, drive, k).0;
            if k % 10 == 0 {
                seen.push(e.position.map(f64::to_bits));
            }
            let h = e.heading_deg.to_radians();
            for (n, p) in ps.iter().enumerate() {
                if h.cos() * p.dir[0] + h.sin() * p.dir[1] < std::f64::consts::FRAC_1_SQRT_2 {
                    continue;
                }
                let r = [e.position[0] - p.from[0], e.position[1] - p.from[1]];
                let along = r[0] * p.dir[0] + r[1] * p.dir[1] - p.start_m;
                // To the right of the direction: (d_y, −d_x).
                let side = r[0] * p.dir[1] - r[1] * p.dir[0];
                let band = p.lane as f64 * w..(p.lane + 1) as f64 * w;
                if along >= 0.0 && band.contains(&side) {
                    let c = (along / p.cell_m) as usize;
                    if c < p.cells {
                        covered.insert((n, c));
                    }
                }
            }
        }
        turns += turns_by(desc, seed, drive, frames - 1);
        trajectories.insert(seen);
    }
    let lane_m = ps.iter().map(|p| p.cells as f64 * p.cell_m).sum();
    let covered_m = covered.iter().map(|&(n, _)| ps[n].cell_m).sum();
    let n = drives.end - drives.start;
    Coverage {
        lane_m,
        covered_m,
        drives: n,
        distinct_drives: trajectories.len() as u64,
        turns_per_drive: turns as f64 / n.max(1) as f64,
    }
}
