//! Traffic signals that show the per-direction phases of
//! `traffic::Schedule`. Every cross junction has one traffic light per
//! approach, on the approach's right-hand corner before the junction, its
//! heads facing the approaching traffic (`signal_sites`, placed by
//! `furniture`). A head lights exactly one lamp: the east–west approaches
//! show green, then amber, then red through an all-red gap, then the
//! north–south approaches' green, amber and all-red, twice, then the
//! pedestrians' stand (`axis_lamp`); vehicles move off as it turns green (no red+amber
//! phase). Junctions without lights but the roundabout (the outer T
//! junctions and corners) keep the same phases unseen. The lamps of frame
//! K are a pure function of (desc, K), set on the traffic-light instances
//! as a material map from the lens slots of `props::LENS_SLOTS` to their
//! emitters.

use std::collections::BTreeMap;

use crate::scene::desc::{ObjectDesc, ShapeDesc};

use super::desc::TownDesc;
use super::layout::Layout;
use super::props::LENS_SLOTS;
use super::traffic::{Plan, Schedule};

/// Name of the traffic-light prefab of one-lane approaches (`street::lights`).
pub const PREFAB: &str = "traffic_light";
/// Every traffic-light prefab: the corner pole with a short arm, and the
/// mast arm with one head per lane of two-lane approaches.
pub const PREFABS: [&str; 2] = [PREFAB, super::street::lights::SIGNAL_MAST];

/// The lamp a signal head shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Lamp {
    /// Stop.
    Red,
    /// Enter only if the junction can be cleared before red.
    Amber,
    /// Go.
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

    /// The controlled traffic's direction: 0 east, 1 north, 2 west, 3 south.
    pub fn dir_index(&self) -> usize {
        ((self.heading_deg / 90.0).round() as i64).rem_euclid(4) as usize
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
/// with stop signs), but the roundabout and the underpass's crossing.
pub fn has_signals(l: &Layout, i: usize, j: usize) -> bool {
    j > 0 && j < l.ny && i <= l.nx && l.roundabout != Some((i, j)) && l.underpass != Some((i, j))
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

/// The lamp the approaches heading `dir` (0 east, 1 north, 2 west, 3
/// south) show at time `t`.
pub fn axis_lamp(s: &Schedule, dir: usize, t: f64) -> Lamp {
    let u = s.axis_time_s(dir, t);
    if u < s.green_s {
        Lamp::Green
    } else if u < s.green_s + s.amber_s {
        Lamp::Amber
    } else {
        Lamp::Red
    }
}

/// Seconds until the approaches heading `dir` turn red, from time `t`
/// (0 while red).
pub fn until_red_s(s: &Schedule, dir: usize, t: f64) -> f64 {
    (s.green_s + s.amber_s - s.axis_time_s(dir, t)).max(0.0)
}

/// One traffic light in one frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Signal {
    /// Where it stands and what it controls.
    pub site: SignalSite,
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
    let t = frame as f64 / desc.fps;
    signal_sites(l)
        .into_iter()
        .map(|site| Signal {
            site,
            lamp: axis_lamp(&plan.schedule, site.dir_index(), t),
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
    fn each_axis_shows_green_amber_red_in_its_windows_and_both_stand_red() {
        // Window 10 + 3 + 2 = 15 s per axis, two rounds (60 s), stand 5 s.
        let s = Schedule {
            green_s: 10.0,
            amber_s: 3.0,
            all_red_s: 2.0,
            stop_s: 5.0,
            speed_mps: 10.0,
            turns: Turns::new(3.5),
            max_len_m: 4.5,
        };
        assert_eq!(crate::town::traffic::ROUNDS_PER_STAND, 2);
        assert_eq!(s.cycle_s(), 65.0);
        assert!(s.standing(0.0) && s.standing(4.999) && !s.standing(5.0));
        use Lamp::*;
        // (u, lamp east/west, lamp north/south, until red east, north)
        // with u on the cycle's clock (0: the first east–west green).
        let want = [
            (0.0, Green, Red, 13.0, 0.0),
            (9.999, Green, Red, 3.001, 0.0),
            (10.0, Amber, Red, 3.0, 0.0),
            (12.999, Amber, Red, 0.001, 0.0),
            (13.0, Red, Red, 0.0, 0.0),
            (14.999, Red, Red, 0.0, 0.0),
            (15.0, Red, Green, 0.0, 13.0),
            (25.0, Red, Amber, 0.0, 3.0),
            (28.0, Red, Red, 0.0, 0.0),
            (30.0, Green, Red, 13.0, 0.0),
            (41.0, Amber, Red, 2.0, 0.0),
            (45.0, Red, Green, 0.0, 13.0),
            (58.0, Red, Red, 0.0, 0.0),
            (60.0, Red, Red, 0.0, 0.0),
            (64.999, Red, Red, 0.0, 0.0),
            (65.0 * 3.0 + 1.0, Green, Red, 12.0, 0.0),
        ];
        for (u, ew, ns, r_e, r_n) in want {
            // Time 0 is the start of the stand before u = 0.
            let t = u + 5.0;
            for d in 0..4 {
                let (lamp, left) = if d % 2 == 0 { (ew, r_e) } else { (ns, r_n) };
                assert_eq!(axis_lamp(&s, d, t), lamp, "u = {u}, dir {d}");
                assert!(
                    (until_red_s(&s, d, t) - left).abs() < 1e-9,
                    "u = {u}, dir {d}"
                );
            }
            // Pedestrians cross exactly while both axes stand past their gap.
            assert_eq!(s.standing(t), (60.0..65.0).contains(&u.rem_euclid(65.0)));
        }
    }
}
