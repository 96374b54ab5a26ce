//! Riders: every bicycle and motorcycle of a town frame carries one seated
//! person, class `rider`, sharing the vehicle's pose and instance id; the
//! rider's prefab exists and is labelled `rider` throughout.

use parallax::scene::desc::ShapeDesc;
use parallax::town::{frame_at, town_scene, CameraConfig, VEHICLE_ID_BASE};

use crate::common::towns::town;

#[test]
fn every_two_wheeler_carries_one_rider_in_its_pose() {
    let desc = town("town03");
    let (seed, frame) = (0, 0);
    let tf = frame_at(&desc, seed, frame);
    let scene = town_scene(&desc, seed, frame, CameraConfig::Normal);
    let riders: Vec<_> = scene
        .objects
        .iter()
        .filter(|o| o.semantic.as_deref() == Some("rider"))
        .collect();
    let two_wheelers: Vec<_> = tf
        .vehicles
        .iter()
        .filter(|v| v.body.seat().is_some())
        .collect();
    assert!(
        two_wheelers.len() >= 5,
        "only {} two-wheelers",
        two_wheelers.len()
    );
    assert_eq!(
        riders.len(),
        two_wheelers.len(),
        "one rider per two-wheeler"
    );
    for v in two_wheelers {
        let id = (VEHICLE_ID_BASE + v.id) as u16;
        let r = riders
            .iter()
            .find(|o| o.instance == Some(id))
            .unwrap_or_else(|| panic!("vehicle {} ({:?}) has no rider", v.id, v.body));
        let at = r.transform.translate.expect("placed");
        for (got, want) in at.iter().zip(v.position) {
            assert!((got - want).abs() < 1e-9, "rider off its vehicle");
        }
        let heading = r.transform.rotate_deg.map_or(0.0, |q| q[2]);
        assert!(
            (heading - v.heading_deg).abs() < 1e-9,
            "rider turned off the heading"
        );
        let ShapeDesc::Instance { prefab, .. } = &r.shape else {
            panic!("a rider is a prefab instance");
        };
        assert!(
            prefab.starts_with(v.body.prefab()),
            "{prefab} rides a {:?}",
            v.body
        );
        let p = scene
            .prefabs
            .iter()
            .find(|p| &p.name == prefab)
            .unwrap_or_else(|| panic!("prefab {prefab} missing"));
        assert!(p.objects.len() >= 3, "{prefab}: {} parts", p.objects.len());
        assert!(p
            .objects
            .iter()
            .all(|o| o.semantic.as_deref() == Some("rider")));
    }
}
