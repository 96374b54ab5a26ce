//! Traffic over a 300-frame sequence in every town: no two vehicles (ego
//! included) on the same level ever overlap (exact rectangle test; a car on
//! the overpass deck and one on the highway below are on two levels), every vehicle stays on the
//! road surface, nothing teleports (every vehicle, ego included, seen in
//! two consecutive frames moved at most the town's speed_kmh / 3.6 / fps),
//! vehicles turn by 90° at junctions and stand still near stop
//! lines, pedestrians stay off the roads except on crosswalks, where some
//! of them are at some frames, and never touch a vehicle. In organic towns
//! the overlap test runs in the bent world, the others on the poses carried
//! back into the level grid (`Warp::unwarp_frame`).

use parallax::town::frame_at;
use parallax::town::layout::{Layout, Rect};
use parallax::town::organic::Warp;
use parallax::town::overpass::Overpass;
use parallax::town::traffic::{Plan, VehiclePose};

use crate::common;
use common::towns::{town, TOWNS};

/// Separating-axis test of two convex quads (touching does not count).
pub(crate) fn quads_overlap(a: &[[f64; 2]; 4], b: &[[f64; 2]; 4]) -> bool {
    for poly in [a, b] {
        for k in 0..4 {
            let (p, q) = (poly[k], poly[(k + 1) % 4]);
            let n = [q[1] - p[1], p[0] - q[0]];
            let proj = |v: &[[f64; 2]; 4]| {
                v.iter()
                    .map(|c| c[0] * n[0] + c[1] * n[1])
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
                        (lo.min(x), hi.max(x))
                    })
            };
            let ((a0, a1), (b0, b1)) = (proj(a), proj(b));
            if a1 <= b0 + 1e-9 || b1 <= a0 + 1e-9 {
                return false;
            }
        }
    }
    true
}

/// Pairs of overlapping vehicles (sweep over the x bounds).
pub(crate) fn overlaps(vs: &[&VehiclePose]) -> Vec<(u32, u32)> {
    let boxes: Vec<Rect> = vs.iter().map(|v| v.footprint()).collect();
    let corners: Vec<_> = vs.iter().map(|v| v.corners()).collect();
    let mut order: Vec<usize> = (0..vs.len()).collect();
    order.sort_by(|&a, &b| boxes[a].min[0].total_cmp(&boxes[b].min[0]));
    let mut out = Vec::new();
    for (k, &a) in order.iter().enumerate() {
        for &b in &order[k + 1..] {
            if boxes[b].min[0] >= boxes[a].max[0] {
                break;
            }
            let touch = vs[a].same_level(vs[b]);
            if touch && boxes[a].overlaps(&boxes[b]) && quads_overlap(&corners[a], &corners[b]) {
                out.push((vs[a].id, vs[b].id));
            }
        }
    }
    out
}

/// Whether the footprint's outline (sampled every 10 cm) lies on roads, on
/// the roundabout's ring (between its island and outer kerb), on a curved
/// loop corner (town04) or on the overpass road and its loops (town06).
pub(crate) fn on_road(
    l: &Layout,
    roads: &[Rect],
    over: Option<&Overpass>,
    v: &VehiclePose,
) -> bool {
    let ring = |x: f64, y: f64| {
        l.roundabout_center().is_some_and(|c| {
            let (r_in, r_out) = l.roundabout_radii();
            let d = (x - c[0]).hypot(y - c[1]);
            d >= r_in && d <= r_out
        })
    };
    let c = v.corners();
    (0..4).all(|k| {
        let (p, q) = (c[k], c[(k + 1) % 4]);
        (0..=50).all(|s| {
            let u = s as f64 / 50.0;
            let x = p[0] + (q[0] - p[0]) * u;
            let y = p[1] + (q[1] - p[1]) * u;
            let at = Rect::centered([x, y], [0.0, 0.0]);
            roads.iter().any(|r| r.contains(&at, 1e-6))
                || ring(x, y)
                || l.on_loop_curve([x, y])
                || over.is_some_and(|o| o.on_surface([x, y]))
        })
    })
}

/// Whether (x, y) lies on a crosswalk (0.5–3.5 m out from a junction edge).
fn on_crosswalk(l: &Layout, x: f64, y: f64) -> bool {
    let hw = l.road_w_m / 2.0;
    let near = |a: f64| {
        let m = a.rem_euclid(l.pitch_m);
        let d = m.min(l.pitch_m - m);
        d >= hw + 0.5 - 0.3 && d <= hw + 3.5 + 0.3
    };
    let across = |a: f64| {
        let m = a.rem_euclid(l.pitch_m);
        m.min(l.pitch_m - m) <= hw + 1.0
    };
    (near(x) && across(y)) || (near(y) && across(x))
}

