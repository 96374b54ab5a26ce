//! Ground truth on a generated car's thin parts (`town::vehicles`): a
//! sedan's painted panels and parts (glass, mirrors, wipers, spoked rims)
//! instanced side-on 3.6 m from a level rig at 96×54, where the rim spokes
//! (2 cm) and the mirror glass seen edge-on are below a pixel. Every
//! pixel's depth and disparity, left and right views, against rays traced
//! here in f64 through the prefabs' triangles placed here (turn about z,
//! shift), the ground plane z = 0 behind (the tracer of `vegetation`).

use crate::common;
use crate::traced::{check_views, dir, trace, H, W};

use common::{camera_block, render, scene_from_toml, GREY_UNDER_SKY};
use glam::DVec3;
use parallax::accel::Backend;
use parallax::scene::desc::{PrefabDesc, ShapeDesc};
use parallax::scene::serialize_scene;
use parallax::town::materials::vehicle_materials;
use parallax::town::parts::{instance, Label};
use parallax::town::vehicles::{vehicle_prefabs, BodyKind};

const BASELINES_M: [f64; 2] = [0.54, 3.0];
const AT: [f64; 3] = [4.6, -0.6, 0.0];
const TURN_DEG: f64 = 93.0;

/// World triangles of `prefab` placed at `AT` turned by `TURN_DEG`, with
/// each triangle's material.
fn placed(prefab: &PrefabDesc) -> Vec<([DVec3; 3], String)> {
    let (s, c) = TURN_DEG.to_radians().sin_cos();
    let place = |p: [f64; 3]| {
        DVec3::new(c * p[0] - s * p[1], s * p[0] + c * p[1], p[2]) + DVec3::from_array(AT)
    };
    let mut out = Vec::new();
    for o in &prefab.objects {
        let ShapeDesc::Mesh {
            positions,
            triangles,
            ..
        } = &o.shape
        else {
            panic!("vehicle prefabs are meshes");
        };
        let m = o.material.clone().unwrap();
        out.extend(
            triangles
                .iter()
                .map(|t| (t.map(|k| place(positions[k as usize])), m.clone())),
        );
    }
    out
}

#[test]
fn depth_and_disparity_exact_on_a_car_with_sub_pixel_spokes_and_mirrors() {
    let c_left = DVec3::new(0.0, 0.0, 0.9);
    let text = format!(
        "{}baselines_cm = [54.0, 300.0]\n{GREY_UNDER_SKY}\n[[object]]\nkind = \"quad\"\nsize = [400.0, 400.0]\nmaterial = \"grey\"\nsemantic = \"terrain\"\n",
        camera_block(W, H, c_left.to_array())
    );
    let mut desc = scene_from_toml(&text).desc;
    desc.materials.extend(vehicle_materials());
    let kind = BodyKind::Sedan;
    let prefabs: Vec<PrefabDesc> = vehicle_prefabs()
        .into_iter()
        .filter(|p| p.name == kind.prefab() || p.name == kind.parts_prefab())
        .collect();
    assert_eq!(prefabs.len(), 2);
    let l = Label {
        class: "car",
        instance: 7,
    };
    for p in &prefabs {
        let map: &[(&str, &str)] = if p.name == kind.prefab() {
            &[("car_paint", "paint_red")]
        } else {
            &[]
        };
        desc.objects.push(instance(&p.name, AT, TURN_DEG, map, l));
    }
    desc.prefabs.extend(prefabs.iter().cloned());
    let r = render(
        &scene_from_toml(&serialize_scene(&desc)),
        Backend::default_backend(),
        0,
    );

    let all: Vec<([DVec3; 3], String)> = prefabs.iter().flat_map(placed).collect();
    let tris: Vec<[DVec3; 3]> = all.iter().map(|(t, _)| *t).collect();
    let of = |m: &str| -> Vec<u32> {
        (0..all.len() as u32)
            .filter(|&k| all[k as usize].1 == m)
            .collect()
    };
    let (rims, mirrors) = (of("rim"), of("mirror"));
    let car = parallax::scene::semantic::class_id("car").expect("class");
    let (mut rim_px, mut mirror_px) = (0usize, 0usize);
    let (checked, ties, car_px) = check_views(&r.out, c_left, &BASELINES_M, &tris, car, |px| {
        // Which part the true first hit is on: the same depth from that
        // part's triangles alone.
        let on = |set: &[u32]| {
            let sub: Vec<u32> = px
                .cand
                .iter()
                .copied()
                .filter(|t| set.contains(t))
                .collect();
            matches!(trace(px.c, dir(px.i, px.j), &tris, &sub), (Some(t), false) if t == px.z)
        };
        rim_px += (px.on_object && on(&rims)) as usize;
        mirror_px += (px.on_object && on(&mirrors)) as usize;
    });
    eprintln!(
        "{checked} pixels checked, {car_px} on the car (left), {rim_px} on rims, {mirror_px} on mirror glass, {ties} edge ties"
    );
    assert!(car_px > 1000, "the car fills {car_px} pixels");
    assert!(
        rim_px >= 20 && mirror_px >= 1,
        "{rim_px} rim, {mirror_px} mirror pixels"
    );
    assert!(ties * 100 <= checked, "{ties} edge ties");
}
