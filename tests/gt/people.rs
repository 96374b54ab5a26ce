//! Ground truth on posed people (`town::people`): three walkers a few
//! metres ahead of a level rig at 96×54, two of them the same (variant,
//! phase) prefab (a shared prototype) and a child, so that legs and arms
//! span a few pixels each. Every pixel's depth and disparity, left and right
//! views, against rays traced here in f64 through the prefabs' triangles
//! placed here (turn about z, shift), with the ground plane z = 0 behind. A
//! pixel whose ray passes within 10 µm of a triangle edge may go either
//! way (the contract's edge tie); such pixels must stay rare.

use crate::common;
use crate::traced::{check_views, dir, placed_triangles, H, W};

use common::{camera_block, render, scene_from_toml, GREY_UNDER_SKY};
use glam::DVec3;
use parallax::accel::Backend;
use parallax::scene::serialize_scene;
use parallax::town::parts::{class, instance};
use parallax::town::people::{self, person_prefab, prefab_name};

const BASELINES_M: [f64; 2] = [0.54, 3.0];
/// (variant, walk phase, position, heading): two alike, one child.
const PEOPLE: [(u32, u32, [f64; 3], f64); 3] = [
    (5, 3, [6.0, 0.9, 0.0], 90.0),
    (5, 3, [6.5, -0.4, 0.0], 250.0),
    (0, 8, [5.5, -1.6, 0.0], 120.0),
];

/// The people's world triangles, placed here: p ↦ R_z(heading)·p + at.
fn people_triangles() -> Vec<[DVec3; 3]> {
    let mut out = Vec::new();
    for (v, ph, at, heading) in PEOPLE {
        let (s, c) = heading.to_radians().sin_cos();
        let place = |p: [f64; 3]| {
            DVec3::new(c * p[0] - s * p[1], s * p[0] + c * p[1], p[2]) + DVec3::from_array(at)
        };
        out.extend(placed_triangles(&person_prefab(v, Some(ph)).objects, place));
    }
    out
}

#[test]
fn depth_and_disparity_exact_on_the_limbs_of_posed_people() {
    let c_left = DVec3::new(0.0, 0.0, 1.0);
    let text = format!(
        "{}baselines_cm = [54.0, 300.0]\n{GREY_UNDER_SKY}\n[[object]]\nkind = \"quad\"\nsize = [400.0, 400.0]\nmaterial = \"grey\"\nsemantic = \"terrain\"\n",
        camera_block(W, H, c_left.to_array())
    );
    let mut desc = scene_from_toml(&text).desc;
    desc.materials.extend(people::people_materials());
    for (v, ph, at, heading) in PEOPLE {
        let name = prefab_name(v, Some(ph));
        if !desc.prefabs.iter().any(|p| p.name == name) {
            desc.prefabs.push(person_prefab(v, Some(ph)));
        }
        desc.objects
            .push(instance(&name, at, heading, &[], class("pedestrian")));
    }
    let scene = scene_from_toml(&serialize_scene(&desc));
    let r = render(&scene, Backend::default_backend(), 0);
    assert_eq!(
        r.scene.prototypes.len(),
        1,
        "the alike pair shares a prototype"
    );

    let tris = people_triangles();
    let ped = parallax::scene::semantic::class_id("pedestrian").expect("class");
    let mut legs_px = 0usize;
    let (checked, ties, person_px) = check_views(&r.out, c_left, &BASELINES_M, &tris, ped, |px| {
        // Legs: left-view hits between the ankles and the hips.
        let hit_z = px.c.z + dir(px.i, px.j).z * px.z;
        legs_px += (px.view == 0 && px.on_object && hit_z > 0.12 && hit_z < 0.75) as usize;
    });
    eprintln!(
        "{checked} pixels checked, {person_px} on people ({legs_px} legs, left), {ties} edge ties"
    );
    assert!(person_px > 150, "the people fill {person_px} pixels");
    assert!(legs_px > 30, "the legs fill {legs_px} pixels");
    assert!(ties * 100 <= checked, "{ties} edge ties");
}
