//! Buses and trucks at a town's corners. They ride lane 0 and turn right
//! only where nothing else is legal: at the corners where a clockwise
//! edge road ends. There they sweep through both lanes of their side on
//! the merged corridor's line (`Turns::merged`), not round the kerb lane's
//! tight corner, whose arc would carry a truck's body over the kerb. Over
//! 600 frames of grid test towns with two and three lanes: every vehicle
//! stays on the road, none overlaps another, and long bodies are seen
//! mid-turn inside corner junctions (so the check is not vacuous).

use parallax::town::layout::Layout;
use parallax::town::vehicles::BodyKind;
use parallax::town::{frame_at, parse_town_str, TownDesc};

use crate::traffic::{on_road, overlaps};

fn grid_town(lane_w: f64, lanes: u32) -> TownDesc {
    let text = format!(
        r#"
name = "long_turns"
extent_m = [360.0, 360.0]
block_size_m = 90.0
lanes_per_direction = {lanes}
lane_width_m = {lane_w}
sidewalk_width_m = 4.0
building_density = 0.5
floors = [2, 3]
vegetation_density = 0.2
terrain = "grass"
traffic_density = 0.6
speed_kmh = 40.0
sun_elevation_deg = 45.0
sun_azimuth_deg = 160.0
"#
    );
    parse_town_str(&text, "long_turns.toml".as_ref()).unwrap()
}

#[test]
fn long_bodies_turn_at_town_corners_without_crossing_the_kerb() {
    for (lane_w, lanes) in [(3.5, 2), (3.2, 2), (3.75, 3)] {
        let desc = grid_town(lane_w, lanes);
        let l = Layout::new(&desc);
        let roads = l.road_rects();
        let hw = l.road_w_m / 2.0;
        let corners: Vec<[f64; 2]> = [(0, 0), (l.nx, 0), (0, l.ny), (l.nx, l.ny)]
            .iter()
            .map(|&(i, j)| [i as f64 * l.pitch_m, j as f64 * l.pitch_m])
            .collect();
        let mut turning = 0;
        for seed in [3, 4] {
            for frame in 0..600 {
                let f = frame_at(&desc, seed, frame);
                let all: Vec<_> = std::iter::once(&f.ego).chain(&f.vehicles).collect();
                let bad = overlaps(&all);
                assert!(
                    bad.is_empty(),
                    "{lane_w}×{lanes} seed {seed} frame {frame}: {bad:?}"
                );
                for v in &all {
                    assert!(
                        on_road(&l, &roads, None, v),
                        "{lane_w}×{lanes} seed {seed} frame {frame}: {} {:?} off the road at {:?} heading {}",
                        v.id,
                        v.body,
                        v.position,
                        v.heading_deg
                    );
                    let long = matches!(v.body, BodyKind::Bus | BodyKind::Truck);
                    let q = v.heading_deg.rem_euclid(90.0);
                    let mid_turn = q > 1.0 && q < 89.0;
                    let in_corner = corners.iter().any(|c| {
                        (v.position[0] - c[0]).abs() < hw && (v.position[1] - c[1]).abs() < hw
                    });
                    turning += (long && mid_turn && in_corner) as usize;
                }
            }
        }
        eprintln!("{lane_w}×{lanes}: {turning} long-body poses mid-turn in a corner");
        assert!(turning > 10, "{lane_w}×{lanes}: {turning}");
    }
}
