//! The town material library (linear RGB albedos, GGX conductors, glass)
//! and the sky and sun of a town. Palettes name the materials buildings and
//! vehicles draw from per instance. Static-world surfaces carry procedural
//! textures (albedo, roughness, relief; kinds in `scene::desc::material`):
//! asphalt, worn paint, paving, kerbs, brick bonds, plaster, stone,
//! concrete, glass, painted and brushed metal, wood, bark, grass and soil.

use crate::scene::desc::{
    ConductorPreset, LightDesc, MaterialDesc, MaterialKindDesc, SkyDesc, TextureDesc,
    TextureKindDesc,
};

use super::desc::{SkyKind, TerrainKind, TownDesc};

/// Wall materials buildings choose from.
pub const WALLS: &[&str] = &[
    "brick_red",
    "brick_brown",
    "brick_buff",
    "plaster_cream",
    "plaster_white",
    "plaster_blue",
    "plaster_ochre",
    "concrete",
    "stone",
];
/// Curtain-wall frame materials of towers.
pub const TOWER_FRAMES: &[&str] = &["concrete", "steel_dark", "plaster_white", "stone"];
/// Radiance of a street-lamp panel, W·m⁻²·sr⁻¹ (warm white, ~5000 cd/m²).
pub const LAMP_RADIANCE: [f64; 3] = [55.0, 50.0, 40.0];
/// Radiance of a lit signal lens (red, amber, green), W·m⁻²·sr⁻¹: each
/// ~6400 cd/m² (luminance Y = 0.2126 R + 0.7152 G + 0.0722 B ≈ 64 units),
/// i.e. EN 12368 class 2's 200 cd over a 200 mm lens, the same for every
/// colour as that standard asks.
pub const SIGNAL_RADIANCE: [[f64; 3]; 3] =
    [[280.0, 6.0, 4.0], [140.0, 48.0, 1.0], [2.0, 84.0, 47.0]];
/// Car paints vehicles choose from.
pub const PAINTS: &[&str] = &[
    "paint_red",
    "paint_blue",
    "paint_white",
    "paint_black",
    "paint_silver",
    "paint_grey",
    "paint_green",
    "paint_yellow",
    "paint_orange",
    "paint_darkblue",
];
/// How often each of `PAINTS` is drawn: like real traffic, mostly white,
/// black, grey and silver (~80 %), some blue and red, few others.
pub const PAINT_WEIGHTS: [f64; 10] = [0.07, 0.06, 0.34, 0.19, 0.1, 0.17, 0.015, 0.01, 0.01, 0.035];

/// The paint of `PAINTS` that a uniform `u` ∈ [0, 1) draws by `PAINT_WEIGHTS`.
pub fn draw_paint(u: f64) -> &'static str {
    let total: f64 = PAINT_WEIGHTS.iter().sum();
    let mut left = u * total;
    for (p, w) in PAINTS.iter().zip(PAINT_WEIGHTS) {
        if left < w {
            return p;
        }
        left -= w;
    }
    PAINTS[PAINTS.len() - 1]
}

/// A plain diffuse material (linear RGB albedo).
pub fn diffuse(name: &str, albedo: [f64; 3]) -> MaterialDesc {
    MaterialDesc {
        name: name.to_string(),
        mask: None,
        texture: None,
        kind: MaterialKindDesc::Diffuse { albedo },
    }
}

/// A diffuse material with a procedural texture of real-world feature size.
pub fn textured(name: &str, albedo: [f64; 3], kind: TextureKindDesc, seed: u32) -> MaterialDesc {
    with_texture(diffuse(name, albedo), kind, seed)
}

/// `m` with a procedural texture of real-world feature size.
pub fn with_texture(m: MaterialDesc, kind: TextureKindDesc, seed: u32) -> MaterialDesc {
    MaterialDesc {
        texture: Some(TextureDesc::new(kind, seed)),
        ..m
    }
}

/// A rough conductor of a preset metal.
pub fn metal(name: &str, preset: ConductorPreset, roughness: f64) -> MaterialDesc {
    MaterialDesc {
        name: name.to_string(),
        mask: None,
        texture: None,
        kind: MaterialKindDesc::Conductor {
            preset: Some(preset),
            eta: None,
            k: None,
            roughness,
        },
    }
}

