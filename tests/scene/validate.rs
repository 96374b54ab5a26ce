//! Schema tests: every shipped scene loads and builds; desc → TOML → desc is
//! the identity; the build places geometry where the description says
//! (bounds, corners, repeats, prefab instancing, f64 origin subtraction).

use std::path::{Path, PathBuf};

use glam::{DVec3, Vec3};
use parallax::light::Light;
use parallax::scene::load::parse_desc;
use parallax::scene::{
    build_scene, load_scene, mask_bits, parse_scene_str, serialize_scene, LoadedScene, Mesh, Scene,
};
use shaders_cpu::bsdf::Bsdf;
use shaders_cpu::sky::Sky;

const HEADER: &str = r#"
[camera]
position = [0.0, 0.0, 1.5]
[sky]
kind = "constant"
le = [1.0, 1.0, 1.0]
[[material]]
name = "grey"
kind = "diffuse"
albedo = [0.5, 0.5, 0.5]
[[material]]
name = "red"
kind = "diffuse"
albedo = [0.9, 0.1, 0.1]
"#;

fn load(body: &str) -> LoadedScene {
    let text = format!("{HEADER}{body}");
    parse_scene_str(&text, Path::new("test.toml")).unwrap_or_else(|e| panic!("{e}"))
}

fn build(body: &str, origin: DVec3) -> Scene {
    build_scene(&load(body), origin).unwrap_or_else(|e| panic!("{e}"))
}

fn bounds(m: &Mesh) -> (DVec3, DVec3) {
    let lo = m
        .p_render
        .iter()
        .fold(DVec3::splat(f64::INFINITY), |a, &p| a.min(p));
    let hi = m
        .p_render
        .iter()
        .fold(DVec3::splat(f64::NEG_INFINITY), |a, &p| a.max(p));
    (lo, hi)
}

fn scene_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            scene_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "toml")
            // Town parameter files are not scenes (tests/town/ covers them).
            && !path.file_name().is_some_and(|n| n.to_string_lossy().starts_with("town"))
        {
            out.push(path);
        }
    }
}

fn all_scene_files() -> Vec<PathBuf> {
    let mut files = Vec::new();
    scene_files(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes"),
        &mut files,
    );
    assert!(
        files.len() >= 5,
        "expected the analytic scenes, found {files:?}"
    );
    files
}

#[test]
fn every_scene_file_loads_and_builds() {
    for path in all_scene_files() {
        let loaded = load_scene(&path).unwrap_or_else(|e| panic!("{e}"));
        let origin = DVec3::from(loaded.desc.camera.position);
        let scene = build_scene(&loaded, origin).unwrap_or_else(|e| panic!("{e}"));
        let prims = scene.triangle_count() as u64 + scene.spheres.len() as u64;
        assert_eq!(prims, loaded.triangle_estimate, "{}", path.display());
        assert!(prims > 0, "{}", path.display());
    }
}

const RICH: &str = r#"
[render]
spp = 16
max_depth = 5
seed = 42
[[light]]
kind = "sun"
elevation_deg = 30.0
azimuth_deg = -45.5
irradiance = [900.0, 800.0, 700.0]
[[light]]
kind = "point"
position = [1.0, 2.0, 3.0]
intensity = [10.0, 10.0, 10.0]
[[light]]
kind = "spot"
position = [0.0, 0.0, 5.0]
direction = [0.0, 0.0, -1.0]
intensity = [100.0, 90.0, 80.0]
inner_deg = 20.0
outer_deg = 30.0
[[material]]
name = "chrome"
kind = "conductor"
preset = "chrome"
roughness = 0.05
[[material]]
name = "metal"
kind = "conductor"
eta = [0.2, 0.9, 1.1]
k = [3.9, 2.4, 2.1]
roughness = 0.4
mask = []
[[material]]
name = "glass"
kind = "dielectric"
ior = 1.52
tint = [0.9, 1.0, 0.9]
[[material]]
name = "lamp"
kind = "emissive"
radiance = [5.0, 5.0, 4.0]
two_sided = true
[[object]]
kind = "cylinder"
radius = 0.1
height = 4.0
segments = 8
capped = false
material = "metal"
semantic = "pole"
repeat = [{ count = 3, offset = [10.0, 0.0, 0.0] }]
[[object]]
kind = "ellipsoid"
radii = [1.0, 1.0, 2.0]
material = "grey"
transform = { scale = [1.0, 2.0, 0.5], rotate_deg = [0.0, 0.0, 10.0] }
[[object]]
kind = "instance"
prefab = "lamp_post"
material_map = { grey = "red" }
semantic = "pole"
instance = 9
transform = { translate = [3.0, 4.0, 0.0], scale = 2.0 }
[[prefab]]
name = "lamp_post"
[[prefab.object]]
kind = "box"
size = [0.2, 0.2, 3.0]
material = "grey"
[[prefab.object]]
kind = "sphere"
radius = 0.3
material = "lamp"
transform = { translate = [0.0, 0.0, 3.2] }
"#;

