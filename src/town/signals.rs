//! Traffic signals that show the phase of the town's stop-and-go clock
//! (`traffic::Schedule`). Every cross junction has one traffic light per
//! approach, on the approach's right-hand corner before the junction, its
//! heads facing the approaching traffic (`signal_sites`, placed by
//! `furniture`). A head lights exactly one lamp: green from the start of
//! the clock's ramp up through the drive (vehicles move off as it turns
//! green, so there is no red+amber phase), amber through the ramp down,
//! red while everything stands (when pedestrians cross). Approaches that
//! only the ring drives (it ignores the clock) show green always; those no
//! route uses follow the clock. The lamps of frame K are a pure function of
//! (desc, K), set on the traffic-light instances as a material map from the
//! lens slots of `props::LENS_SLOTS` to their emitters.

use std::collections::BTreeMap;

use crate::scene::desc::{ObjectDesc, ShapeDesc};

use super::desc::TownDesc;
use super::layout::Layout;
use super::props::LENS_SLOTS;
use super::routes::{Route, RouteKind, Segment};
use super::traffic::{Plan, Schedule};

/// Name of the traffic-light prefab of one-lane approaches (`street::lights`).
pub const PREFAB: &str = "traffic_light";
/// Every traffic-light prefab: the corner pole with a short arm, and the
/// mast arm with one head per lane of two-lane approaches.
pub const PREFABS: [&str; 2] = [PREFAB, super::street::lights::SIGNAL_MAST];
/// How far before a junction's edge a route's straight counts as one of
/// its approaches, metres.
const APPROACH_M: f64 = 20.0;

/// The lamp a signal head shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Lamp {
    /// Stop: the clock stands.
    Red,
    /// Stop if you can: the clock ramps down.
    Amber,
    /// Go: the clock ramps up or drives.
    Green,
}

impl Lamp {
    /// Every lamp, top to bottom in a head.
    pub const ALL: [Lamp; 3] = [Lamp::Red, Lamp::Amber, Lamp::Green];

    /// The prefab's material slot of this lamp's lens (dark glass).
    pub fn slot(self) -> &'static str {
        LENS_SLOTS[self as usize]
    }

    /// The emissive material the slot shows when lit (`materials`).
    pub fn lit(self) -> &'static str {
        ["signal_red_lit", "signal_amber_lit", "signal_green_lit"][self as usize]
    }
}

/// Who drives an approach.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Approach {
    /// Block loops only: they stand while the clock stands.
    Clock,
    /// The ring drives it (it never stands); routes share no lane, so no
    /// block loop does.
    Free,
    /// No route.
    Empty,
}

/// One traffic light: a pole on the right-hand corner before a junction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SignalSite {
    /// Junction (i, j): where y-road i crosses x-road j.
    pub junction: (usize, usize),
    /// Heading of the traffic it controls, degrees counter-clockwise from
    /// +x (0, 90, 180 or 270); also the prefab's heading, whose heads face
    /// local −x, towards that traffic.
    pub heading_deg: f64,
    /// Foot of the pole, world metres.
    pub at: [f64; 3],
}

impl SignalSite {
    /// Unit vector of the controlled traffic's heading (x, y).
    pub fn dir(&self) -> [f64; 2] {
        let h = self.heading_deg.to_radians();
        [h.cos().round(), h.sin().round()]
    }

    /// The junction centre, world metres (x, y).
    pub fn centre(&self, l: &Layout) -> [f64; 2] {
        let (i, j) = self.junction;
        [i as f64 * l.pitch_m, j as f64 * l.pitch_m]
    }
}

/// The four traffic lights of junction (i, j), in placement order:
/// eastbound, westbound, northbound, southbound approaches.
pub fn junction_sites(l: &Layout, i: usize, j: usize) -> [SignalSite; 4] {
    let c = l.road_w_m / 2.0 + 0.5;
    let (x, y) = (i as f64 * l.pitch_m, j as f64 * l.pitch_m);
    [
        ([-c, -c], 0.0),
        ([c, c], 180.0),
        ([c, -c], 90.0),
        ([-c, c], 270.0),
    ]
    .map(|(d, heading_deg)| SignalSite {
        junction: (i, j),
        heading_deg,
        at: [x + d[0], y + d[1], l.walk_z()],
    })
}

/// Whether junction (i, j) has traffic lights: every cross junction, on
/// x-roads j = 1 .. ny − 1 (the outer x-roads end y-roads in T junctions
/// with stop signs), but the roundabout.
pub fn has_signals(l: &Layout, i: usize, j: usize) -> bool {
    j > 0 && j < l.ny && i <= l.nx && l.roundabout != Some((i, j))
}

/// Every traffic light of the town (`junction_sites` of every junction
/// that `has_signals`, by x-road, then y-road).
pub fn signal_sites(l: &Layout) -> Vec<SignalSite> {
    (1..l.ny)
        .flat_map(|j| (0..=l.nx).map(move |i| (i, j)))
        .filter(|&(i, j)| has_signals(l, i, j))
        .flat_map(|(i, j)| junction_sites(l, i, j))
        .collect()
}