/// Car paint: a glossy clear coat (η 1.5) over a coloured base, or over a
/// metal for metallic paints.
fn paint(name: &str, albedo: Option<[f64; 3]>, preset: Option<ConductorPreset>) -> MaterialDesc {
    MaterialDesc {
        name: name.to_string(),
        mask: None,
        texture: None,
        kind: MaterialKindDesc::Coated {
            albedo,
            preset,
            eta: None,
            k: None,
            base_roughness: 0.3,
            coat_ior: 1.5,
            coat_roughness: 0.05,
        },
    }
}

/// An always-on emitter radiating from every front face (W·m⁻²·sr⁻¹).
fn emitter(name: &str, radiance: [f64; 3]) -> MaterialDesc {
    MaterialDesc {
        name: name.to_string(),
        mask: None,
        texture: None,
        kind: MaterialKindDesc::Emissive {
            radiance,
            two_sided: false,
        },
    }
}

/// A signal lens when off: a smooth clear coat (η 1.5) over a dark tint.
fn lens(name: &str, albedo: [f64; 3]) -> MaterialDesc {
    MaterialDesc {
        kind: MaterialKindDesc::Coated {
            albedo: Some(albedo),
            preset: None,
            eta: None,
            k: None,
            base_roughness: 0.5,
            coat_ior: 1.5,
            coat_roughness: 0.02,
        },
        ..paint(name, None, None)
    }
}

fn glass(name: &str, tint: [f64; 3]) -> MaterialDesc {
    MaterialDesc {
        name: name.to_string(),
        mask: None,
        texture: None,
        kind: MaterialKindDesc::Dielectric {
            ior: 1.5,
            roughness: 0.0,
            tint,
        },
    }
}

/// Every material a town uses (names unique), group by group; the order
/// is the scene's material order.
pub fn town_materials(desc: &TownDesc) -> Vec<MaterialDesc> {
    [
        ground_materials(desc),
        building_materials(),
        super::facade::facade_materials(),
        vegetation_materials(),
        super::vegetation::materials(),
        pole_materials(),
        emitter_materials(),
        sign_materials(),
        vehicle_materials(),
        super::people::people_materials(),
        super::street::materials::street_materials(),
    ]
    .concat()
}

/// Roads, their markings, curbs and sidewalks, the river, and the ground
/// (its colour from the terrain kind), lawns and crops.
fn ground_materials(desc: &TownDesc) -> Vec<MaterialDesc> {
    let (ground, ground_kind) = match desc.terrain {
        TerrainKind::Grass => ([0.12, 0.2, 0.07], TextureKindDesc::Grass),
        TerrainKind::Dry => ([0.3, 0.27, 0.15], TextureKindDesc::Soil),
        TerrainKind::Field => ([0.22, 0.15, 0.09], TextureKindDesc::Soil),
    };
    vec![
        textured("asphalt", [0.08, 0.08, 0.085], TextureKindDesc::Asphalt, 1),
        textured(
            "asphalt_patch",
            [0.11, 0.11, 0.11],
            TextureKindDesc::Asphalt,
            2,
        ),
        textured(
            "paint_white_road",
            [0.78, 0.78, 0.74],
            TextureKindDesc::RoadPaint,
            22,
        ),
        textured(
            "paint_yellow_road",
            [0.75, 0.55, 0.1],
            TextureKindDesc::RoadPaint,
            23,
        ),
        textured("curb", [0.55, 0.54, 0.52], TextureKindDesc::Kerb, 3),
        textured("sidewalk", [0.42, 0.41, 0.39], TextureKindDesc::Paving, 4),
        textured("gravel", [0.3, 0.28, 0.25], TextureKindDesc::Soil, 5),
        textured("mud", [0.1, 0.085, 0.06], TextureKindDesc::Soil, 6),
        glass("water", [0.55, 0.7, 0.62]),
        textured("ground", ground, ground_kind, 7),
        textured("lawn", [0.1, 0.22, 0.06], TextureKindDesc::Grass, 8),
        textured("crop", [0.14, 0.24, 0.06], TextureKindDesc::Grass, 9),
    ]
}

