//! A sun of any accepted angular size lights a plane with its stated
//! irradiance: a Lambert plane under a sun disk at elevation e has radiance
//! ρ/π · E · sin e (the projected solid angle of a cap centred at zenith
//! angle θ is π sin²α cos θ exactly, and E = L π sin²α). Tiny suns used to
//! round their cone's cosine to 1 in f32 and turn samples NaN (issue 23
//! item 4); `render` asserts that no sample is non-finite.

use crate::common;

use common::{mean_stderr, render, scene_from_toml};
use parallax::accel::Backend;

const RHO: f64 = 0.5;
const E_SUN: f64 = 3.0;
const ELEVATION_DEG: f64 = 55.0;

/// Mean rendered/expected ratio over the plane's pixels under a sun of
/// `diameter_deg`, with its standard error.
fn plane_ratio(diameter_deg: f64) -> (f64, f64) {
    let text = format!(
        "[camera]\nwidth = 48\nheight = 32\nhfov_deg = 60.0\nbaselines_cm = [10.0]\nposition = [0.0, 0.0, 3.0]\npitch_deg = 90.0\n\
[render]\nspp = 8\nmax_depth = 1\nseed = 5\nfilter_indirect = false\n\
[sky]\nkind = \"constant\"\nle = [0.0, 0.0, 0.0]\n\
[[material]]\nname = \"m\"\nkind = \"diffuse\"\nalbedo = [{RHO:?}, {RHO:?}, {RHO:?}]\n\
[[object]]\nkind = \"quad\"\nsize = [100.0, 100.0]\nmaterial = \"m\"\ninstance = 3\n\
[[light]]\nkind = \"sun\"\nelevation_deg = {ELEVATION_DEG:?}\nazimuth_deg = 30.0\n\
irradiance = [{E_SUN:?}, {E_SUN:?}, {E_SUN:?}]\nangular_diameter_deg = {diameter_deg:?}\n"
    );
    let r = render(&scene_from_toml(&text), Backend::default_backend(), 8);
    let expected = RHO / std::f64::consts::PI * E_SUN * ELEVATION_DEG.to_radians().sin();
    let v: Vec<f64> = (0..r.out.left.instance.len())
        .filter(|&k| r.out.left.instance[k] == 3)
        .map(|k| r.out.images[0].rgb[k].y as f64 / expected)
        .collect();
    assert_eq!(v.len(), 48 * 32, "the plane fills the view");
    mean_stderr(&v)
}

#[test]
fn sunlit_plane_matches_the_irradiance_for_tiny_and_large_suns() {
    for diameter_deg in [0.001, 0.02, 0.533, 20.0] {
        let (mean, se) = plane_ratio(diameter_deg);
        eprintln!("{diameter_deg}°: ratio {mean:.6} ± {se:.6}");
        assert!(
            (mean - 1.0).abs() <= 2e-3 + 4.0 * se,
            "sun of {diameter_deg}°: plane radiance ratio {mean} ± {se}"
        );
    }
}
