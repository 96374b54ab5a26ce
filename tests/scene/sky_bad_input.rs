//! Bad sky input: out-of-range physical, overcast and night parameters and a
//! physical sky with a second, explicit sun are rejected with the key named;
//! the defaults of the physical sky parse and validate.

use std::path::Path;

use parallax::scene::{parse_scene_str, SceneErrorKind};

const FILE: &str = "scenes/bad_sky.toml";
const BODY: &str = "[camera]\nposition = [0.0, 0.0, 1.5]\n[[material]]\nname = \"grey\"\nkind = \"diffuse\"\nalbedo = [0.5, 0.5, 0.5]\n[[object]]\nkind = \"quad\"\nsize = [1.0, 1.0]\nmaterial = \"grey\"\n";

fn expect_invalid(sky: &str, key: &str) {
    let text = format!("{BODY}{sky}");
    match parse_scene_str(&text, Path::new(FILE)) {
        Ok(_) => panic!("accepted bad sky:\n{sky}"),
        Err(e) => {
            let msg = e.to_string();
            eprintln!("{msg}");
            assert_eq!(e.kind, SceneErrorKind::Invalid, "{msg}");
            assert!(
                msg.starts_with(FILE),
                "message does not name the file: {msg}"
            );
            assert!(msg.contains(key), "message does not name `{key}`: {msg}");
        }
    }
}

#[test]
fn physical_sky_rejects_out_of_range_parameters() {
    let p = "[sky]\nkind = \"physical\"\nsun_azimuth_deg = 10.0\n";
    expect_invalid(
        &format!("{p}sun_elevation_deg = 95.0\n"),
        "sky.sun_elevation_deg",
    );
    expect_invalid(
        &format!("{p}sun_elevation_deg = 30.0\ncloud_cover = 1.5\n"),
        "sky.cloud_cover",
    );
    expect_invalid(
        &format!("{p}sun_elevation_deg = 30.0\nturbidity = -1.0\n"),
        "sky.turbidity",
    );
    expect_invalid(
        &format!("{p}sun_elevation_deg = 30.0\nground_albedo = 2.0\n"),
        "sky.ground_albedo",
    );
}

#[test]
fn physical_sky_with_an_explicit_sun_is_rejected() {
    expect_invalid(
        "[sky]\nkind = \"physical\"\nsun_elevation_deg = 30.0\nsun_azimuth_deg = 0.0\n[[light]]\nkind = \"sun\"\nelevation_deg = 30.0\nazimuth_deg = 0.0\nirradiance = [900.0, 900.0, 900.0]\n",
        "light[0]",
    );
}

#[test]
fn overcast_and_night_skies_reject_out_of_range_parameters() {
    expect_invalid(
        "[sky]\nkind = \"overcast\"\nirradiance = [1.0, -1.0, 1.0]\n",
        "sky.irradiance",
    );
    let n = "[sky]\nkind = \"night\"\nmoon_elevation_deg = 30.0\nmoon_azimuth_deg = 0.0\n";
    expect_invalid(
        &format!("{n}moon_phase_deg = 200.0\n"),
        "sky.moon_phase_deg",
    );
    expect_invalid(&format!("{n}sky_glow = -1e-5\n"), "sky.sky_glow");
}

#[test]
fn physical_sky_defaults_validate_and_a_sky_past_twilight_is_no_light() {
    let ok = "[sky]\nkind = \"physical\"\nsun_elevation_deg = 30.0\nsun_azimuth_deg = 0.0\n";
    parse_scene_str(&format!("{BODY}{ok}"), Path::new(FILE)).expect("defaults validate");
    // Past astronomical twilight the physical sky is black: no light at all.
    let dark = "[sky]\nkind = \"physical\"\nsun_elevation_deg = -30.0\nsun_azimuth_deg = 0.0\n";
    let e = parse_scene_str(&format!("{BODY}{dark}"), Path::new(FILE)).unwrap_err();
    assert_eq!(e.kind, SceneErrorKind::NoLight, "{e}");
    assert!(e.to_string().starts_with(FILE), "{e}");
}
