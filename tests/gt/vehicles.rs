//! Ground truth on a generated car's thin parts (`town::vehicles`): a
//! sedan's painted panels and parts (glass, mirrors, wipers, spoked rims)
//! instanced side-on 3.6 m from a level rig at 96×54, where the rim spokes
//! (2 cm) and the mirror glass seen edge-on are below a pixel. Every
//! pixel's depth and disparity, left and right views, against rays traced
//! here in f64 through the prefabs' triangles placed here (turn about z,
//! shift), the ground plane z = 0 behind (the tracer of `vegetation`).

use crate::common;
use crate::vegetation::{buckets, dir, f_px, trace, H, W};

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
    let cams: Vec<DVec3> = std::iter::once(c_left)
        .chain(
            BASELINES_M
                .iter()
                .map(|&b| c_left + DVec3::new(0.0, -b, 0.0)),
        )
        .collect();
    let f = f_px();
    let (mut ties, mut checked, mut car_px) = (0usize, 0usize, 0usize);
    let (mut rim_px, mut mirror_px) = (0usize, 0usize);
    for (v, &c) in cams.iter().enumerate() {
        let cand = buckets(c, &tris);
        for j in 0..H {
            for i in 0..W {
                let k = (j * W + i) as usize;
                let (z_true, tie) = trace(c, dir(i, j), &tris, &cand[k]);
                if tie {
                    ties += 1;
                    continue;
                }
                let (z, d) = if v == 0 {
                    let b = &r.out.baselines;
                    (
                        r.out.left.depth_z[k],
                        b.iter().map(|b| b.disparity_left[k]).collect(),
                    )
                } else {
                    let b = &r.out.baselines[v - 1];
                    (b.depth_right[k] as f64, vec![b.disparity_right[k]])
                };
                checked += 1;
                let Some(zt) = z_true else {
                    assert!(z.is_infinite(), "view {v} ({i},{j}): {z}, not sky");
                    continue;
                };
                assert!(
                    (z - zt).abs() <= 1e-5 * zt,
                    "view {v} pixel ({i},{j}): Z {z} vs {zt}"
                );
                let bs: Vec<f64> = if v == 0 {
                    BASELINES_M.to_vec()
                } else {
                    vec![BASELINES_M[v - 1]]
                };
                for (dv, bm) in d.iter().zip(bs) {
                    let dt = f * bm / zt;
                    let dv = *dv as f64;
                    assert!(
                        (dv - dt).abs() <= 1e-5 * dt + 1e-6,
                        "view {v} pixel ({i},{j}) B={bm}: d {dv} vs {dt}"
                    );
                }
                // Which part the true first hit is on: the same depth from
                // that part's triangles alone.
                let on = |set: &[u32]| {
                    let sub: Vec<u32> = cand[k]
                        .iter()
                        .copied()
                        .filter(|t| set.contains(t))
                        .collect();
                    matches!(trace(c, dir(i, j), &tris, &sub), (Some(t), false) if t == zt)
                };
                let dz = dir(i, j).z;
                let ground = if dz < 0.0 { c.z / -dz } else { f64::INFINITY };
                let on_car = zt < ground * (1.0 - 1e-12);
                if v == 0 {
                    assert_eq!(
                        r.out.left.semantic[k] == car,
                        on_car,
                        "pixel ({i},{j}): semantic {} at Z {zt}",
                        r.out.left.semantic[k]
                    );
                    car_px += on_car as usize;
                }
                rim_px += (on_car && on(&rims)) as usize;
                mirror_px += (on_car && on(&mirrors)) as usize;
            }
        }
    }
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