#[test]
fn desc_to_toml_to_desc_is_identity() {
    let mut texts = vec![format!("{HEADER}{RICH}")];
    texts.extend(
        all_scene_files()
            .iter()
            .map(|p| std::fs::read_to_string(p).unwrap()),
    );
    for text in texts {
        let desc = parse_desc(&text, Path::new("x.toml")).unwrap_or_else(|e| panic!("{e}"));
        let written = serialize_scene(&desc);
        let again = parse_desc(&written, Path::new("written.toml"))
            .unwrap_or_else(|e| panic!("{e}\n{written}"));
        assert_eq!(desc, again, "{written}");
        parse_scene_str(&written, Path::new("written.toml")).unwrap_or_else(|e| panic!("{e}"));
    }
}

#[test]
fn rich_scene_builds_every_shape_with_normals_where_curved() {
    let scene = build(RICH, DVec3::ZERO);
    // 3 cylinders (16 side triangles each), 1 ellipsoid, 1 box; 1 sphere.
    assert_eq!(scene.meshes.len(), 5);
    assert_eq!(scene.spheres.len(), 1);
    for m in &scene.meshes[..4] {
        assert_eq!(m.normals.len(), m.p_f32.len());
        assert!(m.normals.iter().all(|n| (n.length() - 1.0).abs() < 1e-5));
    }
    assert!(scene.meshes[4].normals.is_empty());
    assert_eq!(scene.meshes[0].semantic, 6); // CARLA: pole
                                             // The instance scales the prefab by 2: sphere radius 0.6 at (3, 4, 6.4).
    assert!((scene.spheres[0].radius - 0.6).abs() < 1e-12);
    assert!((scene.spheres[0].center - DVec3::new(3.0, 4.0, 6.4)).length() < 1e-12);
    assert_eq!(scene.spheres[0].instance, 9);
}

#[test]
fn box_bounds_follow_size_and_translation() {
    let scene = build(
        r#"
[[object]]
kind = "box"
size = [2.0, 4.0, 6.0]
material = "grey"
transform = { translate = [10.0, 20.0, 30.0] }
"#,
        DVec3::ZERO,
    );
    let (lo, hi) = bounds(&scene.meshes[0]);
    assert_eq!(lo, DVec3::new(9.0, 18.0, 27.0));
    assert_eq!(hi, DVec3::new(11.0, 22.0, 33.0));
    assert_eq!(scene.meshes[0].triangles.len(), 12);
}

#[test]
fn transformed_quad_corners_follow_scale_rotate_translate_order() {
    // Local corners (±1, ±2, 0) · 2 → (±2, ±4, 0); Rx(90°): (x, y, z) → (x, −z, y)
    // gives (±2, 0, ±4); Rz(90°): (x, y, z) → (−y, x, z) gives (0, ±2, ±4); + (1, 2, 3).
    let scene = build(
        r#"
[[object]]
kind = "quad"
size = [2.0, 4.0]
material = "grey"
transform = { translate = [1.0, 2.0, 3.0], rotate_deg = [90.0, 0.0, 90.0], scale = 2.0 }
"#,
        DVec3::ZERO,
    );
    let mesh = &scene.meshes[0];
    assert_eq!(mesh.p_render.len(), 4);
    for &p in &mesh.p_render {
        assert!((p.x - 1.0).abs() < 1e-12, "{p}");
        assert!(((p.y - 2.0).abs() - 2.0).abs() < 1e-12, "{p}");
        assert!(((p.z - 3.0).abs() - 4.0).abs() < 1e-12, "{p}");
    }
    // The local normal +z: Rx(90°) → −y, Rz(90°) → +x.
    let [a, b, c] = mesh.triangles[0].map(|i| mesh.p_render[i as usize]);
    assert!((b - a).cross(c - a).normalize().distance(DVec3::X) < 1e-12);
}