/// Walls (the `WALLS` and `TOWER_FRAMES` palettes), roofs, windows, doors
/// and glass of buildings and barns.
fn building_materials() -> Vec<MaterialDesc> {
    vec![
        textured("barn_red", [0.38, 0.08, 0.05], TextureKindDesc::Wood, 24),
        textured("brick_red", [0.42, 0.17, 0.11], TextureKindDesc::Brick, 10),
        textured(
            "brick_brown",
            [0.3, 0.18, 0.12],
            TextureKindDesc::BrickFlemish,
            11,
        ),
        textured(
            "brick_buff",
            [0.55, 0.42, 0.28],
            TextureKindDesc::BrickEnglish,
            25,
        ),
        textured(
            "plaster_cream",
            [0.72, 0.66, 0.52],
            TextureKindDesc::Plaster,
            12,
        ),
        textured(
            "plaster_white",
            [0.78, 0.77, 0.74],
            TextureKindDesc::Plaster,
            13,
        ),
        textured(
            "plaster_blue",
            [0.42, 0.52, 0.62],
            TextureKindDesc::Plaster,
            14,
        ),
        textured(
            "plaster_ochre",
            [0.62, 0.45, 0.22],
            TextureKindDesc::Plaster,
            15,
        ),
        textured("concrete", [0.5, 0.5, 0.48], TextureKindDesc::Concrete, 16),
        textured("stone", [0.56, 0.52, 0.45], TextureKindDesc::Stone, 17),
        with_texture(
            metal("steel_dark", ConductorPreset::Iron, 0.5),
            TextureKindDesc::MetalBrushed,
            26,
        ),
        textured("roof", [0.2, 0.19, 0.19], TextureKindDesc::Concrete, 27),
        // Clay tiles: brick courses at twice the size (430 × 130 mm).
        MaterialDesc {
            texture: Some(TextureDesc {
                scale: 2.0,
                ..TextureDesc::new(TextureKindDesc::Brick, 28)
            }),
            ..diffuse("roof_tile", [0.38, 0.14, 0.08])
        },
        textured(
            "window_frame",
            [0.85, 0.85, 0.82],
            TextureKindDesc::MetalPainted,
            29,
        ),
        diffuse("interior", [0.04, 0.035, 0.03]),
        textured("door", [0.25, 0.14, 0.07], TextureKindDesc::Wood, 30),
        with_texture(
            glass("glass", [0.9, 0.95, 0.95]),
            TextureKindDesc::Glass,
            31,
        ),
        with_texture(
            glass("glass_tower", [0.55, 0.7, 0.75]),
            TextureKindDesc::Glass,
            32,
        ),
    ]
}

/// Bark and foliage of trees and bushes.
fn vegetation_materials() -> Vec<MaterialDesc> {
    vec![
        textured("bark", [0.22, 0.15, 0.09], TextureKindDesc::Bark, 18),
        textured("foliage", [0.09, 0.22, 0.05], TextureKindDesc::Foliage, 19),
        textured(
            "foliage_light",
            [0.16, 0.3, 0.07],
            TextureKindDesc::Foliage,
            20,
        ),
        textured(
            "foliage_dark",
            [0.05, 0.14, 0.04],
            TextureKindDesc::Foliage,
            21,
        ),
    ]
}

/// Poles and the street lamp's glass.
fn pole_materials() -> Vec<MaterialDesc> {
    vec![
        with_texture(
            metal("pole_metal", ConductorPreset::Aluminium, 0.45),
            TextureKindDesc::MetalBrushed,
            33,
        ),
        textured(
            "pole_paint",
            [0.12, 0.13, 0.12],
            TextureKindDesc::MetalPainted,
            34,
        ),
        diffuse("lamp_glass", [0.9, 0.9, 0.85]),
    ]
}

/// The always-on emitters: street lamps, vehicle lights and lit rooms.
fn emitter_materials() -> Vec<MaterialDesc> {
    vec![
        // Scene units: the sun's 980 W·m⁻² stands for ~100 klx, so one unit
        // of radiance is ~100 cd/m². Street lamps ~5000 cd/m² (0.15 m² of
        // panel gives ~15 lx on the road 8 m below), head-lights ~3·10⁴
        // cd/m², tail-lights ~10³ cd/m², lit rooms ~200 cd/m².
        emitter("lamp_emit", LAMP_RADIANCE),
        emitter("headlight_emit", [300.0, 300.0, 290.0]),
        emitter("taillight_emit", [12.0, 0.5, 0.3]),
        // Lit brake lamps ~5·10³ cd/m², blinking indicators ~4·10³.
        emitter("brake_lit", [50.0, 2.0, 1.2]),
        emitter("indicator_lit", [40.0, 16.0, 0.8]),
        emitter("window_lit", [2.5, 1.9, 1.1]),
    ]
}

