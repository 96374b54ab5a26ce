use super::cars::{cars_in, parked_in};
use super::layby::{cut_laybys, runs};
use super::*;
use crate::scene::desc::ObjectDesc;
use crate::town::parts::{class, slab};
use crate::town::source::load_named_town;

fn town(name: &str) -> TownDesc {
    load_named_town(name, None).unwrap().desc
}

/// A bay on the north side (+y) of the x-road at y = 0, 7 m half width.
fn north_bay(a0: f64) -> Bay {
    Bay {
        axis: Axis::X,
        road: 0,
        c: 0.0,
        side: 1.0,
        along: (a0, a0 + BAY_LEN_M),
        hw: 7.0,
        depth: 2.2,
    }
}

#[test]
fn bay_depth_keeps_the_kerb_a_walker_half_width_off_the_inner_lane() {
    for sw in [6.0, 6.2, 7.0, 9.0] {
        let d = bay_depth_m(sw);
        // The walkers' inner lane: sw/2 + 0.1 − 0.45 from the road edge.
        let lane = sw / 2.0 + 0.1 - 0.45;
        assert!(d + KERB_M + WALKER_HALF_M <= lane + 1e-12, "{sw}: {d}");
        assert!((DEPTH_M.0 - 1e-9..=DEPTH_M.1).contains(&d), "{sw}: {d}");
    }
    assert!((bay_depth_m(min_sidewalk_m()) - DEPTH_M.0).abs() < 1e-12);
    assert!((bay_depth_m(6.2) - 2.25).abs() < 1e-12);
}

#[test]
fn parking_density_is_refused_out_of_range_or_where_bays_do_not_fit() {
    let mut d = town("town10");
    for bad in [-0.1, 1.5, f64::NAN] {
        d.parking_density = bad;
        let e = d.validate().unwrap_err();
        assert!(e.starts_with("parking_density: must be in [0, 1]"), "{e}");
    }
    d.parking_density = 0.5;
    d.sidewalk_width_m = 4.5;
    let e = d.validate().unwrap_err();
    assert!(
        e.contains("parking_density") && e.contains("sidewalk_width_m ≥ 6.00, got 4.5"),
        "{e}"
    );
    d.sidewalk_width_m = 6.0;
    assert_eq!(d.validate(), Ok(()));
    let mut country = town("town07");
    country.parking_density = 0.3;
    let e = country.validate().unwrap_err();
    assert!(e.contains("level grid town with sidewalks"), "{e}");
    // Town03 parks in lanes; without its keys it has no bays.
    let mut t = town("town03");
    assert!(!bays(&t, &Layout::new(&t), &[]).is_empty());
    (t.parking_density, t.parking_lane_m) = (0.0, 0.0);
    assert!(bays(&t, &Layout::new(&t), &[]).is_empty());
}

#[test]
fn runs_merge_adjacent_bays_of_one_side_only() {
    let mut b = vec![north_bay(10.0), north_bay(16.0), north_bay(30.0)];
    let mut south = north_bay(36.0);
    south.side = -1.0;
    b.push(south);
    let r = runs(&b);
    assert_eq!(r.len(), 3);
    assert_eq!(r[0].along, (10.0, 22.0));
    assert_eq!(r[1].along, (30.0, 36.0));
    assert_eq!(r[2].side, -1.0);
}

fn boxes(objects: &[ObjectDesc], material: &str) -> Vec<Rect> {
    objects
        .iter()
        .filter(|o| o.material.as_deref() == Some(material))
        .filter_map(footprint)
        .collect()
}

fn area(r: &Rect) -> f64 {
    let s = r.size();
    s[0] * s[1]
}

