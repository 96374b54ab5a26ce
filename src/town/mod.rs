//! Procedural towns: a short parameter file (`TownDesc`) plus a seed become
//! a full scene description (`SceneDesc`) for any frame, so validation,
//! materials, building and semantic labels all reuse the scene machinery.
//!
//! Static geometry (roads, blocks, furniture) depends on (desc, seed) only;
//! moving objects come from `traffic::frame_at(desc, seed, frame)` in closed
//! form. World frame: z up, metres, the road grid starts at the origin. The
//! ego vehicle is part of the scene below its cameras (they sit above the
//! front edge of its roof, so the `normal` view does not see it). A graded
//! town (`road_grade_m`) is generated level, then laid onto its ground
//! field (`grade`, `drape`); vehicles take z, pitch and roll from it. An
//! organic town is generated as a grid, then bent by a planar warp
//! (`organic`) before the grade. An
//! overpass (`overpass`) adds its road, deck and traffic loop on top.
//!
//! Instance ids: buildings from 1000, every pole, tree, bush, sign and
//! traffic light from `FURNITURE_ID_BASE` (parked cars after them),
//! moving vehicles (ego included) from `VEHICLE_ID_BASE`, pedestrians from `PEDESTRIAN_ID_BASE`; roads,
//! markings, sidewalks and terrain carry 0.

pub mod buildings;
pub mod desc;
pub mod drape;
pub mod export;
pub mod facade;
pub mod farms;
pub mod furniture;
pub mod grade;
pub mod layout;
pub mod lettering;
pub mod materials;
pub mod organic;
pub mod outskirts;
pub mod overpass;
pub mod parking;
pub mod parts;
pub mod people;
pub mod props;
pub mod ramps;
pub mod report;
pub mod rig;
pub mod rng;
pub mod roads;
pub mod roundabout;
pub mod routes;
pub mod signals;
pub mod source;
mod stations;
pub mod street;
pub mod terrain;
pub mod traffic;
pub mod underpass;
pub mod vegetation;
pub mod vehicles;
pub mod walkers;

use std::path::Path;

pub use desc::{load_town, parse_town_str, TownDesc};
pub use rig::{rig_desc, CameraConfig, CONFIGS};
pub use source::{load_named_town, town_path, NamedTown, TownSource};
pub use traffic::{drive_frame_at, frame_at, TownFrame, VehiclePose};

use crate::scene::desc::{ObjectDesc, RenderDesc, SceneDesc};
use crate::scene::{LoadedScene, Scene, SceneError};

use layout::Layout;
use parts::{instance, Label};

/// First instance id of street furniture and vegetation objects.
pub const FURNITURE_ID_BASE: u32 = 10_000;
/// First instance id of vehicles (id = base + stable vehicle id).
pub const VEHICLE_ID_BASE: u32 = 30_000;
/// First instance id of pedestrians.
pub const PEDESTRIAN_ID_BASE: u32 = 55_000;

/// The static part of a town, generated once per frame: its layout, ramp
/// sites and hills, from which every static object is placed.
pub struct StaticTown<'a> {
    desc: &'a TownDesc,
    seed: u64,
    /// The road grid and blocks.
    pub layout: Layout,
    /// Highway slip-road sites (empty unless `ramps = true`).
    pub sites: Vec<ramps::RampSite>,
    /// The hills (`None` for a flat town).
    pub terrain: Option<terrain::Terrain>,
    /// The ground-elevation field (`None` for a level town).
    pub grade: Option<grade::Grade>,
    /// The overpass (`None` without one).
    pub overpass: Option<overpass::Overpass>,
    /// The organic warp (`None` unless `road_style = "organic"`).
    pub warp: Option<organic::Warp>,
}

impl<'a> StaticTown<'a> {
    /// Lays out the town of `desc` and `seed` (depends on nothing else).
    pub fn new(desc: &'a TownDesc, seed: u64) -> Self {
        let layout = Layout::new(desc);
        let sites = ramps::ramp_sites(desc, &layout);
        let terrain = terrain::Terrain::with_sites(desc, &layout, &sites, seed);
        let overpass = overpass::Overpass::new(desc, &layout);
        StaticTown {
            desc,
            seed,
            layout,
            sites,
            terrain,
            grade: grade::Grade::new(desc, seed),
            overpass,
            warp: organic::Warp::new(desc, seed),
        }
    }

