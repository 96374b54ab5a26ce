//! Ground truth on a parked car (`town::parking`): the first parked car of
//! town10 on an x-road, exactly as the town places it (its panels in the
//! drawn paint, parts, unlit lamps and registration, at its parked heading
//! a fraction of a degree off the kerb line), shifted to stand 2.2 m right
//! of a level rig at 96×54 as a car in the next bay would. Every pixel's
//! depth and disparity, left and right views, against rays traced here in
//! f64 through the prefabs' triangles placed here, the ground z = 0
//! behind (the tracer of `vegetation`).

use crate::common;
use crate::traced::{check_views, placed_triangles, H, W};

use common::towns::town;
use common::{camera_block, render, scene_from_toml, GREY_UNDER_SKY};
use glam::DVec3;
use parallax::accel::Backend;
use parallax::scene::desc::{ObjectDesc, PrefabDesc, ShapeDesc};
use parallax::scene::serialize_scene;
use parallax::town::materials::vehicle_materials;
use parallax::town::vehicles::vehicle_prefabs;
use parallax::town::{StaticTown, FURNITURE_ID_BASE, VEHICLE_ID_BASE};

const BASELINES_M: [f64; 2] = [0.54, 3.0];
/// Where the car's footprint centre is moved to.
const AT: [f64; 2] = [6.5, -2.2];

/// World triangles of `prefab` placed by `o`'s heading (about z) and
/// translation.
fn placed(prefab: &PrefabDesc, o: &ObjectDesc) -> Vec<[DVec3; 3]> {
    let h = o.transform.rotate_deg.map_or(0.0, |r| r[2]).to_radians();
    let (s, c) = h.sin_cos();
    let t = DVec3::from_array(o.transform.translate.unwrap());
    let place = |p: [f64; 3]| DVec3::new(c * p[0] - s * p[1], s * p[0] + c * p[1], p[2]) + t;
    placed_triangles(&prefab.objects, place)
}

#[test]
fn depth_and_disparity_exact_on_a_parked_car() {
    let desc = town("town10");
    let objects = StaticTown::new(&desc, 0).objects();
    // The first parked car on an x-road (heading within a degree of 0 or 180).
    let parked = |o: &ObjectDesc| {
        o.semantic.as_deref() == Some("car")
            && o.instance
                .is_some_and(|i| (FURNITURE_ID_BASE..VEHICLE_ID_BASE).contains(&u32::from(i)))
    };
    let along_x = |o: &ObjectDesc| {
        let h = o
            .transform
            .rotate_deg
            .map_or(0.0, |r| r[2])
            .rem_euclid(180.0);
        !(1.0..=179.0).contains(&h)
    };
    let first = objects
        .iter()
        .find(|o| parked(o) && along_x(o))
        .expect("a parked car on an x-road");
    let id = first.instance;
    let car: Vec<ObjectDesc> = objects
        .iter()
        .filter(|o| o.instance == id && o.semantic.as_deref() == Some("car"))
        .cloned()
        .map(|mut o| {
            let t = o.transform.translate.unwrap();
            let f = first.transform.translate.unwrap();
            o.transform.translate = Some([t[0] - f[0] + AT[0], t[1] - f[1] + AT[1], t[2]]);
            o
        })
        .collect();
    assert_eq!(car.len(), 4, "panels, parts, lamps and plate");

    let c_left = DVec3::new(0.0, 0.0, 0.9);
    let text = format!(
        "{}baselines_cm = [54.0, 300.0]\n{GREY_UNDER_SKY}\n[[object]]\nkind = \"quad\"\nsize = [400.0, 400.0]\nmaterial = \"grey\"\nsemantic = \"terrain\"\n",
        camera_block(W, H, c_left.to_array())
    );
    let mut desc = scene_from_toml(&text).desc;
    desc.materials.extend(vehicle_materials());
    let all = vehicle_prefabs();
    let prefab_of = |o: &ObjectDesc| -> PrefabDesc {
        let ShapeDesc::Instance { prefab, .. } = &o.shape else {
            panic!("an instance");
        };
        all.iter()
            .find(|p| &p.name == prefab)
            .expect("a prefab")
            .clone()
    };
    let mut tris = Vec::new();
    for o in &car {
        let p = prefab_of(o);
        tris.extend(placed(&p, o));
        desc.prefabs.push(p);
        desc.objects.push(o.clone());
    }
    let r = render(
        &scene_from_toml(&serialize_scene(&desc)),
        Backend::default_backend(),
        0,
    );
    let class = parallax::scene::semantic::class_id("car").expect("class");
    let (checked, ties, car_px) = check_views(&r.out, c_left, &BASELINES_M, &tris, class, |_| {});
    eprintln!("{checked} pixels checked, {car_px} on the parked car (left), {ties} edge ties");
    assert!(car_px > 600, "the car fills {car_px} pixels");
    assert!(ties * 100 <= checked, "{ties} edge ties");
    // Its instance id is the parked car's.
    let k = r
        .out
        .left
        .semantic
        .iter()
        .position(|&s| s == class)
        .expect("a car pixel");
    assert_eq!(Some(r.out.left.instance[k]), id);
}
