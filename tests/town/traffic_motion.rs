//! How traffic moves, over 300 frames: vehicles circulate the town03
//! roundabout counter-clockwise, slow down in turns, some stand while
//! others drive; frames are deterministic (alone = in sequence), and the
//! per-description plan cache gives a town with one changed parameter its
//! own plan and frames while the original keeps its own.

use std::collections::BTreeMap;

use std::path::Path;

use parallax::town::layout::Layout;
use parallax::town::traffic::Plan;
use parallax::town::{frame_at, parse_town_str, TownDesc, TownFrame};

use crate::common;
use common::towns::{level_frame, town, town_file};

/// Frames 0..n of seed 11 in the level grid's plane (an organic town's
/// carried back by W⁻¹), where the layout's circles and axes hold.
fn frames(desc: &TownDesc, n: u64) -> Vec<TownFrame> {
    (0..n)
        .map(|k| level_frame(desc, 11, frame_at(desc, 11, k)))
        .collect()
}

#[test]
fn vehicles_circulate_the_roundabout_counter_clockwise() {
    let desc = town("town03");
    let l = Layout::new(&desc);
    let c = l.roundabout_center().expect("town03 has a roundabout");
    let (r_in, r_out) = l.roundabout_radii();
    // Per vehicle: the polar angles (unwrapped) at frames on the ring.
    let mut swept: BTreeMap<u32, (f64, f64, f64)> = BTreeMap::new();
    let mut last_d: BTreeMap<u32, f64> = BTreeMap::new();
    let mut circling = 0usize;
    for f in frames(&desc, 300) {
        for v in &f.vehicles {
            let (dx, dy) = (v.position[0] - c[0], v.position[1] - c[1]);
            let d = dx.hypot(dy);
            if d < r_in || d > r_out - 1.0 {
                continue;
            }
            let a = dy.atan2(dx);
            let e = swept.entry(v.id).or_insert((a, a, 0.0));
            let mut step = a - e.1;
            step -= (step / std::f64::consts::TAU).round() * std::f64::consts::TAU;
            assert!(
                step >= -1e-9,
                "vehicle {} turns clockwise on the ring",
                v.id
            );
            // Heading has a counter-clockwise component everywhere on the
            // ring (|off| < 90° from the ccw tangent a + 90°; entering and
            // leaving it turns towards the arms), and while the vehicle keeps
            // its distance from the centre (driving a circle) it is exactly
            // that tangent.
            let off = (v.heading_deg - (a.to_degrees() + 90.0) + 180.0).rem_euclid(360.0) - 180.0;
            assert!(
                off.abs() < 90.0,
                "vehicle {} heads {off}° off the counter-clockwise tangent",
                v.id
            );
            if last_d
                .insert(v.id, d)
                .is_some_and(|d0| (d - d0).abs() < 1e-6)
            {
                assert!(
                    off.abs() < 1e-6,
                    "vehicle {} circles at {d} m heading {off}° off the ccw tangent",
                    v.id
                );
                circling += 1;
            }
            e.1 = a;
            e.2 += step;
        }
    }
    assert!(circling >= 20, "only {circling} samples circling the ring");
    let circulated = swept.values().filter(|s| s.2 > 0.6).count();
    assert!(
        circulated >= 2,
        "only {circulated} vehicles went round: {swept:?}"
    );
}

#[test]
fn vehicles_slow_down_in_turns() {
    use parallax::town::traffic::A_LAT_MPS2;
    for name in ["town01", "town03", "town05"] {
        let desc = town(name);
        let fs = frames(&desc, 300);
        let (mut turning, mut straight) = (0.0f64, 0.0f64);
        for w in fs.windows(2) {
            for (v, p) in w[1].vehicles.iter().zip(&w[0].vehicles) {
                assert_eq!(v.id, p.id);
                let step = (v.position[0] - p.position[0]).hypot(v.position[1] - p.position[1]);
                let mut dh = (v.heading_deg - p.heading_deg).abs() % 360.0;
                dh = dh.min(360.0 - dh);
                if dh > 2.0 {
                    turning = turning.max(step);
                    // Lateral acceleration v²·κ, κ ≈ turned angle / chord
                    // (an underestimate where a step leaves a straight).
                    // Cars on block loops ride up to 0.65 m ahead of their
                    // slot (fronts at the stop line), so they meet a curve
                    // a little early, at up to ~16% more than the bound.
                    let v_mps = step * desc.fps;
                    let kappa = dh.to_radians() / step;
                    assert!(
                        v_mps * v_mps * kappa <= 1.2 * A_LAT_MPS2,
                        "{name}: vehicle {} at {v_mps} m/s on κ {kappa}",
                        v.id
                    );
                } else if dh < 1e-9 {
                    // Straight (an organic town's headings come back from
                    // W⁻¹ within rounding).
                    straight = straight.max(step);
                }
            }
        }
        assert!(
            turning > 0.0 && straight > 0.0,
            "{name}: {turning} {straight}"
        );
        assert!(
            turning < 0.8 * straight,
            "{name}: {turning} m/frame in turns, {straight} on straights"
        );
    }
}

