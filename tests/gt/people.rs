//! Ground truth on posed people (`town::people`): three walkers a few
//! metres ahead of a level rig at 96×54, two of them the same (variant,
//! phase) prefab (a shared prototype) and a child, so that legs and arms
//! span a few pixels each. Every pixel's depth and disparity, left and right
//! views, against rays traced here in f64 through the prefabs' triangles
//! placed here (turn about z, shift), with the ground plane z = 0 behind. A
//! pixel whose ray passes within 10 µm of a triangle edge may go either
//! way (the contract's edge tie); such pixels must stay rare.

use crate::common;

use common::{camera_block, render, scene_from_toml, GREY_UNDER_SKY};
use glam::DVec3;
use parallax::accel::Backend;
use parallax::scene::desc::ShapeDesc;
use parallax::scene::serialize_scene;
use parallax::town::parts::{class, instance};
use parallax::town::people::{self, person_prefab, prefab_name};

const W: u32 = 96;
const H: u32 = 54;
const BASELINES_M: [f64; 2] = [0.54, 3.0];
/// (variant, walk phase, position, heading): two alike, one child.
const PEOPLE: [(u32, u32, [f64; 3], f64); 3] = [
    (5, 3, [6.0, 0.9, 0.0], 90.0),
    (5, 3, [6.5, -0.4, 0.0], 250.0),
    (0, 8, [5.5, -1.6, 0.0], 120.0),
];
/// Ray-to-edge distance below which a pixel is an edge tie, metres.
const TIE_M: f64 = 1e-5;

fn f_px() -> f64 {
    (W as f64 / 2.0) / 30f64.to_radians().tan()
}

/// Ray direction with x component 1 (so t = depth Z) through pixel (i, j)
/// of a level camera looking along +x.
fn dir(i: u32, j: u32) -> DVec3 {
    let f = f_px();
    DVec3::new(
        1.0,
        -((i as f64 + 0.5) - W as f64 / 2.0) / f,
        -((j as f64 + 0.5) - H as f64 / 2.0) / f,
    )
}

/// The people's world triangles, placed here: p ↦ R_z(heading)·p + at.
fn people_triangles() -> Vec<[DVec3; 3]> {
    let mut out = Vec::new();
    for (v, ph, at, heading) in PEOPLE {
        let (s, c) = heading.to_radians().sin_cos();
        let place = |p: [f64; 3]| {
            DVec3::new(c * p[0] - s * p[1], s * p[0] + c * p[1], p[2]) + DVec3::from_array(at)
        };
        for o in person_prefab(v, Some(ph)).objects {
            let ShapeDesc::Mesh {
                positions,
                triangles,
                ..
            } = &o.shape
            else {
                panic!("a person is meshes");
            };
            out.extend(
                triangles
                    .iter()
                    .map(|t| t.map(|k| place(positions[k as usize]))),
            );
        }
    }
    out
}

/// Nearest hit of the ray c + t·d (Möller–Trumbore in f64) and whether it
/// is a tie: some triangle's boundary passes within `TIE_M` of the ray
/// before the nearest clear hit.
fn trace(c: DVec3, d: DVec3, tris: &[[DVec3; 3]], cand: &[u32]) -> (Option<f64>, bool) {
    let mut best: Option<f64> = None;
    let mut near_edges: Vec<f64> = Vec::new();
    for &k in cand {
        let [a, b, e] = tris[k as usize];
        let (e1, e2) = (b - a, e - a);
        let p = d.cross(e2);
        let det = e1.dot(p);
        if det.abs() < 1e-300 {
            continue;
        }
        let s = c - a;
        let u = s.dot(p) / det;
        let q = s.cross(e1);
        let v = d.dot(q) / det;
        let t = e2.dot(q) / det;
        if t <= 0.0 {
            continue;
        }
        // Distances of the plane hit point to the three edges, metres:
        // barycentric times the height over that edge.
        let area2 = e1.cross(e2).length();
        let bary = [1.0 - u - v, u, v];
        let edges = [e - b, e - a, b - a];
        let dist = |m: usize| bary[m] * area2 / edges[m].length();
        let inside = (0..3).map(dist).fold(f64::INFINITY, f64::min);
        if inside >= TIE_M {
            best = Some(best.map_or(t, |b: f64| b.min(t)));
        } else if inside > -TIE_M {
            near_edges.push(t);
        }
    }
    // The ground: the 400 m square z = 0 round the origin.
    if d.z < 0.0 {
        let t = -c.z / d.z;
        let p = c + d * t;
        if p.x.abs() < 200.0 && p.y.abs() < 200.0 {
            best = Some(best.map_or(t, |b: f64| b.min(t)));
        }
    }
    let tie = near_edges.iter().any(|&t| best.is_none_or(|b| t <= b));
    (best, tie)
}

