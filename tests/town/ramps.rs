//! Highway ramps (`ramps = true`): present in town06 only; the ramp surface
//! joins the highway edge without gaps (rays straight down through taper,
//! gore and ramp hit road or paint at z = 0); ramp sites keep clear of lots,
//! and no vertex of a built building, pole, tree, bush, sign or traffic
//! light lies in a ramp's clear zone; hills stay flat under them; a bad
//! `ramps` key is rejected naming it.

use std::path::Path;

use glam::DVec3;
use parallax::accel::{Accel, Backend, Ray};
use parallax::render::recipe::BuiltScene;
use parallax::scene::build_scene;
use parallax::scene::desc::ShapeDesc;
use parallax::scene::semantic::class_id;
use parallax::town::layout::{Layout, Rect};
use parallax::town::ramps::{ramp_sites, RAMP_MESHES, TAPER_M};
use parallax::town::terrain::Terrain;
use parallax::town::town_scene;
use parallax::town::{load_town_frame, parse_town_str, static_objects, CameraConfig};

use crate::common;
use common::towns::{town, town_file, TOWNS};

#[test]
fn ramps_are_built_in_town06_and_nowhere_else() {
    for name in TOWNS {
        let desc = town(name);
        let sites = ramp_sites(&desc, &Layout::new(&desc));
        if name == "town06" {
            // Five blocks along both outer highways.
            assert_eq!(sites.len(), 10, "{name}");
        } else {
            assert!(sites.is_empty(), "{name} has ramps");
        }
    }
    let desc = town("town06");
    let loaded = load_town_frame(&desc, 3, 0, CameraConfig::Normal, Path::new("t.toml")).unwrap();
    for (name, _, class) in RAMP_MESHES {
        let object = loaded
            .desc
            .objects
            .iter()
            .find(|o| o.name.as_deref() == Some(name))
            .unwrap_or_else(|| panic!("no {name}"));
        let ShapeDesc::Mesh { triangles, .. } = &object.shape else {
            panic!("{name} is not an inline mesh")
        };
        assert!(triangles.len() > 1000, "{name}");
        assert_eq!(object.semantic.as_deref(), Some(class));
    }
    // Loading validates the generated description without altering it
    // (generation is deterministic: this only guards that).
    let plain = town_scene(&desc, 3, 0, CameraConfig::Normal);
    assert_eq!(plain, loaded.desc);
    // One changed parameter changes the scene: town06 without ramps (and
    // the overpass that needs them) has none of the ramp meshes, and town06
    // still has them afterwards.
    let text = std::fs::read_to_string(town_file("town06")).unwrap();
    let off = text
        .replace("ramps = true", "ramps = false")
        .replace("overpass = true", "");
    let off = parse_town_str(&off, Path::new("t.toml")).unwrap();
    let plain_off = town_scene(&off, 3, 0, CameraConfig::Normal);
    for (name, _, _) in RAMP_MESHES {
        assert!(
            !plain_off
                .objects
                .iter()
                .any(|o| o.name.as_deref() == Some(name)),
            "{name} without ramps"
        );
    }
    assert_eq!(town_scene(&desc, 3, 0, CameraConfig::Normal), plain);
}

#[test]
fn ramp_surface_joins_the_highway_edge_without_gaps() {
    let desc = town("town06");
    let l = Layout::new(&desc);
    let loaded = load_town_frame(&desc, 3, 0, CameraConfig::Normal, Path::new("t.toml")).unwrap();
    let BuiltScene { scene, accel, .. } =
        BuiltScene::build(&loaded, DVec3::ZERO, Backend::default_backend()).unwrap();
    let (road, paint) = (class_id("road").unwrap(), class_id("road_line").unwrap());
    let mut checked = 0;
    for s in ramp_sites(&desc, &l) {
        let len = s.len_m();
        // Stations through taper, gore and curve at both ends, and mid-ramp.
        let mut ts: Vec<f64> = (1..90).map(|k| k as f64 * 1.13).collect();
        ts.extend((1..90).map(|k| len - k as f64 * 1.13));
        ts.push(len / 2.0);
        for t in ts {
            let inner = s.edge(t, false, 0.0);
            let outer = s.edge(t, true, 0.0);
            // Across the seam with the highway (o just inside its edge) to
            // just inside the ramp's outer edge; in the gore (inner edge
            // off the highway but within the nose) the pavement is continuous.
            let tm = t.min(len - t);
            let gore = tm >= TAPER_M && tm <= s.nose_m;
            let mut os = vec![s.hw - 0.3, s.hw - 1e-3];
            if tm < TAPER_M || gore {
                os.push(s.hw + 1e-3);
                let top = if tm < TAPER_M { outer[1] } else { inner[1] };
                os.extend((1..8).map(|k| s.hw + (top - s.hw) * k as f64 / 8.0));
            }
            let mut pts: Vec<[f64; 2]> = os.into_iter().map(|o| [t, o]).collect();
            if tm >= TAPER_M {
                for f in [0.02, 0.3, 0.5, 0.7, 0.98] {
                    pts.push([
                        inner[0] + (outer[0] - inner[0]) * f,
                        inner[1] + (outer[1] - inner[1]) * f,
                    ]);
                }
            }
            for p in pts {
                let w = s.world(p);
                let hit = accel
                    .intersect(&Ray::new(
                        // From 3 m: under town06's overpass deck (5.1 m).
                        glam::Vec3::new(w[0] as f32, w[1] as f32, 3.0),
                        glam::Vec3::NEG_Z,
                    ))
                    .unwrap_or_else(|| panic!("nothing below {w:?}"));
                let c = scene.hit_labels(&hit).0;
                let z = 3.0 - hit.t as f64;
                assert!(
                    c == road || c == paint,
                    "class {c} at {w:?} (t {t}, o {})",
                    p[1]
                );
                assert!((-1e-4..0.0085).contains(&z), "z {z} at {w:?}");
                checked += 1;
            }
        }
    }
    assert!(checked > 5000, "{checked}");
}

