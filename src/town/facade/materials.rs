//! The façade materials, named by what they are (brick, plaster, stone,
//! concrete, glass, painted metal, wood, cloth) with a `facade_` prefix;
//! walls, glass, metal and wood carry the texture kind of what they are
//! (albedo, roughness and relief); rooms, signs and awnings are plain.
//! Linear RGB albedos.

use crate::scene::desc::{ConductorPreset, MaterialDesc, MaterialKindDesc, TextureKindDesc};
use crate::town::materials::{diffuse, textured, with_texture};

/// Every façade material (names unique, all prefixed `facade_`).
pub fn facade_materials() -> Vec<MaterialDesc> {
    use TextureKindDesc::{
        BrickFlemish, Concrete, Glass, MetalBrushed, MetalPainted, Plaster, Stone, Wood,
    };
    vec![
        // Walls.
        textured("facade_brick_yellow", [0.55, 0.45, 0.28], BrickFlemish, 201),
        textured("facade_plaster_pink", [0.7, 0.5, 0.45], Plaster, 202),
        textured("facade_sandstone", [0.62, 0.52, 0.36], Stone, 203),
        textured("facade_concrete_dark", [0.3, 0.3, 0.29], Concrete, 204),
        textured("facade_cladding", [0.32, 0.38, 0.42], MetalPainted, 206),
        textured("facade_wood_siding", [0.62, 0.6, 0.52], Wood, 207),
        textured("facade_step", [0.5, 0.49, 0.46], Concrete, 205),
        // Glass: clear, slightly green at the edges of thick panes.
        with_texture(
            MaterialDesc {
                kind: MaterialKindDesc::Dielectric {
                    ior: 1.5,
                    roughness: 0.0,
                    tint: [0.92, 0.96, 0.95],
                },
                ..diffuse("facade_glass", [0.0; 3])
            },
            Glass,
            208,
        ),
        // Painted and bare metal, wood.
        textured("facade_metal_dark", [0.07, 0.075, 0.08], MetalPainted, 209),
        with_texture(
            MaterialDesc {
                kind: MaterialKindDesc::Conductor {
                    preset: Some(ConductorPreset::Aluminium),
                    eta: None,
                    k: None,
                    roughness: 0.55,
                },
                ..diffuse("facade_metal_grey", [0.0; 3])
            },
            MetalBrushed,
            210,
        ),
        textured("facade_railing", [0.04, 0.04, 0.045], MetalPainted, 211),
        textured("facade_pipe", [0.15, 0.15, 0.15], MetalPainted, 212),
        textured("facade_wood", [0.3, 0.18, 0.09], Wood, 213),
        // Rooms behind the glass.
        diffuse("facade_room_wall", [0.6, 0.56, 0.48]),
        diffuse("facade_room_floor", [0.25, 0.16, 0.09]),
        diffuse("facade_room_ceiling", [0.75, 0.75, 0.72]),
        diffuse("facade_lamp_off", [0.8, 0.8, 0.78]),
        diffuse("facade_curtain_cream", [0.7, 0.62, 0.48]),
        diffuse("facade_curtain_red", [0.4, 0.06, 0.05]),
        diffuse("facade_blind", [0.78, 0.78, 0.75]),
        diffuse("facade_sofa", [0.12, 0.16, 0.3]),
        // Shop signs and awnings.
        diffuse("facade_letter", [0.8, 0.68, 0.35]),
        diffuse("facade_sign_green", [0.03, 0.16, 0.08]),
        diffuse("facade_sign_red", [0.3, 0.03, 0.03]),
        diffuse("facade_sign_navy", [0.02, 0.04, 0.16]),
        diffuse("facade_awning_red", [0.5, 0.05, 0.04]),
        diffuse("facade_awning_green", [0.05, 0.25, 0.1]),
        diffuse("facade_awning_blue", [0.05, 0.12, 0.4]),
        diffuse("facade_awning_ochre", [0.6, 0.4, 0.08]),
        diffuse("facade_awning_white", [0.8, 0.79, 0.75]),
    ]
}
