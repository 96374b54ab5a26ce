//! The concrete median barrier of a divided highway (`Layout::median`): a
//! New Jersey profile (`PROFILE`) extruded along the centreline of every
//! outer road, through the T junctions where town streets meet it, ending
//! at the loop's square corners (where the ring turns left inside the
//! junction) and following the curved loop corners' arcs.
//!
//! Built as one closed inline mesh (`MEDIAN_NAME`) with stations at most
//! `STEP_M` apart on straights and `ARC_STEP_M` on arcs, so a grade drapes
//! it like the ramps (h added to every vertex). Its foot is sunk
//! `SINK_M` into the road so no sliver of sky shows under it on a grade.
//! World frame z up, metres.

use glam::DVec3;

use crate::scene::desc::{ObjectDesc, TransformDesc};
use crate::scene::mesh::LocalMesh;

use crate::town::layout::{Layout, STUB_M};

/// Object name of the barrier mesh.
pub const MEDIAN_NAME: &str = "median_barrier";
/// Half the barrier's cross-section, (half width, height) from the foot up
/// the right face: 75 mm vertical reveal, a 55° face to 330 mm, an 84°
/// face to the 152 mm wide top at 810 mm (the New Jersey shape).
pub const PROFILE: [(f64, f64); 4] = [(0.305, 0.0), (0.305, 0.075), (0.1265, 0.33), (0.076, 0.81)];
/// Depth of the foot below the road surface, metres.
pub const SINK_M: f64 = 0.05;
/// Longest station step on straights, metres (the grade's drape step).
const STEP_M: f64 = 5.0;
/// Longest station step on arcs, metres (chord error ≤ 4 mm at R = 120 m).
const ARC_STEP_M: f64 = 2.0;

/// One run of the barrier along its centreline.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Run {
    /// A straight from `from` to `to`, world (x, y).
    Line {
        /// Start, world (x, y), metres.
        from: [f64; 2],
        /// End, world (x, y), metres.
        to: [f64; 2],
    },
    /// An arc of radius `r` about `centre` between polar angles θ0 < θ1.
    Arc {
        /// Centre, world (x, y), metres.
        centre: [f64; 2],
        /// Radius, metres.
        r: f64,
        /// Polar angles of the ends, radians.
        theta: (f64, f64),
    },
}

impl Run {
    /// Stations along the run: (point, unit direction), ends included.
    fn stations(&self) -> Vec<([f64; 2], [f64; 2])> {
        match *self {
            Run::Line { from, to } => {
                let d = [to[0] - from[0], to[1] - from[1]];
                let len = d[0].hypot(d[1]);
                let n = (len / STEP_M).ceil().max(1.0) as usize;
                let u = [d[0] / len, d[1] / len];
                (0..=n)
                    .map(|k| {
                        let t = k as f64 / n as f64;
                        ([from[0] + t * d[0], from[1] + t * d[1]], u)
                    })
                    .collect()
            }
            Run::Arc { centre, r, theta } => {
                let n = (r * (theta.1 - theta.0) / ARC_STEP_M).ceil().max(1.0) as usize;
                (0..=n)
                    .map(|k| {
                        let a = theta.0 + (theta.1 - theta.0) * k as f64 / n as f64;
                        let p = [centre[0] + r * a.cos(), centre[1] + r * a.sin()];
                        (p, [-a.sin(), a.cos()])
                    })
                    .collect()
            }
        }
    }
}

