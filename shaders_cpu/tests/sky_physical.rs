//! The physical sky: transmittance table against direct integration, the sun
//! at noon and sunset, radiance finite/non-negative/continuous across the
//! horizon from noon to astronomical twilight, twilight falling monotonically,
//! the CIE overcast ratio, and cloud shadows fixed in the world.

use glam::{DVec2, DVec3, Vec3};
use shaders_cpu::sampling::luminance;
use shaders_cpu::sky::atmosphere::{
    distance_to_ground, Atmosphere, TransmittanceLut, EARTH_RADIUS_M, SOLAR_IRRADIANCE,
};
use shaders_cpu::sky::{CloudLayer, OvercastSky, PhysicalSky, PhysicalSkyParams, Sky};

fn sun_at(elevation_deg: f32) -> PhysicalSky {
    let e = elevation_deg.to_radians();
    let az = 0.7f32;
    PhysicalSky::new(PhysicalSkyParams {
        source_dir: Vec3::new(e.cos() * az.cos(), e.cos() * az.sin(), e.sin()),
        source_irradiance: DVec3::from(SOLAR_IRRADIANCE).as_vec3(),
        atmosphere: Atmosphere::default(),
        clouds: None,
        glow: None,
    })
}

fn dir(elevation: f32, azimuth: f32) -> Vec3 {
    Vec3::new(
        elevation.cos() * azimuth.cos(),
        elevation.cos() * azimuth.sin(),
        elevation.sin(),
    )
}

/// Mean luminance over the upper hemisphere (uniform in z and φ).
fn hemisphere_mean(sky: &PhysicalSky) -> f64 {
    let (nz, np) = (32, 64);
    let mut sum = 0.0;
    for j in 0..nz {
        let z = (j as f32 + 0.5) / nz as f32;
        for i in 0..np {
            let phi = std::f32::consts::TAU * (i as f32 + 0.5) / np as f32;
            sum += luminance(sky.le(dir(z.asin(), phi))) as f64;
        }
    }
    sum / (nz * np) as f64
}

#[test]
fn transmittance_table_matches_direct_integration() {
    let atmo = Atmosphere::default();
    let lut = TransmittanceLut::new(&atmo);
    let mut worst = 0.0f64;
    for h in [0.0, 10.0, 1_000.0, 5_000.0, 20_000.0, 60_000.0] {
        for mu in [1.0, 0.7, 0.3, 0.1, 0.03, 0.0, -0.02, -0.1] {
            let r = EARTH_RADIUS_M + h;
            if distance_to_ground(r, mu).is_some() {
                continue; // the table holds rays that reach space
            }
            let exact = atmo.transmittance_direct(r, mu, 20_000);
            let table = lut.lookup(r, mu);
            let err = (table - exact).abs().max_element();
            eprintln!("h {h} mu {mu}: {exact} vs {table}");
            worst = worst.max(err);
            assert!(err < 0.01, "h {h} mu {mu}: {exact} vs {table}");
        }
    }
    eprintln!("worst abs error {worst}");
}

#[test]
fn zenith_sun_gives_the_towns_clear_irradiance_and_sinks_red() {
    let noon = sun_at(90.0).source_irradiance_ground();
    eprintln!("noon sun {noon}");
    assert!(
        (noon.x - 980.0).abs() < 20.0 && (noon.z - 850.0).abs() < 40.0,
        "{noon}"
    );
    let low = sun_at(1.0).source_irradiance_ground();
    eprintln!("1° sun {low}");
    assert!(low.x / low.z > 3.0 * noon.x / noon.z, "{low} vs {noon}");
    assert!(low.x < 0.5 * noon.x);
    assert_eq!(sun_at(-2.0).source_irradiance_ground(), Vec3::ZERO);
}

#[test]
fn sky_radiance_is_finite_non_negative_and_continuous_across_the_horizon() {
    for e_sun in [90.0, 60.0, 30.0, 10.0, 3.0, 0.0, -3.0, -6.0, -12.0, -18.0] {
        let sky = sun_at(e_sun);
        let mut peak = 0.0f32;
        let mut worst_jump = 0.0f32;
        for a in 0..24 {
            let az = a as f32 * std::f32::consts::TAU / 24.0;
            // Elevation −10° … +10° in 0.05° steps straddles the horizon.
            let mut prev = sky.le(dir((-10.0f32).to_radians(), az));
            for k in 1..=400 {
                let el = (-10.0 + 0.05 * k as f32).to_radians();
                let l = sky.le(dir(el, az));
                assert!(l.is_finite() && l.min_element() >= 0.0, "{e_sun}: {l}");
                worst_jump = worst_jump.max((l - prev).abs().max_element());
                peak = peak.max(l.max_element());
                prev = l;
            }
        }
        eprintln!("sun {e_sun}°: peak {peak:.3e}, worst jump {worst_jump:.3e}");
        assert!(peak > 0.0);
        assert!(
            worst_jump <= 0.15 * peak,
            "sun {e_sun}°: jump {worst_jump} of peak {peak}"
        );
    }
}

