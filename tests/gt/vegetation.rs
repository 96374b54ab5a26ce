//! Ground truth on a grown tree (`town::vegetation`): one plane tree,
//! instanced with a turn and a scale, 25 m ahead of a level rig at 96×54,
//! where its leaves and twigs are far below a pixel. Every pixel's depth and
//! disparity, left and right views, against rays traced here in f64 through
//! the prefab's triangles transformed here (scale, turn about z, shift), with
//! the ground plane z = 0 behind. A pixel whose ray passes within 10 µm of
//! a triangle edge may go either way (the contract's edge tie); such pixels
//! must stay rare.

use crate::common;
use crate::traced::{check_views, f_px, H, W};

use common::{camera_block, render, scene_from_toml, GREY_UNDER_SKY};
use glam::DVec3;
use parallax::accel::Backend;
use parallax::scene::desc::{ScaleDesc, ShapeDesc};
use parallax::scene::serialize_scene;
use parallax::town::parts::{class, instance};
use parallax::town::vegetation::{self, Species};

const BASELINES_M: [f64; 2] = [0.54, 3.0];
const AT: [f64; 3] = [25.0, 1.0, 0.0];
const TURN_DEG: f64 = 37.0;
const SCALE: f64 = 1.05;

/// The tree's world triangles, placed here: p ↦ R_z(turn)·(s·p) + at;
/// the bark's first, then the leaves' (from the returned index).
fn tree_triangles() -> (Vec<[DVec3; 3]>, usize) {
    let prefab = vegetation::plant_prefab(
        "t".into(),
        &vegetation::grow_tree(Species::Plane, 0),
        "bark_plane".into(),
        "leaves_plane_0".into(),
    );
    let (s, c) = TURN_DEG.to_radians().sin_cos();
    let place = |p: [f64; 3]| {
        let q = DVec3::from_array(p) * SCALE;
        DVec3::new(c * q.x - s * q.y, s * q.x + c * q.y, q.z) + DVec3::from_array(AT)
    };
    let mut out = Vec::new();
    let mut leaves_from = 0;
    for o in &prefab.objects {
        leaves_from = out.len();
        let ShapeDesc::Mesh {
            positions,
            triangles,
            ..
        } = &o.shape
        else {
            panic!("a grown tree is meshes");
        };
        out.extend(
            triangles
                .iter()
                .map(|t| t.map(|k| place(positions[k as usize]))),
        );
    }
    (out, leaves_from)
}

#[test]
fn depth_and_disparity_exact_on_a_grown_tree_with_sub_pixel_leaves() {
    let c_left = DVec3::new(0.0, 0.0, 6.0);
    let text = format!(
        "{}baselines_cm = [54.0, 300.0]\n{GREY_UNDER_SKY}\n[[object]]\nkind = \"quad\"\nsize = [400.0, 400.0]\nmaterial = \"grey\"\nsemantic = \"terrain\"\n",
        camera_block(W, H, c_left.to_array())
    );
    let mut desc = scene_from_toml(&text).desc;
    desc.materials.extend(vegetation::materials());
    desc.prefabs.push(vegetation::plant_prefab(
        "tree".into(),
        &vegetation::grow_tree(Species::Plane, 0),
        "bark_plane".into(),
        "leaves_plane_0".into(),
    ));
    let mut tree = instance("tree", AT, TURN_DEG, &[], class("vegetation"));
    tree.transform.scale = Some(ScaleDesc::Uniform(SCALE));
    desc.objects.push(tree);
    let r = render(
        &scene_from_toml(&serialize_scene(&desc)),
        Backend::default_backend(),
        0,
    );

    let (tris, leaves_from) = tree_triangles();
    // The leaves are sub-pixel here: every leaf triangle spans < 1 px.
    let f = f_px();
    let leaf_px = tris[leaves_from..]
        .iter()
        .map(|t| {
            let ext = (t[1] - t[0]).length().max((t[2] - t[0]).length());
            ext * f / (t[0].x - c_left.x)
        })
        .fold(0.0, f64::max);
    assert!(leaf_px < 1.0, "largest leaf triangle spans {leaf_px} px");

    let veg = parallax::scene::semantic::class_id("vegetation").expect("class");
    let (checked, ties, tree_px) = check_views(&r.out, c_left, &BASELINES_M, &tris, veg, |_| {});
    eprintln!("{checked} pixels checked, {tree_px} on the tree (left), {ties} edge ties");
    // The airy crown: about a third of the pixels it spans hit a leaf or twig.
    assert!(tree_px > 200, "the tree fills {tree_px} pixels");
    assert!(ties * 100 <= checked, "{ties} edge ties");
}