    /// Roads, markings, sidewalks, buildings, vegetation, street
    /// furniture and parked cars, numbered (`number_objects`); not the
    /// generated meshes.
    pub fn objects(&self) -> Vec<ObjectDesc> {
        self.objects_and_bays().0
    }

    /// [`StaticTown::objects`] and the parking bays cut into its sidewalks.
    pub fn objects_and_bays(&self) -> (Vec<ObjectDesc>, Vec<parking::Bay>) {
        let (desc, seed, l) = (self.desc, self.seed, &self.layout);
        let mut out = roads::road_objects(l, &self.sites);
        let mut next_id = buildings::BUILDING_ID_BASE;
        out.extend(buildings::block_objects(desc, l, seed, &mut next_id));
        out.extend(outskirts::outskirt_objects(desc, l, seed, &mut next_id));
        let mut furniture = furniture::furniture_objects(desc, l, &self.sites, seed, &out);
        // Nothing stands on the roundabout's ring or sidewalk, nor in the
        // square of a curved loop corner (its arc and the cut-off corner).
        furniture.retain(|o| {
            let t = o.transform.translate.unwrap_or_default();
            !l.near_roundabout(&layout::Rect::centered([t[0], t[1]], [0.0, 0.0]))
                && !l.in_loop_corner([t[0], t[1]])
        });
        // Bays in the parking lanes, or lay-bys in the gaps the road-side
        // furniture leaves.
        let bays = parking::bays(desc, l, &furniture);
        if desc.parking_lane_m > 0.0 {
            out.extend(parking::lane::bay_marks(&bays));
        } else {
            parking::cut_laybys(&mut out, &bays);
        }
        out.extend(furniture);
        if let Some(t) = &self.terrain {
            out.extend(t.vegetation(desc.vegetation_density, seed));
        }
        if let Some(o) = &self.overpass {
            clear_for_overpass(o, &mut out);
        }
        number_objects(&mut out);
        // Parked cars: static, numbered after the furniture; placed after
        // the bend (as vehicles: at W(p), turned by W's Jacobian).
        let ids = (next_static_id(&out), VEHICLE_ID_BASE);
        let parked =
            parking::parked_cars(&bays, seed, desc.parking_density, ids, self.warp.as_ref());
        if let Some(w) = &self.warp {
            // Graded towns cut finer, for the grade's chord error.
            let step = match self.grade {
                Some(_) => drape::STEP_M,
                None => organic::bend::STEP_M,
            };
            out = organic::bend::bend_objects(out, w, step);
        }
        out.extend(parked);
        let out = match &self.grade {
            Some(g) => drape::drape_objects(out, g),
            None => out,
        };
        (out, bays)
    }

    /// The generated triangle meshes as inline mesh objects: the hills
    /// (`terrain::TERRAIN_NAME`), the ramp surfaces (`ramps::RAMP_MESHES`)
    /// and a divided highway's median barrier (`roads::median`).
    pub fn meshes(&self) -> Vec<ObjectDesc> {
        let mut out: Vec<ObjectDesc> = self.terrain.iter().map(|t| t.object()).collect();
        out.extend(ramps::ramp_meshes(&self.sites));
        out.extend(roads::median::median_meshes(&self.layout));
        if let Some(w) = &self.warp {
            organic::bend::bend_meshes(&mut out, w);
        }
        if let Some(g) = &self.grade {
            drape::drape_meshes(&mut out, g);
        }
        out.extend(self.overpass.iter().flat_map(overpass::overpass_meshes));
        out
    }
}