#[test]
fn a_layby_cuts_the_kerb_and_walk_back_to_its_own_kerb() {
    // The north kerb (7 .. 7.25) and walk (7.25 .. 13) of a 40 m segment.
    let l = class("sidewalk");
    let mut objects = vec![
        slab([0.0, 7.0], [40.0, 7.25], 0.0, 0.15, "curb", l),
        slab([0.0, 7.25], [40.0, 13.0], 0.0, 0.14, "sidewalk", l),
        // The south side stays whole.
        slab([0.0, -13.0], [40.0, -7.25], 0.0, 0.14, "sidewalk", l),
    ];
    let bays = [north_bay(10.0), north_bay(16.0)];
    cut_laybys(&mut objects, &bays);
    let bay = Rect {
        min: [10.0, 7.0],
        max: [22.0, 9.2],
    };
    let walks = boxes(&objects, "sidewalk");
    // Walk area: the original minus the bay and its kerb (12 × 2.2 m of
    // the walk's 12 × (9.35 − 7.25) m strip).
    let total: f64 = walks.iter().map(area).sum();
    let want = 40.0 * 5.75 * 2.0 - 12.0 * (9.2 + KERB_M - 7.25);
    assert!((total - want).abs() < 1e-9, "{total} vs {want}");
    let curbs = boxes(&objects, "curb");
    let curb_area: f64 = curbs.iter().map(area).sum();
    assert!((curb_area - (28.0 * 0.25 + 12.0 * KERB_M)).abs() < 1e-9);
    for r in walks.iter().chain(&curbs) {
        assert!(!r.overlaps(&bay), "{r:?} stands in the bay");
    }
    // The bay's own kerb runs along its back.
    let near = |a: &Rect, b: &Rect| {
        (0..2).all(|k| (a.min[k] - b.min[k]).abs() < 1e-9 && (a.max[k] - b.max[k]).abs() < 1e-9)
    };
    let kerb = Rect {
        min: [10.0, 9.2],
        max: [22.0, 9.2 + KERB_M],
    };
    assert!(curbs.iter().any(|c| near(c, &kerb)), "{curbs:?}");
    // Its surface at road level fills it, lines at both ends and between.
    let floor = boxes(&objects, "asphalt");
    assert!(floor.len() == 1 && near(&floor[0], &bay), "{floor:?}");
    assert_eq!(boxes(&objects, "paint_white_road").len(), 3);
}

#[test]
fn parked_cars_fit_their_bay_near_the_kerb_facing_the_traffic() {
    for (side, heading) in [(1.0, 180.0), (-1.0, 0.0)] {
        let mut bay = north_bay(100.0);
        bay.side = side;
        let mut seen = 0;
        for k in 0..200 {
            let Some(car) = parked_in(&bay, k, 7, 1.0) else {
                panic!("density 1 fills every bay");
            };
            seen += 1;
            assert_eq!(car.body.class(), "car");
            assert!((car.heading_deg - heading).abs() <= 0.8 + 1e-12);
            let r = bay.rect();
            for q in car.corners() {
                let inside = q[0] >= r.min[0] && q[0] <= r.max[0];
                let off = side * (q[1] - bay.c);
                assert!(
                    inside && off >= bay.hw && off <= bay.hw + bay.depth,
                    "{q:?}"
                );
            }
        }
        assert_eq!(seen, 200);
    }
}

#[test]
fn the_fill_follows_parking_density_and_the_seed() {
    let bays: Vec<Bay> = (0..400).map(|k| north_bay(10.0 + 6.0 * k as f64)).collect();
    for d in [0.0, 0.3, 0.7] {
        let n = cars_in(&bays, 1, d).len() as f64 / 400.0;
        assert!((n - d).abs() < 0.08, "{d}: {n}");
    }
    assert_eq!(cars_in(&bays, 1, 0.5), cars_in(&bays, 1, 0.5));
    assert_ne!(cars_in(&bays, 1, 0.5), cars_in(&bays, 2, 0.5));
}

#[test]
fn the_parked_mix_is_the_cars_that_fit_a_bay() {
    use crate::town::vehicles::BodyKind as K;
    let kinds: Vec<K> = super::cars::fitting(bay_depth_m(6.2))
        .iter()
        .map(|k| k.0)
        .collect();
    assert_eq!(kinds, [K::Sedan, K::Hatchback, K::Suv, K::Estate, K::Coupe]);
    // The shallowest bay leaves out the SUV (2.14 m with its mirrors).
    let kinds: Vec<K> = super::cars::fitting(DEPTH_M.0)
        .iter()
        .map(|k| k.0)
        .collect();
    assert!(
        !kinds.contains(&K::Suv) && kinds.contains(&K::Sedan),
        "{kinds:?}"
    );
}