#[test]
fn ramps_keep_clear_of_lots_buildings_and_furniture() {
    let desc = town("town06");
    let l = Layout::new(&desc);
    let zones: Vec<_> = ramp_sites(&desc, &l)
        .iter()
        .map(|s| s.clear_zone())
        .collect();
    for z in &zones {
        for i in 0..l.nx {
            for j in 0..l.ny {
                assert!(!z.overlaps(&l.block_interior(i, j)), "lot ({i}, {j})");
            }
        }
        // The zone holds the highway's outer shoulder and nothing of its lanes.
        assert!(!l.road_rects().iter().any(|r| r.overlaps(z)));
    }
    for seed in [0, 7] {
        let objects = static_objects(&desc, seed);
        let mut standing = 0;
        for o in &objects {
            let class = o.semantic.as_deref().unwrap_or("");
            if !matches!(
                class,
                "building" | "pole" | "vegetation" | "traffic_sign" | "traffic_light"
            ) {
                continue;
            }
            standing += 1;
            let t = o.transform.translate.unwrap_or_default();
            for z in &zones {
                let inside =
                    (z.min[0]..=z.max[0]).contains(&t[0]) && (z.min[1]..=z.max[1]).contains(&t[1]);
                assert!(!inside, "{class} at {t:?} on a ramp (seed {seed})");
            }
        }
        assert!(standing > 100, "{standing}");
    }
    // The built frame, every vertex of every building, pole, tree, bush,
    // sign and traffic light (repeat copies and whole footprints included,
    // wherever the object's anchor is):
    // - nothing stands in a clear zone: no vertex within 0.5 m of the
    //   (level) ground lies strictly inside one;
    // - nothing reaches over the site itself (the zone without its 3 m
    //   margin beyond the site's ends and outer shoulder): no triangle
    //   overlaps it in plan view at any height. Tree crowns may overhang
    //   the margin (seed 7: a crown 1.1 m into it).
    // The overpass structure (walls, pier line) spans the slip road by
    // design and is left out.
    let mut loaded =
        load_town_frame(&desc, 7, 0, CameraConfig::Normal, Path::new("t.toml")).unwrap();
    let n = loaded.desc.objects.len();
    loaded
        .desc
        .objects
        .retain(|o| o.name.as_deref() != Some("overpass_structure"));
    assert_eq!(loaded.desc.objects.len(), n - 1, "one overpass structure");
    let scene = build_scene(&loaded, DVec3::ZERO).unwrap();
    let standing: Vec<u8> = [
        "building",
        "pole",
        "vegetation",
        "traffic_sign",
        "traffic_light",
    ]
    .iter()
    .map(|c| class_id(c).unwrap())
    .collect();
    let sites: Vec<(Rect, Rect)> = ramp_sites(&desc, &l)
        .iter()
        .map(|s| {
            let z = s.clear_zone();
            let mut site = Rect {
                min: [z.min[0] + 3.0, z.min[1]],
                max: [z.max[0] - 3.0, z.max[1]],
            };
            // The outer shoulder's side carries the margin.
            if s.side > 0.0 {
                site.max[1] -= 3.0;
            } else {
                site.min[1] += 3.0;
            }
            (z, site)
        })
        .collect();
    let eps = 1e-6;
    let inside = |z: &Rect, p: DVec3| {
        p.x > z.min[0] + eps && p.x < z.max[0] - eps && p.y > z.min[1] + eps && p.y < z.max[1] - eps
    };
    let (mut low, mut near, mut triangles) = (0usize, 0usize, 0usize);
    for m in scene
        .flattened_meshes()
        .filter(|m| standing.contains(&m.semantic))
    {
        let world: Vec<DVec3> = m.p_render.iter().map(|&p| p + scene.origin_world).collect();
        for &p in world.iter().filter(|p| p.z < 0.5) {
            low += 1;
            for (z, _) in &sites {
                assert!(
                    !inside(z, p),
                    "class {} instance {}: ground vertex {p} in a ramp zone {z:?}",
                    m.semantic,
                    m.instance
                );
                // Within 50 m of a zone: the check sees the sites' surroundings.
                let dx = (z.min[0] - p.x).max(p.x - z.max[0]).max(0.0);
                let dy = (z.min[1] - p.y).max(p.y - z.max[1]).max(0.0);
                near += usize::from(dx.hypot(dy) < 50.0);
            }
        }
        // Plan-view overlap of each triangle with each site (separating
        // axes: the site's two axes, then the triangle's edge normals; a
        // vertical face's plan view is a segment, its normal still separates).
        for t in &m.triangles {
            let q = t.map(|i| world[i as usize]);
            triangles += 1;
            for (_, z) in &sites {
                let lo = |a: f64, b: f64, c: f64| a.min(b).min(c);
                let hi = |a: f64, b: f64, c: f64| a.max(b).max(c);
                if hi(q[0].x, q[1].x, q[2].x) <= z.min[0] + eps
                    || lo(q[0].x, q[1].x, q[2].x) >= z.max[0] - eps
                    || hi(q[0].y, q[1].y, q[2].y) <= z.min[1] + eps
                    || lo(q[0].y, q[1].y, q[2].y) >= z.max[1] - eps
                {
                    continue;
                }
                let corners = [
                    [z.min[0] + eps, z.min[1] + eps],
                    [z.max[0] - eps, z.min[1] + eps],
                    [z.max[0] - eps, z.max[1] - eps],
                    [z.min[0] + eps, z.max[1] - eps],
                ];
                let separated = (0..3).any(|e| {
                    let (a, b) = (q[e], q[(e + 1) % 3]);
                    let n = [b.y - a.y, a.x - b.x];
                    if n == [0.0, 0.0] {
                        return false;
                    }
                    let proj = |x: f64, y: f64| x * n[0] + y * n[1];
                    let tri = q.map(|p| proj(p.x, p.y));
                    let rect = corners.map(|k| proj(k[0], k[1]));
                    let r0 = rect.iter().copied().fold(f64::INFINITY, f64::min);
                    let r1 = rect.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                    hi(tri[0], tri[1], tri[2]) <= r0 || r1 <= lo(tri[0], tri[1], tri[2])
                });
                assert!(
                    separated,
                    "class {} instance {}: triangle {q:?} over a ramp site {z:?}",
                    m.semantic, m.instance
                );
            }
        }
    }
    assert!(low > 10_000 && triangles > 10_000, "{low} {triangles}");
    assert!(near > 100, "only {near} ground vertices near the ramps");
}