/// Removes every building with a part, and every other object standing,
/// in the overpass's clear zone (the highway's lights under the deck, lots
/// and trees on its approaches); roads, markings and ground stay.
fn clear_for_overpass(o: &overpass::Overpass, objects: &mut Vec<ObjectDesc>) {
    let zone = o.clear_zone();
    let inside = |ob: &ObjectDesc| {
        let t = ob.transform.translate.unwrap_or_default();
        zone.contains(&layout::Rect::centered([t[0], t[1]], [0.0, 0.0]), 0.0)
    };
    let flat = |ob: &ObjectDesc| {
        matches!(
            ob.semantic.as_deref(),
            Some("road" | "road_line" | "terrain" | "sidewalk")
        )
    };
    let buildings: std::collections::BTreeSet<u16> = objects
        .iter()
        .filter(|ob| ob.semantic.as_deref() == Some("building") && inside(ob))
        .filter_map(|ob| ob.instance)
        .collect();
    objects.retain(|ob| {
        let gone = ob.instance.is_some_and(|i| buildings.contains(&i));
        !gone && (flat(ob) || !inside(ob))
    });
}

/// Objects that do not move, without the generated meshes (`StaticTown`).
pub fn static_objects(desc: &TownDesc, seed: u64) -> Vec<ObjectDesc> {
    StaticTown::new(desc, seed).objects()
}

/// Gives every pole, tree, bush, sign, traffic light, fixture, fence and
/// guard rail its own instance
/// id, in generation order (deterministic), from `FURNITURE_ID_BASE`.
fn number_objects(objects: &mut [ObjectDesc]) {
    let mut next = FURNITURE_ID_BASE;
    for o in objects.iter_mut() {
        let numbered = matches!(
            o.semantic.as_deref(),
            Some(
                "pole"
                    | "vegetation"
                    | "traffic_sign"
                    | "traffic_light"
                    | "static"
                    | "fence"
                    | "guard_rail"
            )
        );
        if numbered && o.instance.is_none() && next < VEHICLE_ID_BASE {
            o.instance = Some(next as u16);
            next += 1;
        }
    }
}

/// The first instance id above every furniture id in `objects`.
fn next_static_id(objects: &[ObjectDesc]) -> u32 {
    objects
        .iter()
        .filter_map(|o| o.instance.map(u32::from))
        .filter(|&i| (FURNITURE_ID_BASE..VEHICLE_ID_BASE).contains(&i))
        .max()
        .map_or(FURNITURE_ID_BASE, |i| i + 1)
}

/// Seated people per two-wheeler body type.
const RIDER_VARIANTS: u32 = 4;

/// Prefab name of rider `variant` of two-wheeler `body`.
fn rider_prefab_name(body: vehicles::BodyKind, variant: u32) -> String {
    format!("{}_rider{variant}", body.prefab())
}

/// The riders of every two-wheeler body type (`BodyKind::seat`), generated
/// once per process.
fn rider_prefabs() -> Vec<crate::scene::desc::PrefabDesc> {
    static PREFABS: std::sync::OnceLock<Vec<crate::scene::desc::PrefabDesc>> =
        std::sync::OnceLock::new();
    PREFABS.get_or_init(generate_riders).clone()
}

fn generate_riders() -> Vec<crate::scene::desc::PrefabDesc> {
    vehicles::BODIES
        .iter()
        .filter_map(|&b| b.seat().map(|seat| (b, seat)))
        .flat_map(|(b, seat)| {
            (0..RIDER_VARIANTS)
                .map(move |k| people::rider::rider_prefab(&rider_prefab_name(b, k), seat, k))
        })
        .collect()
}

