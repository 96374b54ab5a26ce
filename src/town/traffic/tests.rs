//! Tests of where a drive's background vehicles start and how cyclists
//! are limited.

use super::sim::Agent;
use super::spawn::spawn;
use super::*;

fn town(name: &str) -> TownDesc {
    crate::town::source::load_named_town(name, None)
        .unwrap()
        .desc
}

/// The lane (0 = next to the centreline) of a start pose of a link
/// heading `h` radians: its lateral offset right of the road's centre
/// line, over the lane width.
fn lane_of(l: &Layout, p: [f64; 2], h: f64) -> f64 {
    let (u, r) = ([h.cos(), h.sin()], [h.sin(), -h.cos()]);
    // The road's centre line: the nearest multiple of the pitch across.
    let across = if u[0].abs() > 0.5 { p[1] } else { p[0] };
    let c = (across / l.pitch_m).round() * l.pitch_m;
    let off = (across - c) * if u[0].abs() > 0.5 { r[1] } else { r[0] };
    off / l.lane_w_m
}

#[test]
fn vehicles_start_apart_on_the_straights_in_the_inner_and_kerb_lanes() {
    for name in ["town02", "town03", "town06"] {
        let desc = town(name);
        let l = Layout::new(&desc);
        let plan = Plan::new(&desc);
        let agents: Vec<Agent> = spawn(3, 7, 0, desc.traffic_density, &l, &plan);
        assert!(agents.len() > 40, "{name}: {} vehicles", agents.len());
        let hw = l.road_w_m / 2.0;
        let poses: Vec<VehiclePose> = agents
            .iter()
            .map(|a| {
                let (p, h) = a.path.pose(0.0);
                let lane = lane_of(&l, p, h);
                let k = lane.floor();
                assert!(
                    (lane - k - 0.5).abs() < 1e-6,
                    "{name}: off a lane centre: {lane}"
                );
                let k = k as u32;
                assert!(k == 0 || k + 1 == l.lanes, "{name}: lane {k}");
                if a.body == BodyKind::Bicycle {
                    assert_eq!(k + 1, l.lanes, "{name}: a bicycle off the kerb lane");
                    assert_eq!(a.v_max, cyclist_speed_mps(plan.schedule.speed_mps));
                } else {
                    assert_eq!(a.v_max, plan.schedule.speed_mps);
                }
                if matches!(a.body, BodyKind::Bus | BodyKind::Truck) {
                    assert!(l.lanes > 1 && k == 0, "{name}: a {:?} in lane {k}", a.body);
                }
                // Not in a junction: both coordinates off the grid lines
                // by more than the half road width plus the body.
                let along = if h.cos().abs() > 0.5 { p[0] } else { p[1] };
                let g = (along - (along / l.pitch_m).round() * l.pitch_m).abs();
                assert!(
                    g > hw + a.body.footprint_m()[0] / 2.0,
                    "{name}: {g} m from a junction"
                );
                a.pose()
            })
            .collect();
        for (i, a) in poses.iter().enumerate() {
            for b in &poses[i + 1..] {
                assert!(
                    a.footprint().min[0] >= b.footprint().max[0]
                        || b.footprint().min[0] >= a.footprint().max[0]
                        || a.footprint().min[1] >= b.footprint().max[1]
                        || b.footprint().min[1] >= a.footprint().max[1],
                    "{name}: {} and {} start overlapping",
                    a.id,
                    b.id
                );
            }
        }
        let ids: std::collections::BTreeSet<u32> = poses.iter().map(|p| p.id).collect();
        assert_eq!(ids.len(), poses.len());
        // Another drive starts other traffic.
        let other = spawn(3, 8, 0, desc.traffic_density, &l, &plan);
        assert!(
            other.len() != agents.len() || other.iter().zip(&agents).any(|(a, b)| a.body != b.body)
        );
    }
}

#[test]
fn cyclists_keep_below_the_limit_and_never_above_it() {
    assert_eq!(cyclist_speed_mps(40.0 / 3.6), 5.5);
    assert_eq!(cyclist_speed_mps(4.0), 4.0);
}

#[test]
fn a_follower_stays_behind_where_its_leader_will_be_and_could_stop_if_it_braked() {
    use super::sim::follow_cap;
    let (b, dt) = (A_LON_MPS2, 0.1);
    for (g, u) in [
        (0.0, 0.0),
        (5.0, 0.0),
        (20.0, 10.0),
        (40.0, 25.0),
        (0.5, 20.0),
    ] {
        let v = follow_cap(g, u, dt);
        // No further than the leader's rear after the step, and able to
        // stop behind it were it to brake at b from then on; one of the
        // two binds.
        let room = g + u * dt - v * dt;
        let braking = g + u * dt + u * u / (2.0 * b) - v * dt - v * v / (2.0 * b);
        assert!(room >= -1e-9 && braking >= -1e-9, "g {g} u {u}: {v}");
        assert!(
            room.abs() < 1e-9 || braking.abs() < 1e-9,
            "g {g} u {u}: {v}"
        );
    }
    // A standing leader 24 m beyond the gap: √(0.3² + 2·3·24) − 0.3.
    assert!((follow_cap(24.0, 0.0, dt) - ((0.09f64 + 144.0).sqrt() - 0.3)).abs() < 1e-12);
}
