//! Traffic over a 300-frame sequence in every town: no two vehicles (ego
//! included) ever overlap, every vehicle stays on its road surface, the ego
//! stays on the road and moves by v / fps per frame except where its lane
//! wraps at the town edge, and pedestrians stay off the roads.

use std::path::Path;

use parallax::town::layout::{Layout, Rect};
use parallax::town::roads::Axis;
use parallax::town::traffic::lanes;
use parallax::town::{frame_at, load_town};

const TOWNS: [&str; 8] = [
    "town01", "town02", "town03", "town04", "town05", "town06", "town07", "town10",
];

/// Pairs of overlapping rectangles (sweep over x).
fn overlaps(rects: &[Rect]) -> Vec<(usize, usize)> {
    let mut order: Vec<usize> = (0..rects.len()).collect();
    order.sort_by(|&a, &b| rects[a].min[0].total_cmp(&rects[b].min[0]));
    let mut out = Vec::new();
    for (k, &a) in order.iter().enumerate() {
        for &b in &order[k + 1..] {
            if rects[b].min[0] >= rects[a].max[0] {
                break;
            }
            if rects[a].overlaps(&rects[b]) {
                out.push((a, b));
            }
        }
    }
    out
}

#[test]
fn no_vehicles_overlap_and_the_ego_stays_on_the_road_for_300_frames_in_every_town() {
    for name in TOWNS {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("scenes/{name}.toml"));
        let desc = load_town(&path).unwrap_or_else(|e| panic!("{e}"));
        let layout = Layout::new(&desc);
        let all_lanes = lanes(&layout);
        let road_of = |lane: usize| {
            let ln = &all_lanes[lane];
            match ln.axis {
                Axis::X => layout.x_road(ln.road),
                Axis::Y => layout.y_road(ln.road),
            }
        };
        let step_m = desc.speed_kmh / 3.6 / desc.fps;
        let mut prev_ego: Option<[f64; 3]> = None;
        let (mut min_count, mut wraps) = (usize::MAX, 0);
        for k in 0..300u64 {
            let f = frame_at(&desc, 11, k);
            let mut rects = vec![f.ego.footprint()];
            rects.extend(f.vehicles.iter().map(|v| v.footprint()));
            let bad = overlaps(&rects);
            assert!(
                bad.is_empty(),
                "{name} frame {k}: vehicles overlap: {bad:?}"
            );
            assert!(
                road_of(f.ego.lane).contains(&rects[0], 1e-9),
                "{name} frame {k}: ego off the road at {:?}",
                f.ego.position
            );
            for v in &f.vehicles {
                assert!(
                    road_of(v.lane).contains(&v.footprint(), 1e-9),
                    "{name} frame {k}: vehicle {} off its road at {:?}",
                    v.id,
                    v.position
                );
            }
            for p in &f.pedestrians {
                let feet = Rect::centered([p.position[0], p.position[1]], [0.5, 0.5]);
                assert!(
                    layout.road_rects().iter().all(|r| !r.overlaps(&feet)),
                    "{name} frame {k}: pedestrian {} on the road at {:?}",
                    p.id,
                    p.position
                );
            }
            if let Some(prev) = prev_ego {
                let moved =
                    (f.ego.position[0] - prev[0]).abs() + (f.ego.position[1] - prev[1]).abs();
                if (moved - step_m).abs() > 1e-6 {
                    wraps += 1;
                    assert!(
                        moved > layout.len_x() / 2.0,
                        "{name} frame {k}: ego jumped {moved} m"
                    );
                }
            }
            prev_ego = Some(f.ego.position);
            min_count = min_count.min(f.vehicles.len());
        }
        assert!(
            wraps <= 1,
            "{name}: ego wrapped {wraps} times in 300 frames"
        );
        if desc.traffic_density >= 0.2 {
            assert!(
                min_count >= 5,
                "{name}: only {min_count} vehicles in some frame"
            );
        }
    }
}