#[test]
fn repeat_grid_makes_every_copy_at_its_offset() {
    let scene = build(
        r#"
[[object]]
kind = "box"
size = [1.0, 1.0, 1.0]
material = "grey"
repeat = [{ count = 3, offset = [5.0, 0.0, 0.0] }, { count = 2, offset = [0.0, 10.0, 0.0] }]
"#,
        DVec3::ZERO,
    );
    assert_eq!(scene.meshes.len(), 6);
    let mut centres: Vec<[i64; 3]> = scene
        .meshes
        .iter()
        .map(|m| {
            let (lo, hi) = bounds(m);
            ((lo + hi) / 2.0).round().as_i64vec3().to_array()
        })
        .collect();
    centres.sort();
    let mut expected: Vec<[i64; 3]> = (0..3)
        .flat_map(|i| (0..2).map(move |j| [5 * i, 10 * j, 0]))
        .collect();
    expected.sort();
    assert_eq!(centres, expected);
}

#[test]
fn prefab_instance_applies_transform_material_map_and_overrides() {
    let scene = build(
        r#"
[[object]]
kind = "instance"
prefab = "car"
material_map = { paint = "red" }
semantic = "car"
instance = 5
transform = { translate = [100.0, 0.0, 0.0], rotate_deg = [0.0, 0.0, 90.0] }
[[prefab]]
name = "car"
[[prefab.object]]
kind = "box"
size = [4.0, 2.0, 1.0]
material = "paint"
semantic = "unlabeled"
transform = { translate = [0.0, 0.0, 1.0] }
[[prefab.object]]
kind = "sphere"
radius = 0.4
material = "grey"
transform = { translate = [1.5, 1.0, 0.4] }
[[material]]
name = "paint"
kind = "diffuse"
albedo = [0.2, 0.2, 0.9]
"#,
        DVec3::new(100.0, 0.0, 0.0),
    );
    let body = &scene.meshes[0];
    assert_eq!(scene.materials[body.tri_material[0] as usize].name, "red");
    assert_eq!((body.semantic, body.instance), (14, 5)); // CARLA: car
                                                         // Rz(90°): the 4 m long axis now runs along y.
    let (lo, hi) = bounds(body);
    assert!((lo - DVec3::new(-1.0, -2.0, 0.5)).length() < 1e-12, "{lo}");
    assert!((hi - DVec3::new(1.0, 2.0, 1.5)).length() < 1e-12, "{hi}");
    let wheel = &scene.spheres[0];
    assert!(
        (wheel.center - DVec3::new(-1.0, 1.5, 0.4)).length() < 1e-12,
        "{}",
        wheel.center
    );
    assert_eq!(scene.materials[wheel.material as usize].name, "grey");
    assert_eq!((wheel.semantic, wheel.instance), (14, 5));
    assert_eq!(scene.spheres_f32[0].w, 0.4);
}

#[test]
fn origin_subtraction_is_exact_far_from_the_world_origin() {
    let scene = build(
        r#"
[[object]]
kind = "box"
size = [0.5, 0.5, 0.5]
material = "grey"
transform = { translate = [200000.25, -300000.0, 12.5] }
[[object]]
kind = "sphere"
radius = 1.0
material = "grey"
transform = { translate = [200003.0, -300000.0, 10.0] }
"#,
        DVec3::new(200000.0, -300000.0, 10.0),
    );
    let (lo, hi) = bounds(&scene.meshes[0]);
    assert_eq!(lo, DVec3::new(0.0, -0.25, 2.25));
    assert_eq!(hi, DVec3::new(0.5, 0.25, 2.75));
    assert_eq!(
        scene.meshes[0].p_f32[0],
        scene.meshes[0].p_render[0].as_vec3()
    );
    assert_eq!(scene.spheres[0].center, DVec3::new(3.0, 0.0, 0.0));
}