#[test]
fn twilight_luminance_falls_monotonically_as_the_sun_sinks() {
    let mut prev: Option<(f64, f64)> = None;
    let mut e = 10.0f32;
    while e >= -18.0 {
        let sky = sun_at(e);
        let zenith = luminance(sky.le(Vec3::Z)) as f64;
        let mean = hemisphere_mean(&sky);
        eprintln!("sun {e}°: zenith {zenith:.4e}, hemisphere mean {mean:.4e}");
        if let Some((pz, pm)) = prev {
            assert!(
                zenith < pz && mean < pm,
                "sun {e}°: {zenith} / {mean} vs {pz} / {pm}"
            );
        }
        prev = Some((zenith, mean));
        e -= 2.0;
    }
    // Astronomical twilight: at least four decades below the 10° sky.
    let (z18, _) = prev.unwrap();
    assert!(z18 < 1e-4 * luminance(sun_at(10.0).le(Vec3::Z)) as f64);
}

#[test]
fn noon_sky_is_blue_and_tens_of_watts() {
    let l = sun_at(60.0).le(Vec3::Z);
    eprintln!("zenith at 60° sun: {l}");
    assert!(l.z > l.x && l.z > 5.0 && l.z < 100.0, "{l}");
}

#[test]
fn overcast_zenith_to_horizon_ratio_is_three() {
    let o = OvercastSky::from_irradiance(Vec3::new(100.0, 110.0, 120.0), 0.2);
    let ratio = o.le(Vec3::Z) / o.le(Vec3::X);
    assert!(
        (ratio - Vec3::splat(3.0)).abs().max_element() < 1e-5,
        "{ratio}"
    );
    // E = ∫ L cos dω over the hemisphere reproduces the input irradiance.
    let n = 4000;
    let e: f64 = (0..n)
        .map(|i| {
            let z = (i as f32 + 0.5) / n as f32;
            let r = (1.0 - z * z).sqrt();
            (o.le(Vec3::new(r, 0.0, z)).x * z) as f64
        })
        .sum::<f64>()
        * std::f64::consts::TAU
        / n as f64;
    assert!((e - 100.0).abs() < 0.05, "{e}");
}

#[test]
fn cloud_shadow_survives_render_space_rounding() {
    let layer = CloudLayer::new(0.5, 42);
    let sun = Vec3::new(0.3, 0.2, 0.93).normalize();
    let e = sun_at(60.0);
    let sky = Sky::Physical(Box::new(PhysicalSky::new(PhysicalSkyParams {
        clouds: Some(layer),
        ..*e.params()
    })));
    // The same world point rebuilt from two f32 render-space positions
    // (render origins 1 km apart), as the renderer rebuilds it: rounding in
    // render space must not move the shadow. (That the renderer passes world
    // positions at all is checked through its light set in
    // `tests/light/sky_physical_furnace.rs`.)
    let mut shadowed = 0;
    for k in 0..2000 {
        let p_world = DVec3::new(37.0 * k as f64, -11.0 * k as f64, 0.1 * (k % 7) as f64);
        let from_left = {
            let origin = DVec3::new(5.0, 2.0, 1.6);
            let p_render = (p_world - origin).as_vec3();
            sky.cloud_transmittance(origin + p_render.as_dvec3(), sun)
        };
        let from_far = {
            let origin = DVec3::new(1005.0, 2.54, 1.6);
            let p_render = (p_world - origin).as_vec3();
            sky.cloud_transmittance(origin + p_render.as_dvec3(), sun)
        };
        assert!(
            (from_left - from_far).abs() < 1e-4,
            "{k}: {from_left} vs {from_far}"
        );
        shadowed += (from_left < 0.5) as usize;
    }
    // Half cover: a real fraction of the ground is shadowed, not all of it.
    eprintln!("shadowed {shadowed} of 2000");
    assert!((400..1600).contains(&shadowed), "{shadowed}");
    assert_eq!(
        layer.opacity(DVec2::new(1.0, 2.0)),
        CloudLayer::new(0.5, 42).opacity(DVec2::new(1.0, 2.0))
    );
}