/// The vehicles (ego included) and pedestrians of one frame as instances.
pub fn dynamic_objects(frame: &TownFrame) -> Vec<ObjectDesc> {
    let mut out = Vec::with_capacity(frame.vehicles.len() + frame.pedestrians.len() + 1);
    for v in std::iter::once(&frame.ego).chain(&frame.vehicles) {
        let l = Label {
            class: v.body.class(),
            instance: (VEHICLE_ID_BASE + v.id).min(PEDESTRIAN_ID_BASE - 1) as u16,
        };
        let map = [("car_paint", v.paint)];
        let mut o = instance(v.body.prefab(), v.position, v.heading_deg, &map, l);
        if v.pitch_deg != 0.0 || v.roll_deg != 0.0 {
            let r = grade::body_rotation_deg(v.heading_deg, v.pitch_deg, v.roll_deg);
            o.transform.rotate_deg = Some(r);
        }
        // The unpainted parts and a registration share the body's pose:
        // one prototype per model for them, one per (model, paint) above.
        let plate = v.body.plate_prefab(v.id % vehicles::plates::PLATE_VARIANTS);
        let shared = o.clone();
        out.push(o);
        for name in [v.body.parts_prefab(), v.body.lamps_prefab()]
            .into_iter()
            .chain(plate)
        {
            let mut p = shared.clone();
            let map = if name == v.body.lamps_prefab() {
                lit_lamps(v)
            } else {
                Vec::new()
            };
            p.shape = parts::instance(&name, v.position, 0.0, &map, l).shape;
            out.push(p);
        }
        // A two-wheeler carries its rider (class `rider`, the vehicle's
        // instance id), posed on the seat in the vehicle's frame.
        if v.body.seat().is_some() {
            let mut p = shared.clone();
            let name = rider_prefab_name(v.body, v.id % RIDER_VARIANTS);
            p.shape = parts::instance(&name, v.position, 0.0, &[], l).shape;
            p.semantic = Some("rider".to_string());
            out.push(p);
        }
    }
    for p in &frame.pedestrians {
        let l = Label {
            class: "pedestrian",
            instance: (PEDESTRIAN_ID_BASE + p.id).min(u16::MAX as u32) as u16,
        };
        let prefab = people::prefab_name(p.variant, p.phase.map(people::phase_index));
        out.push(instance(&prefab, p.position, p.heading_deg, &[], l));
    }
    out
}

/// The material map of a four-wheeled vehicle's lamps prefab for its lit
/// lamps: the brake lens and tail lamps to the brake emitter while
/// braking, each lit indicator's lenses to the indicator emitter. (The
/// lamps prefab is flat and small: mapping it adds no prototype.)
/// Two-wheelers' lamps stay as they are.
fn lit_lamps(v: &VehiclePose) -> Vec<(&'static str, &'static str)> {
    use vehicles::lamps::{BRAKE_SLOT, INDICATOR_SLOTS};
    let mut map = Vec::new();
    if v.body.seat().is_some() {
        return map;
    }
    if v.lamps.brake {
        map.extend([(BRAKE_SLOT, "brake_lit"), ("taillight_emit", "brake_lit")]);
    }
    for (lit, slot) in [v.lamps.left, v.lamps.right]
        .into_iter()
        .zip(INDICATOR_SLOTS)
    {
        if lit {
            map.push((slot, "indicator_lit"));
        }
    }
    map
}

/// What a town frame holds that does not depend on the frame: the static
/// objects (`StaticTown::objects`), the generated meshes and the layout (the
/// signals' sites), generated once per (description, seed) and shared by
/// every frame (`town_scene_with`).
#[derive(Clone, Debug)]
pub struct StaticScene {
    /// Roads, buildings, vegetation and furniture (lamps unlit).
    pub objects: Vec<ObjectDesc>,
    /// The generated meshes (hills, ramps, overpass).
    pub meshes: Vec<ObjectDesc>,
    /// The road grid and blocks.
    pub layout: Layout,
}

impl StaticScene {
    /// Generates the static part of the town of `desc` and `seed`.
    pub fn new(desc: &TownDesc, seed: u64) -> StaticScene {
        let town = StaticTown::new(desc, seed);
        StaticScene {
            objects: town.objects(),
            meshes: town.meshes(),
            layout: town.layout,
        }
    }
}

/// The resolved scene description of one town frame (of drive 0) seen
/// from `config`, generated meshes included.
pub fn town_scene(desc: &TownDesc, seed: u64, frame: u64, config: CameraConfig) -> SceneDesc {
    town_drive_scene(desc, seed, 0, frame, config)
}

/// `town_scene` of frame `frame` of drive `drive` (`drive_frame_at`).
pub fn town_drive_scene(
    desc: &TownDesc,
    seed: u64,
    drive: u64,
    frame: u64,
    config: CameraConfig,
) -> SceneDesc {
    town_scene_with(
        &StaticScene::new(desc, seed),
        desc,
        seed,
        (drive, frame),
        config,
    )
}