/// The barrier's runs: each divided x-road, then each divided y-road
/// (split at the square loop corners' junctions), then the curved corners.
pub fn runs(l: &Layout) -> Vec<Run> {
    if !l.median {
        return Vec::new();
    }
    let hw = l.road_w_m / 2.0;
    let mut out = Vec::new();
    // Along one road from a0 to a1, cut at the corner junctions' boxes.
    let mut road = |line: &dyn Fn(f64) -> [f64; 2], a0: f64, a1: f64, corners: &[f64]| {
        let mut at = a0;
        for &c in corners {
            if c - hw > at {
                out.push(Run::Line {
                    from: line(at),
                    to: line(c - hw),
                });
            }
            at = at.max(c + hw);
        }
        if a1 > at {
            out.push(Run::Line {
                from: line(at),
                to: line(a1),
            });
        }
    };
    let curved = l.loop_radius_m > 0.0;
    let r = l.loop_radius_m;
    for j in (0..=l.ny).filter(|&j| l.median_x(j)) {
        let y = j as f64 * l.pitch_m;
        let corners: Vec<f64> = [0, l.nx]
            .into_iter()
            .filter(|&i| !curved && l.median_y(i))
            .map(|i| i as f64 * l.pitch_m)
            .collect();
        let (a0, a1) = if curved {
            (r, l.len_x() - r)
        } else {
            (-STUB_M, l.len_x() + STUB_M)
        };
        road(&|a| [a, y], a0, a1, &corners);
    }
    for i in (0..=l.nx).filter(|&i| l.median_y(i)) {
        let x = i as f64 * l.pitch_m;
        let corners: Vec<f64> = [0, l.ny]
            .into_iter()
            .filter(|&j| !curved && l.median_x(j))
            .map(|j| j as f64 * l.pitch_m)
            .collect();
        let (a0, a1) = if curved {
            (r, l.len_y() - r)
        } else {
            (-hw, l.len_y() + hw)
        };
        road(&|a| [x, a], a0, a1, &corners);
    }
    out.extend(l.loop_corners().iter().map(|c| Run::Arc {
        centre: c.centre,
        r,
        theta: c.theta,
    }));
    out
}

/// The cross-section's corners, from the right foot up, over the top and
/// down the left face: (lateral offset to the left of the run, z).
fn ring() -> Vec<(f64, f64)> {
    let right = PROFILE.iter().map(|&(w, z)| (-w, z));
    let left = PROFILE.iter().rev().map(|&(w, z)| (w, z));
    let mut v: Vec<(f64, f64)> = right.chain(left).collect();
    v[0].1 = -SINK_M;
    let n = v.len();
    v[n - 1].1 = -SINK_M;
    v
}

/// Appends one run's closed solid: side faces between successive rings and
/// a fan cap at each end about the section's inner point (0, 0.35), from
/// which the concave profile is star-shaped.
fn extrude(run: &Run, m: &mut LocalMesh) {
    let sec = ring();
    let k = sec.len() as u32;
    let st = run.stations();
    let base = m.positions.len() as u32;
    for (p, u) in &st {
        let left = [-u[1], u[0]];
        for &(o, z) in &sec {
            m.positions
                .push(DVec3::new(p[0] + o * left[0], p[1] + o * left[1], z));
        }
    }
    for s in 0..st.len() as u32 - 1 {
        let (a, b) = (base + s * k, base + (s + 1) * k);
        for e in 0..k {
            let f = (e + 1) % k;
            // Outward: the ring runs clockwise seen from ahead.
            m.triangles.push([a + e, b + e, b + f]);
            m.triangles.push([a + e, b + f, a + f]);
        }
    }
    for (end, (p, _)) in [(0u32, st[0]), (st.len() as u32 - 1, st[st.len() - 1])] {
        let c = m.positions.len() as u32;
        m.positions.push(DVec3::new(p[0], p[1], 0.35));
        let first = base + end * k;
        for e in 0..k {
            let f = (e + 1) % k;
            // Seen from ahead the ring runs clockwise: the start cap faces
            // back as is, the end cap ahead reversed.
            if end == 0 {
                m.triangles.push([c, first + e, first + f]);
            } else {
                m.triangles.push([c, first + f, first + e]);
            }
        }
    }
}

/// The barrier as one inline mesh object (none without a median).
pub fn median_meshes(l: &Layout) -> Vec<ObjectDesc> {
    let runs = runs(l);
    if runs.is_empty() {
        return Vec::new();
    }
    let mut mesh = LocalMesh::default();
    for r in &runs {
        extrude(r, &mut mesh);
    }
    vec![ObjectDesc {
        name: Some(MEDIAN_NAME.to_string()),
        material: Some("concrete".to_string()),
        semantic: Some("guard_rail".to_string()),
        instance: None,
        transform: TransformDesc::default(),
        repeat: Vec::new(),
        shape: mesh.into_shape(),
    }]
}