#[test]
fn lights_and_sky_are_built_in_render_space() {
    let scene = build(
        r#"
[[light]]
kind = "sun"
elevation_deg = 0.0
azimuth_deg = 90.0
irradiance = [1.0, 2.0, 3.0]
angular_diameter_deg = 1.0
[[light]]
kind = "point"
position = [105.0, 2.0, 3.0]
intensity = [1.0, 1.0, 1.0]
[[light]]
kind = "spot"
position = [100.0, 0.0, 10.0]
direction = [0.0, 0.0, -3.0]
intensity = [1.0, 1.0, 1.0]
inner_deg = 60.0
outer_deg = 90.0
"#,
        DVec3::new(100.0, 0.0, 0.0),
    );
    let Light::Sun {
        dir_to_sun,
        angular_radius_rad,
        irradiance,
    } = scene.lights[0]
    else {
        panic!("{:?}", scene.lights[0])
    };
    assert!((dir_to_sun - Vec3::Y).length() < 1e-7);
    assert!((angular_radius_rad - 0.5f32.to_radians()).abs() < 1e-7);
    assert_eq!(irradiance, Vec3::new(1.0, 2.0, 3.0));
    assert_eq!(
        scene.lights[1],
        Light::Point {
            p: Vec3::new(5.0, 2.0, 3.0),
            intensity: Vec3::ONE
        }
    );
    let Light::Spot {
        p,
        dir,
        cos_inner,
        cos_outer,
        ..
    } = scene.lights[2]
    else {
        panic!("{:?}", scene.lights[2])
    };
    assert_eq!((p, dir), (Vec3::new(0.0, 0.0, 10.0), -Vec3::Z));
    assert!((cos_inner - 0.5).abs() < 1e-7 && cos_outer.abs() < 1e-7);
    assert_eq!(scene.sky, Sky::Constant { le: Vec3::ONE });
}

#[test]
fn material_kinds_set_mask_bits() {
    let scene = build(
        r#"
[[material]]
name = "chrome"
kind = "conductor"
preset = "chrome"
roughness = 0.05
[[material]]
name = "brushed"
kind = "conductor"
preset = "aluminium"
roughness = 0.5
[[material]]
name = "glass"
kind = "dielectric"
[[material]]
name = "puddle"
kind = "diffuse"
albedo = [0.1, 0.1, 0.1]
mask = ["mirror", "transparent"]
[[object]]
kind = "quad"
size = [1.0, 1.0]
material = "grey"
"#,
        DVec3::ZERO,
    );
    let find = |name: &str| scene.materials.iter().find(|m| m.name == name).unwrap();
    assert_eq!(find("grey").mask, 0);
    assert_eq!(find("chrome").mask, mask_bits::MIRROR);
    assert_eq!(find("brushed").mask, 0);
    assert_eq!(find("glass").mask, mask_bits::TRANSPARENT);
    assert_eq!(
        find("puddle").mask,
        mask_bits::MIRROR | mask_bits::TRANSPARENT
    );
    assert!(matches!(find("brushed").bsdf, Bsdf::Conductor { alpha, .. } if alpha == 0.25));
    assert!(matches!(find("glass").bsdf, Bsdf::Dielectric { eta, .. } if eta == 1.5));
}

#[test]
fn obj_with_mtl_becomes_meshes_with_named_materials() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("sign.mtl"),
        "newmtl plate\nKd 0.8 0.8 0.8\nnewmtl light\nKd 0 0 0\nKe 4 4 4\n",
    )
    .unwrap();
    std::fs::write(
        dir.path().join("sign.obj"),
        "mtllib sign.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\n\
         usemtl plate\nf 1 2 3 4\nusemtl light\nf 1 2 3\nf 1 2 5\n",
    )
    .unwrap();
    let scene_path = dir.path().join("s.toml");
    let text =
        "[camera]\nposition = [0.0, 0.0, 0.0]\n[[object]]\nkind = \"obj\"\nfile = \"sign.obj\"\n\
                semantic = \"traffic_sign\"\ntransform = { translate = [10.0, 0.0, 0.0] }\n";
    std::fs::write(&scene_path, text).unwrap();
    // No sun, sky or point light: the emissive MTL material is the scene's light.
    let loaded = load_scene(&scene_path).unwrap_or_else(|e| panic!("{e}"));
    // "f 1 2 5" is collinear: dropped.
    assert_eq!(loaded.objs["sign.obj"].dropped_degenerate, 1);
    assert_eq!(loaded.triangle_estimate, 3);
    let scene = build_scene(&loaded, DVec3::ZERO).unwrap();
    assert_eq!(scene.triangle_count(), 3);
    let mesh = &scene.meshes[0];
    assert_eq!(mesh.semantic, 8); // CARLA: traffic_sign
    let names: Vec<&str> = mesh
        .tri_material
        .iter()
        .map(|&m| scene.materials[m as usize].name.as_str())
        .collect();
    assert_eq!(
        names,
        ["sign.obj/plate", "sign.obj/plate", "sign.obj/light"]
    );
    let light = scene
        .materials
        .iter()
        .find(|m| m.name == "sign.obj/light")
        .unwrap();
    assert_eq!(light.le, Vec3::splat(4.0));
    assert!(mesh.p_render.iter().all(|p| p.x >= 10.0 && p.x <= 12.0));
}

