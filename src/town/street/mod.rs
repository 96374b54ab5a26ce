//! Street furniture prefabs (issue 21 item 5): printed traffic signs and
//! street-name plates (`signs`), lamp posts and traffic lights (`lights`),
//! benches, bins, bollards, hydrants, meters, bus shelters and billboards
//! (`fixtures`), fences, railings, guard rails, utility poles and wires
//! (`barriers`), built with `kit` and painted with `materials`. Each item
//! is a prefab placed by `kind = "instance"` objects (`town::furniture`),
//! so its detail is stored once however often it stands in a town.
//!
//! `StreetStyle` says which of them a town's streets get.

pub mod barriers;
pub mod fixtures;
pub mod kit;
pub mod lights;
pub mod materials;
pub mod names;
pub mod place;
pub mod signs;

use crate::scene::desc::{ObjectDesc, PrefabDesc};

use super::desc::{RoadStyle, TownDesc};

fn prefab(name: &str, objects: Vec<ObjectDesc>) -> PrefabDesc {
    PrefabDesc {
        name: name.to_string(),
        objects,
    }
}

/// Every street-furniture prefab.
pub fn furniture_prefabs() -> Vec<PrefabDesc> {
    [
        signs::sign_prefabs(),
        lights::light_prefabs(),
        fixtures::fixture_prefabs(),
        barriers::barrier_prefabs(),
    ]
    .concat()
}

/// The furniture style of a town's streets, from its description.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StreetStyle {
    /// Multi-lane streets with sidewalks: cobra-head lamps, mast-arm
    /// signals, parking meters, bus shelters, bollards, corner railings.
    City,
    /// One-lane streets with sidewalks: heritage lanterns, utility poles
    /// with overhead wires behind the sidewalk.
    SmallTown,
    /// Highway towns (`road_style = "highway"` or ≥ 80 km/h): twin-arm
    /// masts, guard rails, billboards.
    Highway,
    /// Country roads (no sidewalks): utility poles with wires, farm
    /// fences, the odd billboard, few lamps.
    Country,
}

impl StreetStyle {
    /// The style of `desc`.
    pub fn of(desc: &TownDesc) -> Self {
        if desc.road_style == RoadStyle::Highway || desc.speed_kmh >= 80.0 {
            StreetStyle::Highway
        } else if !desc.sidewalks {
            StreetStyle::Country
        } else if desc.lanes_per_direction >= 2 {
            StreetStyle::City
        } else {
            StreetStyle::SmallTown
        }
    }

    /// The lamp-post prefab of the style.
    pub fn lamp(self) -> &'static str {
        match self {
            StreetStyle::City | StreetStyle::Country => lights::LAMP_COBRA,
            StreetStyle::SmallTown => lights::LAMP_HERITAGE,
            StreetStyle::Highway => lights::LAMP_HIGHWAY,
        }
    }

    /// Whether utility poles carry overhead wires along the streets.
    pub fn wires(self) -> bool {
        matches!(self, StreetStyle::SmallTown | StreetStyle::Country)
    }
}

#[cfg(test)]
mod gallery {
    use crate::scene::desc::serialize_scene;
    use crate::town::parts::{class, ground_quad, instance};
    use crate::town::{source::load_named_town, town_scene, CameraConfig};

    /// Writes a scene with every furniture prefab in a row along +y, faces
    /// towards −x, seen from x = −`PARALLAX_GALLERY_DIST` (default 8 m),
    /// y = `PARALLAX_GALLERY_Y`, height `PARALLAX_GALLERY_Z`, pitch
    /// `PARALLAX_GALLERY_PITCH` (degrees, positive down), to the file
    /// `PARALLAX_GALLERY`: `cargo test --release --lib gallery --
    /// --ignored`, then `parallax render FILE`.
    #[test]
    #[ignore]
    fn write_gallery_scene() {
        let Ok(path) = std::env::var("PARALLAX_GALLERY") else {
            return;
        };
        let var = |name: &str, default: f64| -> f64 {
            std::env::var(name)
                .ok()
                .and_then(|d| d.parse().ok())
                .unwrap_or(default)
        };
        let (dist, at_y) = (
            var("PARALLAX_GALLERY_DIST", 8.0),
            var("PARALLAX_GALLERY_Y", 0.0),
        );
        let desc = load_named_town("town03", None).unwrap().desc;
        let mut scene = town_scene(&desc, 0, 0, CameraConfig::Normal);
        let mut objects = vec![ground_quad(
            [-40.0, -20.0],
            [40.0, 200.0],
            0.0,
            "sidewalk",
            class("sidewalk"),
        )];
        let mut y = 0.0;
        for p in super::furniture_prefabs() {
            objects.push(instance(&p.name, [0.0, y, 0.0], 0.0, &[], class("static")));
            y += 4.0;
        }
        scene.objects = objects;
        scene.camera.position = [-dist, at_y, var("PARALLAX_GALLERY_Z", 1.8)];
        scene.camera.yaw_deg = 0.0;
        scene.camera.pitch_deg = var("PARALLAX_GALLERY_PITCH", -8.0);
        std::fs::write(path, serialize_scene(&scene)).unwrap();
        for (k, p) in super::furniture_prefabs().iter().enumerate() {
            eprintln!("{k:3} y={:5.0} {}", 4.0 * k as f64, p.name);
        }
    }
}

#[cfg(test)]
mod tests;
