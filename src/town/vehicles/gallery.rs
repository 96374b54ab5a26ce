//! A test-only gallery scene: every vehicle model side by side on a
//! ground plane, for looking at them (`cargo test --release --lib
//! vehicle_gallery -- --ignored` with `PARALLAX_VEHICLES=FILE`, then
//! `parallax render FILE`).

use crate::scene::desc::serialize_scene;
use crate::town::parts::{class, ground_quad, instance, Label};
use crate::town::{source::load_named_town, town_scene, CameraConfig};

use super::BODIES;

/// Writes the gallery: models 6 m apart along +y, heading
/// `PARALLAX_VEHICLES_HEADING` (default 150°), seen from x =
/// −`PARALLAX_VEHICLES_DIST` (default 9 m) at y = `PARALLAX_VEHICLES_Y`,
/// height `PARALLAX_VEHICLES_Z`; `PARALLAX_VEHICLES_NIGHT=1` adds the
/// head-light spots (render with `--weather night`).
#[test]
#[ignore]
fn write_vehicle_gallery_scene() {
    let Ok(path) = std::env::var("PARALLAX_VEHICLES") else {
        return;
    };
    let var = |name: &str, default: f64| -> f64 {
        std::env::var(name)
            .ok()
            .and_then(|d| d.parse().ok())
            .unwrap_or(default)
    };
    let desc = load_named_town("town03", None).unwrap().desc;
    let mut scene = town_scene(&desc, 0, 0, CameraConfig::Normal);
    let mut objects = vec![ground_quad(
        [-60.0, -30.0],
        [60.0, 200.0],
        0.0,
        "asphalt",
        class("road"),
    )];
    let heading = var("PARALLAX_VEHICLES_HEADING", 150.0);
    let paints = crate::town::materials::PAINTS;
    for (k, b) in BODIES.iter().enumerate() {
        let at = [0.0, 6.0 * k as f64, 0.0];
        let l = Label {
            class: b.class(),
            instance: 30_000 + k as u16,
        };
        let paint = [("car_paint", paints[k % paints.len()])];
        objects.push(instance(b.prefab(), at, heading, &paint, l));
        objects.push(instance(&b.parts_prefab(), at, heading, &[], l));
        objects.push(instance(&b.lamps_prefab(), at, heading, &[], l));
        if let Some(p) = b.plate_prefab(0) {
            objects.push(instance(&p, at, heading, &[], l));
        }
    }
    scene.objects = objects;
    if std::env::var("PARALLAX_VEHICLES_NIGHT").is_ok() {
        super::add_headlights(&mut scene);
    }
    scene.camera.position = [
        -var("PARALLAX_VEHICLES_DIST", 9.0),
        var("PARALLAX_VEHICLES_Y", 0.0),
        var("PARALLAX_VEHICLES_Z", 1.6),
    ];
    scene.camera.yaw_deg = 0.0;
    scene.camera.pitch_deg = var("PARALLAX_VEHICLES_PITCH", -6.0);
    std::fs::write(path, serialize_scene(&scene)).unwrap();
}
