//! The `texture` key of materials: parsing, defaults, round trip, and the
//! errors for misuse.

use crate::common;

use common::scene_from_toml;
use parallax::scene::desc::{TextureDesc, TextureKindDesc};
use parallax::scene::parse_scene_str;

fn scene_with(material: &str) -> String {
    format!(
        "{}[[light]]\nkind = \"sun\"\nelevation_deg = 40.0\nazimuth_deg = 0.0\nirradiance = [1.0, 1.0, 1.0]\n\
[[material]]\nname = \"m\"\n{material}\n[[object]]\nkind = \"quad\"\nsize = [4.0, 4.0]\nmaterial = \"m\"\n",
        common::camera_block(8, 8, [0.0, 0.0, 1.0])
    )
}

fn error_of(material: &str) -> String {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/inline.toml");
    match parse_scene_str(&scene_with(material), &path) {
        Ok(_) => panic!("accepted: {material}"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn texture_key_parses_with_defaults_and_round_trips() {
    let loaded = scene_from_toml(&scene_with(
        "kind = \"diffuse\"\nalbedo = [0.4, 0.2, 0.1]\ntexture = { kind = \"brick\" }",
    ));
    let t = loaded.desc.materials[0].texture.expect("texture parsed");
    assert_eq!(
        t,
        TextureDesc {
            kind: TextureKindDesc::Brick,
            scale: 1.0,
            seed: 0,
            bump: 1.0,
        }
    );
    let text = parallax::scene::serialize_scene(&loaded.desc);
    assert!(text.contains("brick"), "{text}");
    let again = scene_from_toml(&text);
    assert_eq!(again.desc.materials, loaded.desc.materials);
}

#[test]
fn texture_misuse_is_rejected_with_key_path() {
    // Every kind but emitters takes a texture.
    let e = error_of(
        "kind = \"emissive\"\nradiance = [1.0, 1.0, 1.0]\ntexture = { kind = \"asphalt\" }",
    );
    assert!(
        e.contains("material[0].texture") && e.contains("emissive"),
        "{e}"
    );
    let metal = scene_from_toml(&scene_with(
        "kind = \"conductor\"\npreset = \"iron\"\nroughness = 0.4\ntexture = { kind = \"metal_brushed\", bump = 0.5 }",
    ));
    let t = metal.desc.materials[0].texture.unwrap();
    assert_eq!((t.kind, t.bump), (TextureKindDesc::MetalBrushed, 0.5));
    let e = error_of(
        "kind = \"diffuse\"\nalbedo = [0.4, 0.4, 0.4]\ntexture = { kind = \"stone\", bump = 5.0 }",
    );
    assert!(
        e.contains("material[0].texture.bump") && e.contains('5'),
        "{e}"
    );
    let e = error_of("kind = \"diffuse\"\nalbedo = [0.4, 0.4, 0.4]\ntexture = { kind = \"asphalt\", scale = 0.0 }");
    assert!(e.contains("material[0].texture.scale"), "{e}");
    let e =
        error_of("kind = \"diffuse\"\nalbedo = [0.4, 0.4, 0.4]\ntexture = { kind = \"marble\" }");
    assert!(e.contains("marble"), "{e}");
    let e = error_of(
        "kind = \"diffuse\"\nalbedo = [0.4, 0.4, 0.4]\ntexture = { kind = \"brick\", size = 2.0 }",
    );
    assert!(e.contains("size"), "{e}");
}