/// Traffic-light housings and lenses (off and lit) and road signs.
fn sign_materials() -> Vec<MaterialDesc> {
    vec![
        textured(
            "signal_housing",
            [0.06, 0.06, 0.05],
            TextureKindDesc::MetalPainted,
            35,
        ),
        // Signal lenses: dark tinted glass when off (a clear coat over a
        // dark base), emitters when lit (`signals` picks one per head).
        lens("signal_red", [0.1, 0.015, 0.01]),
        lens("signal_amber", [0.1, 0.06, 0.01]),
        lens("signal_green", [0.01, 0.07, 0.04]),
        emitter("signal_red_lit", SIGNAL_RADIANCE[0]),
        emitter("signal_amber_lit", SIGNAL_RADIANCE[1]),
        emitter("signal_green_lit", SIGNAL_RADIANCE[2]),
        textured(
            "sign_red",
            [0.55, 0.03, 0.03],
            TextureKindDesc::MetalPainted,
            36,
        ),
        textured(
            "sign_white",
            [0.8, 0.8, 0.8],
            TextureKindDesc::MetalPainted,
            37,
        ),
        textured(
            "sign_blue",
            [0.04, 0.15, 0.5],
            TextureKindDesc::MetalPainted,
            38,
        ),
    ]
}

/// Car paints (the `PAINTS` palette), cargo boxes, tyres, hubs and trim.
pub fn vehicle_materials() -> Vec<MaterialDesc> {
    vec![
        paint("paint_red", Some([0.55, 0.04, 0.03]), None),
        paint("paint_blue", Some([0.05, 0.12, 0.45]), None),
        paint("paint_white", Some([0.8, 0.8, 0.78]), None),
        paint("paint_black", Some([0.03, 0.03, 0.035]), None),
        paint("paint_silver", None, Some(ConductorPreset::Aluminium)),
        paint("paint_grey", Some([0.3, 0.31, 0.32]), None),
        paint("paint_green", Some([0.08, 0.3, 0.12]), None),
        paint("paint_yellow", Some([0.75, 0.6, 0.08]), None),
        paint("paint_orange", Some([0.7, 0.25, 0.04]), None),
        paint("paint_darkblue", Some([0.02, 0.04, 0.15]), None),
        diffuse("cargo", [0.7, 0.7, 0.68]),
        diffuse("rubber", [0.03, 0.03, 0.03]),
        metal("chrome", ConductorPreset::Chrome, 0.05),
        diffuse("plastic_black", [0.05, 0.05, 0.05]),
        // Vehicle parts: tinted glass, trim, seams, cabin, rims, lenses
        // (amber and red when off), plates.
        glass("car_glass", [0.72, 0.78, 0.78]),
        diffuse("trim_black", [0.025, 0.025, 0.025]),
        diffuse("grille", [0.012, 0.012, 0.012]),
        diffuse("seam", [0.004, 0.004, 0.004]),
        diffuse("car_interior", [0.04, 0.038, 0.035]),
        metal("mirror", ConductorPreset::Silver, 0.0),
        metal("rim", ConductorPreset::Aluminium, 0.2),
        lens("lamp_amber", [0.35, 0.14, 0.01]),
        lens("indicator_left", [0.35, 0.14, 0.01]),
        lens("indicator_right", [0.35, 0.14, 0.01]),
        lens("lamp_red", [0.25, 0.01, 0.01]),
        diffuse("plate", [0.78, 0.78, 0.74]),
        diffuse("plate_ink", [0.02, 0.02, 0.02]),
        diffuse("frame_dark", [0.04, 0.04, 0.045]),
        metal("engine", ConductorPreset::Aluminium, 0.45),
        diffuse("seat_leather", [0.02, 0.018, 0.016]),
    ]
}

/// The town's gradient sky (W·m⁻²·sr⁻¹): a clear sky gives about a tenth of
/// the sun's irradiance as diffuse light.
pub fn town_sky(desc: &TownDesc) -> SkyDesc {
    match desc.sky {
        SkyKind::Clear => SkyDesc::Gradient {
            zenith: [9.0, 16.0, 38.0],
            horizon: [30.0, 33.0, 37.0],
            ground: [6.0, 5.6, 5.2],
        },
        SkyKind::Hazy => SkyDesc::Gradient {
            zenith: [20.0, 24.0, 32.0],
            horizon: [36.0, 37.0, 38.0],
            ground: [7.0, 6.8, 6.5],
        },
    }
}

