//! Materials of the street furniture (linear RGB albedos, GGX metals,
//! glass), by name, with the texture kind of what they are (brushed and
//! painted metal, wood, concrete, glass; sign faces and inks stay plain so
//! the print reads): painted and galvanised metal, sign faces and inks,
//! wood, concrete, shelter glass and billboard prints. The signal lenses
//! and the lamp emitter (`lamp_emit`) stay in `town::materials`, which
//! lists these with one line.

use crate::scene::desc::{ConductorPreset, MaterialDesc, MaterialKindDesc, TextureKindDesc};
use crate::town::materials::{diffuse, metal, with_texture};

fn named(name: &str, kind: MaterialKindDesc) -> MaterialDesc {
    MaterialDesc {
        kind,
        ..diffuse(name, [0.0; 3])
    }
}

/// Every street-furniture material (names unique, all prefixed `street_`
/// or `sign_`).
pub fn street_materials() -> Vec<MaterialDesc> {
    vec![
        with_texture(
            metal("street_galvanised", ConductorPreset::Aluminium, 0.55),
            TextureKindDesc::MetalBrushed,
            301,
        ),
        with_texture(
            metal("street_steel_dark", ConductorPreset::Iron, 0.45),
            TextureKindDesc::MetalBrushed,
            302,
        ),
        with_texture(
            diffuse("street_paint_black", [0.025, 0.025, 0.025]),
            TextureKindDesc::MetalPainted,
            303,
        ),
        with_texture(
            diffuse("street_paint_green", [0.03, 0.09, 0.05]),
            TextureKindDesc::MetalPainted,
            304,
        ),
        with_texture(
            diffuse("street_paint_grey", [0.22, 0.23, 0.23]),
            TextureKindDesc::MetalPainted,
            305,
        ),
        with_texture(
            diffuse("street_paint_red", [0.5, 0.04, 0.03]),
            TextureKindDesc::MetalPainted,
            306,
        ),
        with_texture(
            diffuse("street_paint_yellow", [0.7, 0.52, 0.04]),
            TextureKindDesc::MetalPainted,
            307,
        ),
        with_texture(
            diffuse("street_wood", [0.36, 0.22, 0.12]),
            TextureKindDesc::Wood,
            308,
        ),
        with_texture(
            diffuse("street_wood_pole", [0.2, 0.14, 0.09]),
            TextureKindDesc::Wood,
            309,
        ),
        with_texture(
            diffuse("street_concrete", [0.5, 0.49, 0.46]),
            TextureKindDesc::Concrete,
            310,
        ),
        diffuse("street_plastic_black", [0.04, 0.04, 0.04]),
        diffuse("street_wire", [0.02, 0.02, 0.02]),
        diffuse("street_insulator", [0.6, 0.6, 0.58]),
        with_texture(
            named(
                "street_glass",
                MaterialKindDesc::Dielectric {
                    ior: 1.5,
                    roughness: 0.0,
                    tint: [0.85, 0.9, 0.9],
                },
            ),
            TextureKindDesc::Glass,
            312,
        ),
        // Sign faces (retroreflective sheeting read as diffuse) and inks.
        with_texture(
            diffuse("sign_back_grey", [0.3, 0.31, 0.31]),
            TextureKindDesc::MetalBrushed,
            311,
        ),
        diffuse("sign_face_white", [0.82, 0.82, 0.8]),
        diffuse("sign_face_red", [0.55, 0.03, 0.03]),
        diffuse("sign_face_blue", [0.03, 0.13, 0.48]),
        diffuse("sign_face_green", [0.02, 0.25, 0.1]),
        diffuse("sign_face_yellow", [0.78, 0.6, 0.05]),
        diffuse("sign_ink_black", [0.025, 0.025, 0.025]),
        // Billboard prints: a pale ground and three ink colours.
        diffuse("sign_print_cream", [0.75, 0.7, 0.58]),
        diffuse("sign_print_orange", [0.75, 0.3, 0.04]),
        diffuse("sign_print_teal", [0.03, 0.35, 0.38]),
        diffuse("sign_print_purple", [0.25, 0.06, 0.35]),
    ]
}