#[test]
fn hills_stay_flat_under_the_ramps() {
    let text = std::fs::read_to_string(town_file("town06")).unwrap();
    let hilly = format!("{text}hills_m = 60.0\nhill_wavelength_m = 120.0\n");
    let desc = parse_town_str(&hilly, Path::new("hilly.toml")).unwrap();
    let l = Layout::new(&desc);
    let t = Terrain::new(&desc, &l, 5).unwrap();
    let mut highest: f64 = 0.0;
    for s in ramp_sites(&desc, &l) {
        let z = s.clear_zone();
        for i in 0..=40 {
            for j in 0..=10 {
                let x = z.min[0] + (z.max[0] - z.min[0]) * i as f64 / 40.0;
                let y = z.min[1] + (z.max[1] - z.min[1]) * j as f64 / 10.0;
                assert_eq!(t.height_m(x, y), 0.0, "hill at ({x}, {y})");
            }
        }
        // Hills do rise beyond the ramps.
        let far = s.y_road_m + s.side * 150.0;
        highest = highest.max(t.height_m((s.a0 + s.a1) / 2.0, far));
    }
    assert!(highest > 1.0, "{highest}");
}

#[test]
fn bad_ramps_key_is_rejected_naming_it() {
    let p = Path::new("bad.toml");
    // town05's blocks are too short for a ramp site.
    let short = format!(
        "{}ramps = true\n",
        std::fs::read_to_string(town_file("town05")).unwrap()
    );
    let e = parse_town_str(&short, p).unwrap_err();
    assert!(e.contains("ramps") && e.contains("block_size_m"), "{e}");
    let text = std::fs::read_to_string(town_file("town06")).unwrap();
    let typed = text.replace("ramps = true", "ramps = 3");
    let e = parse_town_str(&typed, p).unwrap_err();
    assert!(e.contains("ramps"), "{e}");
    // The overpass needs the ramps (it spans the slip road): off with them.
    let off = text
        .replace("ramps = true", "ramps = false")
        .replace("overpass = true", "");
    let desc = parse_town_str(&off, p).unwrap();
    assert!(ramp_sites(&desc, &Layout::new(&desc)).is_empty());
}