/// Who drives the approach of `site`: the routes with a straight on its
/// side of the road (right-hand traffic), heading its way, that runs up
/// to within `APPROACH_M` of the junction's edge from before it.
pub fn approach(l: &Layout, routes: &[&Route], site: &SignalSite) -> Approach {
    let d = site.dir();
    let right = [d[1], -d[0]];
    let c = site.centre(l);
    let hw = l.road_w_m / 2.0;
    let (mut clock, mut free) = (false, false);
    for r in routes {
        for seg in &r.segments {
            let Segment::Line {
                from,
                heading,
                len_m,
            } = *seg
            else {
                continue;
            };
            if (heading.cos() - d[0]).abs() > 1e-6 || (heading.sin() - d[1]).abs() > 1e-6 {
                continue;
            }
            let rel = [from[0] - c[0], from[1] - c[1]];
            let a0 = rel[0] * d[0] + rel[1] * d[1];
            let lat = rel[0] * right[0] + rel[1] * right[1];
            if lat > 0.0 && lat < hw && a0 < -hw && a0 + len_m > -hw - APPROACH_M {
                match r.kind {
                    RouteKind::Ring | RouteKind::Overpass => free = true,
                    RouteKind::Block { .. } => clock = true,
                }
            }
        }
    }
    match (free, clock) {
        (true, _) => Approach::Free,
        (false, true) => Approach::Clock,
        (false, false) => Approach::Empty,
    }
}

/// The lamp the clock shows at time `t`: green from the start of the ramp
/// up to the end of the drive, amber through the ramp down, red during the
/// stand (exactly when `Schedule::standing`).
pub fn clock_lamp(s: &Schedule, t: f64) -> Lamp {
    let tau = t.rem_euclid(s.cycle_s());
    if tau >= s.moving_s() {
        Lamp::Red
    } else if tau >= s.go_s {
        Lamp::Amber
    } else {
        Lamp::Green
    }
}

/// One traffic light in one frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Signal {
    /// Where it stands and what it controls.
    pub site: SignalSite,
    /// Who drives its approach.
    pub approach: Approach,
    /// The lamp both its heads show.
    pub lamp: Lamp,
}

/// Every traffic light of the town (`signal_sites` order) at `frame`
/// (time frame / fps, as `traffic::frame_at`).
pub fn signals_at(desc: &TownDesc, frame: u64) -> Vec<Signal> {
    signals_on(desc, &Layout::new(desc), frame)
}

/// [`signals_at`] on the town's already built layout `l`.
fn signals_on(desc: &TownDesc, l: &Layout, frame: u64) -> Vec<Signal> {
    let plan = Plan::new(desc);
    let routes: Vec<&Route> = plan.routes.iter().map(|p| &p.route).collect();
    let lamp = clock_lamp(&plan.schedule, frame as f64 / desc.fps);
    signal_sites(l)
        .into_iter()
        .map(|site| {
            let approach = approach(l, &routes, &site);
            Signal {
                site,
                approach,
                lamp: if approach == Approach::Free {
                    Lamp::Green
                } else {
                    lamp
                },
            }
        })
        .collect()
}

/// Lights the lamps of `frame` on every traffic-light instance in
/// `objects`: its lit lens slot maps to the emitter, the other two stay
/// dark glass. Instances are matched to sites by junction and heading;
/// `l` is the town's layout (`Layout::new(desc)`, built once per town).
pub fn set_lamps(desc: &TownDesc, l: &Layout, frame: u64, objects: &mut [ObjectDesc]) {
    let lamps: BTreeMap<(usize, usize, i64), Lamp> = signals_on(desc, l, frame)
        .iter()
        .map(|s| (key(l, s.site.at, s.site.heading_deg), s.lamp))
        .collect();
    for o in objects {
        let ShapeDesc::Instance {
            prefab,
            material_map,
        } = &mut o.shape
        else {
            continue;
        };
        if !PREFABS.contains(&prefab.as_str()) {
            continue;
        }
        let at = o.transform.translate.unwrap_or_default();
        let heading = o.transform.rotate_deg.map_or(0.0, |r| r[2]);
        let Some(&lamp) = lamps.get(&key(l, at, heading)) else {
            continue;
        };
        for other in Lamp::ALL {
            material_map.remove(other.slot());
        }
        material_map.insert(lamp.slot().to_string(), lamp.lit().to_string());
    }
}

/// (junction i, junction j, heading quadrant) of a pole at `at`.
fn key(l: &Layout, at: [f64; 3], heading_deg: f64) -> (usize, usize, i64) {
    let ij = |v: f64| (v / l.pitch_m).round().max(0.0) as usize;
    let q = (heading_deg / 90.0).round() as i64;
    (ij(at[0]), ij(at[1]), q.rem_euclid(4))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::town::routes::Turns;

    #[test]
    fn clock_lamp_switches_at_the_clock_phase_boundaries() {
        // Cycle 17 s: ramp up 0–2 and drive to 10 (green), ramp down to 12
        // (amber), stand to 17 (red).
        let s = Schedule {
            go_s: 10.0,
            ramp_s: 2.0,
            stop_s: 5.0,
            speed_mps: 10.0,
            turns: Turns::new(3.5),
            max_len_m: 4.5,
        };
        let want = [
            (0.0, Lamp::Green),
            (1.0, Lamp::Green),
            (9.999, Lamp::Green),
            (10.0, Lamp::Amber),
            (11.999, Lamp::Amber),
            (12.0, Lamp::Red),
            (16.999, Lamp::Red),
            (17.0, Lamp::Green),
            (17.0 * 3.0 + 12.5, Lamp::Red),
        ];
        for (t, lamp) in want {
            assert_eq!(clock_lamp(&s, t), lamp, "t = {t}");
            assert_eq!(lamp == Lamp::Red, s.standing(t), "t = {t}");
        }
    }
}
