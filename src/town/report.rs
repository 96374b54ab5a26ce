//! The content report of one town frame (`parallax town … --report
//! FILE.json`): what the frame holds (objects per semantic class, prototypes,
//! instances, unique and instanced triangles) and what building it cost
//! (seconds per stage, the process's peak resident memory).

use std::collections::BTreeMap;
use std::io;
use std::path::Path;

use serde::Serialize;

use crate::scene::desc::{ObjectDesc, SceneDesc, ShapeDesc};
use crate::scene::Content;

/// What a town frame holds and what it cost to build.
#[derive(Clone, Debug, Serialize)]
pub struct ContentReport {
    /// Town name.
    pub town: String,
    /// Town seed.
    pub seed: u64,
    /// Town frame (time step).
    pub frame: u64,
    /// Camera configuration.
    pub config: String,
    /// Top-level objects of the generated description.
    pub objects: usize,
    /// Top-level objects per semantic class; an object made of parts of
    /// several classes (a traffic light: pole and head) counts once in each.
    pub objects_per_class: BTreeMap<String, usize>,
    /// Flat meshes, prototypes, instances, unique and instanced triangles
    /// and spheres of the built scene.
    pub geometry: Content,
    /// Build time per stage, seconds.
    pub seconds: BuildSeconds,
    /// Peak resident memory of the process so far (bytes; None where the
    /// platform does not say).
    pub peak_rss_bytes: Option<u64>,
}

/// Seconds spent generating the description, building the scene and the
/// accelerator.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct BuildSeconds {
    /// Town generation (the scene description of the frame).
    pub generate: f64,
    /// Scene build (meshes, materials, lights).
    pub scene: f64,
    /// Accelerator build.
    pub accel: f64,
}

/// Counts top-level objects per semantic class (see [`ContentReport`]).
pub fn objects_per_class(desc: &SceneDesc) -> BTreeMap<String, usize> {
    let mut counts = BTreeMap::new();
    for object in &desc.objects {
        let mut classes = Vec::new();
        classes_of(desc, object, None, &mut classes, 0);
        classes.sort_unstable();
        classes.dedup();
        for class in classes {
            *counts.entry(class.to_string()).or_insert(0) += 1;
        }
    }
    counts
}

/// Prefabs nest at most this deep in generated towns; deeper chains (which
/// validation refuses as cycles) stop here.
const MAX_PREFAB_DEPTH: usize = 16;

fn classes_of<'a>(
    desc: &'a SceneDesc,
    object: &'a ObjectDesc,
    outer: Option<&'a str>,
    out: &mut Vec<&'a str>,
    depth: usize,
) {
    // The outermost override wins, as when the scene is built.
    let class = outer.or(object.semantic.as_deref());
    match &object.shape {
        ShapeDesc::Instance { prefab, .. } if depth < MAX_PREFAB_DEPTH => {
            let Some(p) = desc.prefabs.iter().find(|p| &p.name == prefab) else {
                return;
            };
            for child in &p.objects {
                classes_of(desc, child, class, out, depth + 1);
            }
        }
        _ => out.push(class.unwrap_or("unlabeled")),
    }
}

/// Peak resident memory of this process, bytes (Linux: `VmHWM`).
pub fn peak_rss_bytes() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

impl ContentReport {
    /// Writes the report as pretty JSON, whole or not at all (a temporary
    /// file renamed into place).
    pub fn write(&self, path: &Path) -> io::Result<()> {
        let json = serde_json::to_string_pretty(self).map_err(io::Error::other)?;
        let tmp = path.with_extension("json.partial");
        std::fs::write(&tmp, json + "\n")?;
        std::fs::rename(&tmp, path)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::parse_scene_str;

    #[test]
    fn objects_count_once_per_class_through_prefabs() {
        let toml = r#"
            [camera]
            position = [0.0, 0.0, 1.65]
            hfov_deg = 60.0

            [sky]
            kind = "constant"
            le = [1.0, 1.0, 1.0]

            [[material]]
            name = "m"
            kind = "diffuse"
            albedo = [0.5, 0.5, 0.5]

            [[prefab]]
            name = "lamp"
            [[prefab.object]]
            kind = "box"
            size = [0.1, 0.1, 3.0]
            material = "m"
            semantic = "pole"
            [[prefab.object]]
            kind = "box"
            size = [0.3, 0.3, 0.3]
            material = "m"
            semantic = "traffic_light"
            [[prefab.object]]
            kind = "box"
            size = [0.1, 0.1, 0.1]
            material = "m"
            semantic = "pole"

            [[object]]
            kind = "instance"
            prefab = "lamp"

            [[object]]
            kind = "instance"
            prefab = "lamp"
            semantic = "static"

            [[object]]
            kind = "box"
            size = [1.0, 1.0, 1.0]
            material = "m"
        "#;
        let desc = parse_scene_str(toml, Path::new("t.toml")).unwrap();
        let counts = objects_per_class(&desc.desc);
        let want: BTreeMap<String, usize> = [
            ("pole", 1),
            ("traffic_light", 1),
            ("static", 1),
            ("unlabeled", 1),
        ]
        .into_iter()
        .map(|(k, v)| (k.to_string(), v))
        .collect();
        assert_eq!(counts, want);
    }

    #[test]
    fn peak_rss_is_reported_on_linux() {
        let rss = peak_rss_bytes();
        if cfg!(target_os = "linux") {
            // A test process holds at least a megabyte.
            assert!(rss.unwrap() > 1 << 20, "{rss:?}");
        }
    }
}