/// [`town_scene`] over the static part already generated (`stat` must be
/// `StaticScene::new(desc, seed)`): adds the frame's moving objects and lamp
/// states (the same description, object for object).
pub fn town_scene_with(
    stat: &StaticScene,
    desc: &TownDesc,
    seed: u64,
    (drive, frame): (u64, u64),
    config: CameraConfig,
) -> SceneDesc {
    let tf = drive_frame_at(desc, seed, drive, frame);
    let mut objects = Vec::with_capacity(stat.objects.len() + stat.meshes.len() + 64);
    objects.extend_from_slice(&stat.objects);
    objects.extend(dynamic_objects(&tf));
    // The lamps follow the drive's traffic clock.
    signals::set_lamps(desc, &stat.layout, tf.frame, &mut objects);
    // Meshes last, after the moving objects: keeps geometry ids and
    // `geometry_hash` values as they were.
    objects.extend_from_slice(&stat.meshes);
    let mut prefabs = props::street_prefabs();
    prefabs.extend(people::people_prefabs());
    prefabs.extend(vehicles::vehicle_prefabs());
    prefabs.extend(rider_prefabs());
    prefabs.extend(vegetation::vegetation_prefabs());
    SceneDesc {
        camera: rig_desc(config, &tf.ego),
        render: RenderDesc {
            spp: 16,
            max_depth: 5,
            seed: Some(seed),
            ..RenderDesc::default()
        },
        sky: Some(materials::town_sky(desc)),
        medium: None,
        rain: None,
        wetness: None,
        lights: vec![materials::town_sun(desc)],
        materials: materials::town_materials(desc),
        objects,
        prefabs,
    }
}

/// The town frame (of drive 0) as a validated scene, named `town_file` in
/// messages.
pub fn load_town_frame(
    desc: &TownDesc,
    seed: u64,
    frame: u64,
    config: CameraConfig,
    town_file: &Path,
) -> Result<LoadedScene, SceneError> {
    load_town_drive_frame(desc, seed, 0, frame, config, town_file)
}

/// `load_town_frame` of frame `frame` of drive `drive`.
pub fn load_town_drive_frame(
    desc: &TownDesc,
    seed: u64,
    drive: u64,
    frame: u64,
    config: CameraConfig,
    town_file: &Path,
) -> Result<LoadedScene, SceneError> {
    load_town_frame_with(
        &StaticScene::new(desc, seed),
        desc,
        seed,
        (drive, frame),
        config,
        town_file,
    )
}

/// [`load_town_frame`] over the static part already generated (see
/// [`town_scene_with`]).
pub fn load_town_frame_with(
    stat: &StaticScene,
    desc: &TownDesc,
    seed: u64,
    (drive, frame): (u64, u64),
    config: CameraConfig,
    town_file: &Path,
) -> Result<LoadedScene, SceneError> {
    let scene = town_scene_with(stat, desc, seed, (drive, frame), config);
    let (objs, triangle_estimate) = crate::scene::validate::validate(&scene, town_file)?;
    // The static objects come first, the generated meshes last (see
    // `town_scene_with`); the frame's moving objects lie between.
    let n = scene.objects.len();
    let static_objects = vec![0..stat.objects.len(), n - stat.meshes.len()..n];
    Ok(LoadedScene {
        path: town_file.to_path_buf(),
        desc: scene,
        objs,
        triangle_estimate,
        static_objects,
    })
}

/// A hash of a built scene's geometry: every f64 position (world), triangle,
/// semantic class and instance id, in order (FNV-1a over the bits).
pub fn geometry_hash(scene: &Scene) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    let mut eat = |x: u64| {
        for b in x.to_le_bytes() {
            h = (h ^ b as u64).wrapping_mul(0x100_0000_01b3);
        }
    };
    for m in scene.flattened_meshes() {
        eat(m.semantic as u64 | (m.instance as u64) << 8);
        for p in &m.p_render {
            let w = *p + scene.origin_world;
            eat(w.x.to_bits());
            eat(w.y.to_bits());
            eat(w.z.to_bits());
        }
        for t in &m.triangles {
            eat(t[0] as u64 | (t[1] as u64) << 21 | (t[2] as u64) << 42);
        }
    }
    h
}