#[test]
fn some_vehicles_stand_while_others_drive() {
    let desc = town("town02");
    let fs = frames(&desc, 300);
    let mixed = fs.windows(2).any(|w| {
        let moved: Vec<bool> = w[1]
            .vehicles
            .iter()
            .zip(&w[0].vehicles)
            .map(|(v, p)| v.position != p.position)
            .collect();
        moved.iter().any(|&m| m) && moved.iter().any(|&m| !m)
    });
    assert!(
        mixed,
        "every vehicle stands or drives at once in every frame"
    );
}

#[test]
fn frames_are_deterministic_and_a_changed_description_gets_its_own_plan() {
    for (name, lane_w) in [("town03", "3.5"), ("town06", "3.75")] {
        let desc = town(name);
        // Determinism: frame 5000 alone and within a sequence agree.
        let alone = frame_at(&desc, 7, 5000);
        let seq: Vec<TownFrame> = (4990..=5000).map(|k| frame_at(&desc, 7, k)).collect();
        assert_eq!(alone, seq[10], "{name}");
        assert_ne!(seq[9], seq[10], "{name}: nothing moved");
        assert_eq!(frame_at(&desc, 7, 4995), seq[5]);
        // The plan cache (`Plan::new`, per description): with this town's
        // plan cached, the same town with 3.3 m lanes (same name) gets
        // another plan (lane centrelines move) and other frames; then the
        // original still gets its own.
        let text = std::fs::read_to_string(town_file(name)).unwrap();
        let from = format!("lane_width_m = {lane_w}");
        assert!(text.contains(&from), "{name}");
        let narrow = text.replace(&from, "lane_width_m = 3.3");
        let narrow = parse_town_str(&narrow, Path::new("t.toml")).unwrap();
        assert_eq!((narrow.name.as_str(), narrow.lane_width_m), (name, 3.3));
        let original = Plan::new(&desc);
        let other = Plan::new(&narrow);
        assert_ne!(
            *original, *other,
            "{name}: narrow lanes got the cached plan"
        );
        assert_eq!(other.routes.len(), original.routes.len(), "{name}");
        let moved = frame_at(&narrow, 7, 5000);
        assert_ne!(moved.vehicles, alone.vehicles, "{name}");
        assert_eq!(*Plan::new(&desc), *original, "{name}");
        assert_eq!(frame_at(&desc, 7, 5000), alone, "{name}");
    }
}

#[test]
fn buses_and_trucks_drive_and_turn_in_every_multi_lane_town() {
    use parallax::town::vehicles::BodyKind;
    let mut turned_long = 0;
    for name in [
        "town01", "town02", "town03", "town04", "town05", "town06", "town07", "town10",
    ] {
        let desc = town(name);
        let lanes = Layout::new(&desc).lanes;
        // Per bus or truck id: its first heading and whether it turned by 90°.
        let mut long: BTreeMap<u32, (f64, bool)> = BTreeMap::new();
        for f in frames(&desc, 300) {
            for v in f.vehicles.iter().chain(std::iter::once(&f.ego)) {
                if !matches!(v.body, BodyKind::Bus | BodyKind::Truck) {
                    continue;
                }
                let e = long.entry(v.id).or_insert((v.heading_deg, false));
                let d = (v.heading_deg - e.0).rem_euclid(360.0);
                e.1 |= (d - 90.0).abs() < 1e-6 || (d - 270.0).abs() < 1e-6;
            }
        }
        let buses = long.len();
        if lanes >= 2 {
            // Two lanes make a corridor a bus can turn in.
            assert!(buses >= 2, "{name}: only {buses} buses or trucks");
            turned_long += long.values().filter(|e| e.1).count();
        } else {
            // One 3.2–3.5 m lane is too narrow to turn an 8 m truck.
            assert_eq!(buses, 0, "{name}");
        }
    }
    assert!(turned_long > 0, "no bus or truck turned a corner");
}

#[test]
fn a_frame_is_the_same_whatever_the_process_computed_before_and_chunks_start_anew() {
    use parallax::town::drive_frame_at;
    use std::collections::BTreeSet;
    // A description of its own: no other test fills its caches.
    let mut desc = town("town03");
    desc.traffic_density *= 0.97;
    let (seed, drive, k) = (4, 3, 1250);
    // Frame 1250 (chunk 2) first, cold; then other chunks and another
    // drive push it out of the caches, and the frames before it follow
    // in sequence.
    let cold = drive_frame_at(&desc, seed, drive, k);
    for f in [700, 1900, 2500] {
        drive_frame_at(&desc, seed, drive, f);
    }
    drive_frame_at(&desc, seed, drive + 1, k);
    let warm: Vec<TownFrame> = (1190..=k)
        .map(|f| drive_frame_at(&desc, seed, drive, f))
        .collect();
    assert_eq!(warm.last(), Some(&cold));
    // Within a chunk vehicles keep their ids; at a chunk's first frame the
    // traffic starts anew under other ids (the ego's leaders keep theirs
    // for the whole drive).
    let ids = |f: &TownFrame| {
        f.vehicles
            .iter()
            .filter(|v| v.route != parallax::town::traffic::CONVOY_ROUTE)
            .map(|v| v.id)
            .collect::<BTreeSet<u32>>()
    };
    // warm[10] is frame 1200, chunk 2's first.
    let (before, first) = (ids(&warm[9]), ids(&warm[10]));
    assert!(before.len() > 20 && first.len() > 20);
    assert!(
        before.is_disjoint(&first),
        "ids shared across a chunk start"
    );
    assert_eq!(first, ids(&warm[11]));
}