#[test]
fn vehicles_never_overlap_stay_on_the_road_turn_and_stop_for_300_frames() {
    let mut ego_turned = 0;
    for name in TOWNS {
        let desc = town(name);
        let layout = Layout::new(&desc);
        let roads = layout.road_rects();
        let over = Overpass::new(&desc, &layout);
        // Independently of the plan: the town file's speed limit, per frame.
        let v_max = desc.speed_kmh / 3.6 / desc.fps;
        assert!((Plan::new(&desc).schedule.speed_mps - desc.speed_kmh / 3.6).abs() < 1e-12);
        let mut steps = 0usize;
        let bent: Vec<_> = (0..300u64).map(|k| frame_at(&desc, 11, k)).collect();
        // Organic towns: overlaps in the bent world, the layout checks in
        // the level grid's plane (W⁻¹).
        let warp = Warp::new(&desc, 11);
        let frames: Vec<_> = bent
            .iter()
            .map(|f| warp.map_or(f.clone(), |w| w.unwarp_frame(f)))
            .collect();
        let (mut min_count, mut crossing, mut stopped_at_line) = (usize::MAX, 0, 0);
        let mut turned = std::collections::BTreeSet::new();
        let mut first_heading = std::collections::BTreeMap::new();
        for (k, f) in frames.iter().enumerate() {
            let all: Vec<&VehiclePose> = std::iter::once(&f.ego).chain(&f.vehicles).collect();
            let world = &bent[k];
            let bad = overlaps(
                &std::iter::once(&world.ego)
                    .chain(&world.vehicles)
                    .collect::<Vec<_>>(),
            );
            assert!(
                bad.is_empty(),
                "{name} frame {k}: vehicles overlap: {bad:?}"
            );
            for v in &all {
                assert!(
                    on_road(&layout, &roads, over.as_ref(), v),
                    "{name} frame {k}: vehicle {} off the road at {:?} heading {}",
                    v.id,
                    v.position,
                    v.heading_deg
                );
                let h0 = *first_heading.entry(v.id).or_insert(v.heading_deg);
                let d = (v.heading_deg - h0).rem_euclid(360.0);
                if (d - 90.0).abs() < 1e-6 || (d - 270.0).abs() < 1e-6 {
                    turned.insert(v.id);
                }
            }
            for p in &f.pedestrians {
                let feet = Rect::centered([p.position[0], p.position[1]], [0.5, 0.5]);
                let on_roads = roads.iter().any(|r| r.overlaps(&feet));
                if on_roads {
                    assert!(
                        on_crosswalk(&layout, p.position[0], p.position[1]),
                        "{name} frame {k}: pedestrian {} on the road at {:?}",
                        p.id,
                        p.position
                    );
                    crossing += 1;
                }
                let sq = [
                    [feet.min[0], feet.min[1]],
                    [feet.max[0], feet.min[1]],
                    [feet.max[0], feet.max[1]],
                    [feet.min[0], feet.max[1]],
                ];
                for v in all.iter().filter(|v| v.footprint().overlaps(&feet)) {
                    assert!(
                        !quads_overlap(&sq, &v.corners()),
                        "{name} frame {k}: pedestrian {} under vehicle {}",
                        p.id,
                        v.id
                    );
                }
            }
            if k > 0 {
                let prev = &frames[k - 1];
                let moved = |a: &VehiclePose, b: &VehiclePose| {
                    (a.position[0] - b.position[0]).hypot(a.position[1] - b.position[1])
                };
                // Every vehicle id present in both frames (the ego included),
                // matched by id.
                let before: std::collections::BTreeMap<u32, &VehiclePose> = prev
                    .vehicles
                    .iter()
                    .chain(std::iter::once(&prev.ego))
                    .map(|v| (v.id, v))
                    .collect();
                for v in &all {
                    if let Some(w) = before.get(&v.id) {
                        let step = moved(v, w);
                        assert!(
                            step <= v_max + 1e-9,
                            "{name} frame {k}: vehicle {} jumped {step} m (at most {v_max})",
                            v.id
                        );
                        steps += 1;
                    }
                }
                // Standing vehicles whose front is at a stop line: 3.8–4.4 m
                // before a junction edge along their heading.
                for (v, w) in f.vehicles.iter().zip(&prev.vehicles) {
                    if v.id != w.id || moved(v, w) > 0.0 {
                        continue;
                    }
                    let h = v.heading_deg.to_radians();
                    let half = v.body.footprint_m()[0] / 2.0 - 0.05;
                    let front = [
                        v.position[0] + half * h.cos(),
                        v.position[1] + half * h.sin(),
                    ];
                    let ahead = if h.cos().abs() > 0.5 {
                        front[0] * h.cos().signum()
                    } else {
                        front[1] * h.sin().signum()
                    };
                    // Distance to the next junction edge along the heading.
                    let p = layout.pitch_m;
                    let edge = |a: f64| {
                        let next = ((a + layout.road_w_m / 2.0) / p).ceil() * p;
                        next - layout.road_w_m / 2.0 - a
                    };
                    let d = edge(ahead);
                    if (3.7..=4.6).contains(&d) {
                        stopped_at_line += 1;
                    }
                }
            }
            min_count = min_count.min(f.vehicles.len());
        }
        let f0 = &frames[0].ego;
        if frames.iter().any(|f| {
            ((f.ego.heading_deg - f0.heading_deg).rem_euclid(360.0) - 90.0).abs() < 1.0
                || ((f.ego.heading_deg - f0.heading_deg).rem_euclid(360.0) - 270.0).abs() < 1.0
        }) {
            ego_turned += 1;
        }
        assert!(
            steps >= 299 * min_count,
            "{name}: only {steps} vehicle steps matched by id"
        );
        assert!(
            turned.len() >= 3,
            "{name}: only {} vehicles turned",
            turned.len()
        );
        assert!(
            stopped_at_line > 0,
            "{name}: no vehicle stood at a stop line"
        );
        if layout.sidewalks && layout.nx >= 2 && layout.ny >= 2 {
            assert!(crossing > 0, "{name}: nobody on a crosswalk in 300 frames");
        }
        if desc.traffic_density >= 0.2 {
            assert!(
                min_count >= 5,
                "{name}: only {min_count} vehicles in some frame"
            );
        }
    }
    assert!(ego_turned >= 2, "the ego turned in only {ego_turned} towns");
}