/// Nearest hit parameter of the ray o + t·d over every triangle and sphere
/// (brute force, f64; Möller–Trumbore), `None` for sky.
fn nearest_hit(scene: &Scene, o: DVec3, d: DVec3) -> Option<f64> {
    let mut best = f64::INFINITY;
    for m in &scene.meshes {
        for t in &m.triangles {
            if let Some(t) = crate::common::triangle::hit(o, d, t.map(|i| m.p_render[i as usize])) {
                best = best.min(t);
            }
        }
    }
    for s in &scene.spheres {
        let oc = s.center - o;
        let (dd, b) = (d.length_squared(), d.dot(oc));
        let disc = b * b - dd * (oc.length_squared() - s.radius * s.radius);
        if disc >= 0.0 {
            best = best.min((b - disc.sqrt()) / dd);
        }
    }
    best.is_finite().then_some(best)
}

/// depth_z along camera direction (a, b, 1) for the unrotated rig of a shipped
/// scene: world direction (1, −a, −b), so depth_z = t.
fn depth_z(name: &str, a: f64, b: f64) -> Option<f64> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes/analytic")
        .join(name);
    let loaded = load_scene(&path).unwrap_or_else(|e| panic!("{e}"));
    let cam = &loaded.desc.camera;
    assert_eq!([cam.yaw_deg, cam.pitch_deg, cam.roll_deg], [0.0; 3]);
    let scene = build_scene(&loaded, DVec3::from(cam.position)).unwrap();
    nearest_hit(&scene, DVec3::ZERO, DVec3::new(1.0, -a, -b))
}

#[test]
fn analytic_scene_comments_match_the_built_geometry() {
    let tan30 = 30f64.to_radians().tan();
    let close = |z: Option<f64>, want: f64| {
        let z = z.expect("expected a hit");
        assert!((z - want).abs() <= 1e-9 * want, "{z} vs {want}");
    };
    for (a, b) in [(0.0, 0.0), (-0.5, 0.3), (0.57, -0.32), (0.123, 0.456)] {
        close(depth_z("fronto_plane.toml", a, b), 10.0);
        close(depth_z("tilted_plane.toml", a, b), 10.0 / (1.0 - tan30 * a));
    }
    // Sphere: s = (10, 0, 0), r = 2, d = (1, −a, −b).
    for (a, b) in [(0.0, 0.0), (0.1, -0.05), (-0.15, 0.12)] {
        let d = DVec3::new(1.0, -a, -b);
        let ds = 10.0;
        let want =
            (ds - (ds * ds - d.length_squared() * (100.0 - 4.0)).sqrt()) / d.length_squared();
        close(depth_z("sphere.toml", a, b), want);
    }
    assert_eq!(depth_z("sphere.toml", 0.3, 0.0), None);
    // Boxes: through each front-face centre (x, y, 1.5) the direction is (1, −y/x, 0).
    close(depth_z("boxes.toml", -1.5 / 5.0, 0.0), 5.0);
    close(depth_z("boxes.toml", 0.0, 0.05), 10.0);
    close(depth_z("boxes.toml", 4.0 / 20.0, -0.02), 20.0);
    close(depth_z("boxes.toml", -0.5, 0.4), 60.0);
    // Road: depth_z = 1.5 / b below the horizon up to the 10 km edge, sky above.
    for b in [0.5, 0.01, 2e-4] {
        close(depth_z("road_plane.toml", 0.3, b), 1.5 / b);
    }
    assert_eq!(depth_z("road_plane.toml", 0.0, 1e-4), None);
    assert_eq!(depth_z("road_plane.toml", 0.0, -0.1), None);
    // Box on ground: the cube's front face x = 5 for a ∈ [−0.3, 0.1] and
    // b ∈ [−0.07, 0.33], the ground at 1.65 / b elsewhere below the horizon.
    for (a, b) in [(0.0, 0.0), (-0.29, 0.32), (0.09, -0.06)] {
        close(depth_z("box_on_ground.toml", a, b), 5.0);
    }
    for (a, b) in [(0.3, 0.1), (-0.4, 0.05), (0.0, 0.34), (0.2, 0.004)] {
        close(depth_z("box_on_ground.toml", a, b), 1.65 / b);
    }
    assert_eq!(depth_z("box_on_ground.toml", 0.0, -0.08), None);
    assert_eq!(depth_z("box_on_ground.toml", 0.2, 0.003), None);
}
