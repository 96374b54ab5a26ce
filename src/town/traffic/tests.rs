//! Tests of how traffic slots fill and where bodies ride in them.

use super::*;

fn town(name: &str) -> TownDesc {
    crate::town::source::load_named_town(name, None)
        .unwrap()
        .desc
}

#[test]
fn slots_fill_at_the_density_bus_lines_always_and_the_ego_slot_always() {
    let mut desc = town("town05");
    let plan = Plan::new(&desc);
    let bus = plan
        .routes
        .iter()
        .find(|rp| rp.route.kind == RouteKind::Ring && rp.route.bodies.contains(&BodyKind::Bus));
    let bus = bus.expect("town05's ring has a long-vehicle route");
    let cars = plan
        .routes
        .iter()
        .find(|rp| !rp.route.bodies.contains(&BodyKind::Bus))
        .expect("town05 has car-only routes");
    let mut r = Rng::new(&[9]);
    for density in [0.0, 1.0] {
        desc.traffic_density = density;
        for n in 0..12 {
            // A closed slot stays empty unless it is the ego's.
            assert_eq!(slot_body(&desc, cars, (n, false), &mut r, None), None);
            let ego = Some(BodyKind::Van);
            assert_eq!(slot_body(&desc, cars, (n, false), &mut r, ego), ego);
            let car = slot_body(&desc, cars, (n, true), &mut r, None);
            assert_eq!(car.is_some(), density == 1.0, "slot {n}");
            assert!(car.is_none_or(|b| cars.route.bodies.contains(&b)));
            // Every third slot of the long-vehicle route is a bus line.
            let b = slot_body(&desc, bus, (n, true), &mut r, None);
            if n % 3 == 0 {
                assert!(matches!(b, Some(BodyKind::Bus | BodyKind::Truck)), "{b:?}");
            } else {
                assert_eq!(b.is_some(), density == 1.0, "slot {n}");
            }
        }
    }
}

#[test]
fn shorter_bodies_ride_forward_on_block_loops_and_centred_on_the_ring() {
    let plan = Plan::new(&town("town05"));
    for rp in &plan.routes {
        let longest = *rp
            .route
            .bodies
            .iter()
            .max_by(|a, b| a.footprint_m()[0].total_cmp(&b.footprint_m()[0]))
            .unwrap();
        let short = BodyKind::Hatchback;
        // At the route's start both lie on its first straight.
        let (p_long, h_long) = slot_pose(rp, 0.0, longest);
        let (p_short, h_short) = slot_pose(rp, 0.0, short);
        // The longest body fills its slot: no shift from the slot's pose.
        let (p_slot, h_slot) = rp.route.pose(rp.profile.arc_at(0.0));
        let d_long = (p_long[0] - p_slot[0]).hypot(p_long[1] - p_slot[1]);
        assert!(d_long < 1e-9 && (h_long - h_slot).abs() < 1e-12, "{d_long}");
        let ahead = [p_short[0] - p_long[0], p_short[1] - p_long[1]];
        let along = ahead[0] * h_long.cos() + ahead[1] * h_long.sin();
        let expected = match rp.route.kind {
            RouteKind::Block { .. } => (longest.footprint_m()[0] - short.footprint_m()[0]) / 2.0,
            _ => 0.0,
        };
        assert!(
            (along - expected).abs() < 1e-9,
            "{:?}: {along}",
            rp.route.kind
        );
        assert!((h_short - h_long).abs() < 1e-12);
    }
}
