//! The shipped towns: their names and parameter files.

use std::path::{Path, PathBuf};

use parallax::accel::Accel;
use parallax::camera::StereoRig;
use parallax::render::{render_frame, FrameOutput, RenderSettings};
use parallax::scene::Scene;
use parallax::town::organic::Warp;
use parallax::town::{load_town, rig_desc, CameraConfig, TownDesc, TownFrame, VehiclePose};

/// Every town shipped in `scenes/`.
pub const TOWNS: [&str; 8] = [
    "town01", "town02", "town03", "town04", "town05", "town06", "town07", "town10",
];

/// `scenes/NAME.toml` of the repository.
pub fn town_file(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("scenes/{name}.toml"))
}

/// The parsed town file `scenes/NAME.toml` (panics with the loader's message).
pub fn town(name: &str) -> TownDesc {
    load_town(&town_file(name)).unwrap_or_else(|e| panic!("{e}"))
}

/// A town frame carried back into the level grid's plane: unchanged,
/// unless the town is organic, then through `Warp::unwarp_frame` (W⁻¹),
/// so that its poses can be checked against the `Layout`. Headings come
/// back through J⁻¹, so a level heading returns within rounding (1e-12°),
/// not bit for bit.
pub fn level_frame(desc: &TownDesc, seed: u64, f: TownFrame) -> TownFrame {
    match Warp::new(desc, seed) {
        Some(w) => w.unwarp_frame(&f),
        None => f,
    }
}

/// The ground-truth pass alone (spp 0) of `config`'s rig on `ego`, resized
/// to `width`×`height` with `baselines_cm`, over an already built town scene.
pub fn gt_frame(
    scene: &Scene,
    accel: &impl Accel,
    config: CameraConfig,
    ego: &VehiclePose,
    size: (u32, u32),
    baselines_cm: &[f64],
    (seed, frame): (u64, u64),
) -> (StereoRig, FrameOutput) {
    let mut rd = rig_desc(config, ego);
    (rd.width, rd.height, rd.baselines_cm) = (size.0, size.1, baselines_cm.to_vec());
    let rig = StereoRig::from_desc(&rd);
    let settings = RenderSettings {
        spp: 0,
        max_depth: 1,
        seed,
        frame: frame as u32,
        adaptive: false,
    };
    let out = render_frame(scene, accel, &rig, &settings, &|_, _| {});
    (rig, out)
}

/// A description's `Debug` text with class names as they were before
/// CARLA's table (issue 21): pinned hashes of descriptions computed before
/// the switch stay valid through it, which shows that the switch relabelled
/// classes one for one.
pub fn pre_carla_names(debug: &str) -> String {
    debug
        .replace("\"road_line\"", "\"lane_marking\"")
        .replace("\"bridge\"", "\"building\"")
        .replace("\"car\"", "\"vehicle\"")
        .replace("\"truck\"", "\"vehicle\"")
        .replace("\"bus\"", "\"vehicle\"")
}

/// Frame 0 of a town (`file` names it in errors) without its movers
/// (vehicles, riders, pedestrians), built around `origin`: the static
/// world that rays in the road tests should meet.
pub fn static_town_scene(
    desc: &TownDesc,
    seed: u64,
    file: &Path,
    origin: glam::DVec3,
) -> parallax::render::recipe::BuiltScene {
    let mut loaded = parallax::town::load_town_frame(desc, seed, 0, CameraConfig::Normal, file)
        .unwrap_or_else(|e| panic!("{e}"));
    loaded.desc.objects.retain(|ob| {
        !matches!(
            ob.semantic.as_deref(),
            Some("car" | "bus" | "truck" | "pedestrian" | "bicycle" | "motorcycle" | "rider")
        )
    });
    parallax::render::recipe::BuiltScene::build(
        &loaded,
        origin,
        parallax::accel::Backend::default_backend(),
    )
    .unwrap()
}

/// Every surface a ray straight down from world (x, y, from) passes, top
/// first: (class id, world z).
pub fn surfaces_below(
    built: &parallax::render::recipe::BuiltScene,
    origin: glam::DVec3,
    (x, y, from): (f64, f64, f64),
) -> Vec<(u8, f64)> {
    let mut out = Vec::new();
    let mut top = from;
    while let Some(hit) = built.accel.intersect(&parallax::accel::Ray::new(
        (glam::DVec3::new(x, y, top) - origin).as_vec3(),
        glam::Vec3::NEG_Z,
    )) {
        let z = top - hit.t as f64;
        out.push((built.scene.hit_labels(&hit).0, z));
        top = z - 1e-3;
    }
    out
}

/// Town01, town02 and town03 as they were before their parking lanes
/// (`parking_lane_m` 0, no parked cars, town02's 48 m and town03's 90 m
/// blocks, which grew with the wider roads): pins computed before hold
/// with the key at 0. Other towns are left as they are.
pub fn without_parking_lanes(desc: &mut TownDesc) {
    if desc.parking_lane_m == 0.0 {
        return;
    }
    (desc.parking_lane_m, desc.parking_density) = (0.0, 0.0);
    match desc.name.as_str() {
        "town02" => (desc.block_size_m, desc.extent_m) = (48.0, [240.0, 240.0]),
        "town03" => (desc.block_size_m, desc.extent_m) = (90.0, [540.0, 450.0]),
        _ => {}
    }
}