/// The sun of the town.
pub fn town_sun(desc: &TownDesc) -> LightDesc {
    let irradiance = match desc.sky {
        SkyKind::Clear => [980.0, 930.0, 850.0],
        SkyKind::Hazy => [700.0, 680.0, 640.0],
    };
    LightDesc::Sun {
        elevation_deg: desc.sun_elevation_deg,
        azimuth_deg: desc.sun_azimuth_deg,
        irradiance,
        angular_diameter_deg: 0.533,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::town::props::LENS_SLOTS;

    #[test]
    fn static_surfaces_carry_their_texture_kind() {
        use TextureKindDesc as K;
        let desc = crate::town::source::load_named_town("town01", None)
            .unwrap()
            .desc;
        let all = town_materials(&desc);
        let kind = |n: &str| {
            let m = all.iter().find(|m| m.name == n).unwrap();
            m.texture.map(|t| t.kind)
        };
        let expect = [
            ("asphalt", K::Asphalt),
            ("paint_white_road", K::RoadPaint),
            ("paint_yellow_road", K::RoadPaint),
            ("sidewalk", K::Paving),
            ("curb", K::Kerb),
            ("brick_red", K::Brick),
            ("brick_brown", K::BrickFlemish),
            ("brick_buff", K::BrickEnglish),
            ("stone", K::Stone),
            ("plaster_white", K::Plaster),
            ("concrete", K::Concrete),
            ("glass", K::Glass),
            ("steel_dark", K::MetalBrushed),
            ("pole_metal", K::MetalBrushed),
            ("pole_paint", K::MetalPainted),
            ("door", K::Wood),
            ("bark", K::Bark),
            ("lawn", K::Grass),
            ("mud", K::Soil),
        ];
        for (name, k) in expect {
            assert_eq!(kind(name), Some(k), "{name}");
        }
        // Everything of the static world is textured but water and the
        // dark room interiors.
        let bare: Vec<String> = [
            ground_materials(&desc),
            building_materials(),
            vegetation_materials(),
        ]
        .concat()
        .into_iter()
        .filter(|m| m.texture.is_none())
        .map(|m| m.name)
        .collect();
        assert_eq!(bare, ["water", "interior"]);
    }

    #[test]
    fn names_are_unique_every_palette_and_prefab_material_is_defined_and_the_ground_follows_the_terrain(
    ) {
        let mut desc = crate::town::source::load_named_town("town01", None)
            .unwrap()
            .desc;
        let mut grounds = Vec::new();
        for terrain in [TerrainKind::Grass, TerrainKind::Dry, TerrainKind::Field] {
            desc.terrain = terrain;
            let all = town_materials(&desc);
            let names: Vec<&str> = all.iter().map(|m| m.name.as_str()).collect();
            let mut unique = names.clone();
            unique.sort_unstable();
            unique.dedup();
            assert_eq!(unique.len(), names.len(), "{names:?}");
            let lit: Vec<String> = LENS_SLOTS.iter().map(|s| format!("{s}_lit")).collect();
            let palettes = WALLS
                .iter()
                .chain(TOWER_FRAMES)
                .chain(PAINTS)
                .chain(&LENS_SLOTS);
            for name in palettes.copied().chain(lit.iter().map(String::as_str)) {
                assert!(names.contains(&name), "{name} missing");
            }
            // Every prefab part's material but the per-instance slots.
            let prefabs = crate::town::props::street_prefabs()
                .into_iter()
                .chain(crate::town::vehicles::vehicle_prefabs());
            for o in prefabs.flat_map(|p| p.objects) {
                let m = o.material.unwrap();
                let slot = ["car_paint", "shirt"].contains(&m.as_str());
                assert!(slot || names.contains(&m.as_str()), "{m} missing");
            }
            let ground = all.iter().find(|m| m.name == "ground").unwrap();
            grounds.push(ground.kind.clone());
        }
        assert!(grounds[0] != grounds[1] && grounds[1] != grounds[2] && grounds[0] != grounds[2]);
    }
}