/// Triangle indices whose projected bounding box covers each pixel of a
/// camera at `c` (every vertex is ahead of it).
fn buckets(c: DVec3, tris: &[[DVec3; 3]]) -> Vec<Vec<u32>> {
    let f = f_px();
    let mut out = vec![Vec::new(); (W * H) as usize];
    for (k, t) in tris.iter().enumerate() {
        let (mut lo, mut hi) = ([f64::MAX; 2], [f64::MIN; 2]);
        for p in t {
            let d = *p - c;
            assert!(d.x > 1.0, "person vertex behind the camera");
            let uv = [
                W as f64 / 2.0 - f * d.y / d.x,
                H as f64 / 2.0 - f * d.z / d.x,
            ];
            for a in 0..2 {
                lo[a] = lo[a].min(uv[a]);
                hi[a] = hi[a].max(uv[a]);
            }
        }
        // Pixel centres i + 0.5 in [lo, hi], one pixel of margin.
        let i0 = (lo[0] - 1.5).ceil().max(0.0) as u32;
        let i1 = ((hi[0] + 0.5).floor()).min(W as f64 - 1.0);
        let j0 = (lo[1] - 1.5).ceil().max(0.0) as u32;
        let j1 = ((hi[1] + 0.5).floor()).min(H as f64 - 1.0);
        if i1 < 0.0 || j1 < 0.0 {
            continue;
        }
        for j in j0..=j1 as u32 {
            for i in i0..=i1 as u32 {
                out[(j * W + i) as usize].push(k as u32);
            }
        }
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
    let f = f_px();
    let ped = parallax::scene::semantic::class_id("pedestrian").expect("class");
    let cams: Vec<DVec3> = std::iter::once(c_left)
        .chain(
            BASELINES_M
                .iter()
                .map(|&b| c_left + DVec3::new(0.0, -b, 0.0)),
        )
        .collect();
    let (mut ties, mut person_px, mut legs_px, mut checked) = (0, 0, 0, 0);
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
                    assert!(
                        z.is_infinite() && z > 0.0,
                        "view {v} ({i},{j}): {z}, not sky"
                    );
                    assert!(
                        d.iter().all(|&d| d == 0.0),
                        "view {v} ({i},{j}): sky disparity"
                    );
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
                let dz = dir(i, j).z;
                let ground = if dz < 0.0 { c.z / -dz } else { f64::INFINITY };
                // (beyond the square's edge the sky: no person there either)
                let on_person = zt < ground * (1.0 - 1e-12);
                if v == 0 {
                    assert_eq!(
                        r.out.left.semantic[k] == ped,
                        on_person,
                        "pixel ({i},{j}): semantic {} at Z {zt}",
                        r.out.left.semantic[k]
                    );
                    person_px += on_person as usize;
                    // Legs: hits between the ankles and the hips.
                    let hit_z = c.z + dz * zt;
                    legs_px += (on_person && hit_z > 0.12 && hit_z < 0.75) as usize;
                }
            }
        }
    }
    eprintln!(
        "{checked} pixels checked, {person_px} on people ({legs_px} legs, left), {ties} edge ties"
    );
    assert!(person_px > 150, "the people fill {person_px} pixels");
    assert!(legs_px > 30, "the legs fill {legs_px} pixels");
    assert!(ties * 100 <= checked, "{ties} edge ties");
}
