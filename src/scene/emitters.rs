//! The emitters a `Scene` stores, as data: explicit lights (`Light`, built
//! from `[[light]]` in render space) and the frame's sky, with the light its
//! source brings: the physical sky's sun, or the night sky's moon, as a
//! distant disk whose irradiance is the atmosphere's (top-of-atmosphere ×
//! transmittance). Sampling them is `light`'s job.
//!
//! World directions, z up; degrees from the description, radians inside.

use glam::{DVec3, Vec3};
use shaders_cpu::sky::atmosphere::{Atmosphere, SOLAR_IRRADIANCE, SUN_ANGULAR_RADIUS_RAD};
use shaders_cpu::sky::{CloudLayer, NightGlow, OvercastSky, PhysicalSky, PhysicalSkyParams, Sky};

use super::desc::{LightDesc, SceneDesc, SkyDesc};
use crate::material::build::v3;

/// An explicit light source.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Light {
    /// Distant sun: a uniform disk of angular radius `angular_radius_rad`
    /// around `dir_to_sun`, delivering `irradiance` (W·m⁻² on a surface facing it).
    Sun {
        /// Unit vector towards the sun's centre.
        dir_to_sun: Vec3,
        /// Angular radius of the disk (the sun's is 0.004654 rad = 0.2666°).
        angular_radius_rad: f32,
        /// RGB irradiance on a surface perpendicular to `dir_to_sun`.
        irradiance: Vec3,
    },
    /// Isotropic point light.
    Point {
        /// Position, render space.
        p: Vec3,
        /// Radiant intensity, W·sr⁻¹ per RGB channel.
        intensity: Vec3,
    },
    /// Spot light with a smooth falloff between the inner and outer cones.
    Spot {
        /// Position, render space.
        p: Vec3,
        /// Unit axis of the cone.
        dir: Vec3,
        /// Radiant intensity on the axis, W·sr⁻¹.
        intensity: Vec3,
        /// Cosine of the full-intensity half-angle.
        cos_inner: f32,
        /// Cosine of the cut-off half-angle.
        cos_outer: f32,
    },
}

/// The explicit lights of `desc` in render space around `origin_world`, then
/// its sky and the sky's disk light (if its source is up).
pub fn build_emitters(desc: &SceneDesc, origin_world: DVec3) -> (Vec<Light>, Sky) {
    let (sky, sky_light) = build_sky(desc.sky.as_ref(), origin_world);
    let lights = desc
        .lights
        .iter()
        .map(|l| build_light(l, origin_world))
        .chain(sky_light)
        .collect();
    (lights, sky)
}

/// Unit vector towards a direction given by elevation above the horizon and
/// azimuth counter-clockwise from +x (world z up).
fn dir_from_elevation_azimuth(elevation_deg: f64, azimuth_deg: f64) -> DVec3 {
    let (e, a) = (elevation_deg.to_radians(), azimuth_deg.to_radians());
    DVec3::new(e.cos() * a.cos(), e.cos() * a.sin(), e.sin())
}

/// Full-moon irradiance relative to the sun's (both outside the atmosphere).
pub const MOON_TO_SUN: f64 = 2.5e-6;
/// Angular radius of the moon, rad (0.259°).
const MOON_ANGULAR_RADIUS_RAD: f32 = 0.004_52;

/// Brightness of the moon at phase angle `phase_deg` relative to full: the
/// Lambert-sphere law ((π − α) cos α + sin α)/π.
pub fn moon_phase_factor(phase_deg: f64) -> f64 {
    let a = phase_deg.clamp(0.0, 180.0).to_radians();
    (((std::f64::consts::PI - a) * a.cos() + a.sin()) / std::f64::consts::PI).max(0.0)
}

/// The sky of `desc` (black without one) and the disk light it brings, if its
/// source is above the horizon. `viewer_world` (the rig) is where the cloud
/// deck drawn in the sky is seen from.
pub fn build_sky(desc: Option<&SkyDesc>, viewer_world: DVec3) -> (Sky, Option<Light>) {
    let Some(desc) = desc else {
        return (Sky::Constant { le: Vec3::ZERO }, None);
    };
    match desc {
        SkyDesc::Constant { le } => (Sky::Constant { le: v3(*le) }, None),
        SkyDesc::Gradient {
            zenith,
            horizon,
            ground,
        } => (
            Sky::Gradient {
                zenith: v3(*zenith),
                horizon: v3(*horizon),
                ground: v3(*ground),
            },
            None,
        ),
        SkyDesc::Overcast {
            irradiance,
            ground_albedo,
        } => (
            Sky::overcast(OvercastSky::from_irradiance(
                v3(*irradiance),
                *ground_albedo as f32,
            )),
            None,
        ),
        SkyDesc::Physical {
            sun_elevation_deg,
            sun_azimuth_deg,
            turbidity,
            ground_albedo,
            cloud_cover,
            cloud_seed,
        } => {
            let clouds = (*cloud_cover > 0.0)
                .then(|| CloudLayer::new(*cloud_cover as f32, *cloud_seed).seen_from(viewer_world));
            source_sky(
                PhysicalSkyParams {
                    source_dir: dir_from_elevation_azimuth(*sun_elevation_deg, *sun_azimuth_deg)
                        .as_vec3(),
                    source_irradiance: v3(SOLAR_IRRADIANCE),
                    atmosphere: Atmosphere {
                        turbidity: *turbidity,
                        ground_albedo: *ground_albedo,
                    },
                    clouds,
                    glow: None,
                },
                SUN_ANGULAR_RADIUS_RAD as f32,
            )
        }
        SkyDesc::Night {
            moon_elevation_deg,
            moon_azimuth_deg,
            moon_phase_deg,
            sky_glow,
            stars,
            star_seed,
            turbidity,
        } => {
            let moon = MOON_TO_SUN * moon_phase_factor(*moon_phase_deg);
            source_sky(
                PhysicalSkyParams {
                    source_dir: dir_from_elevation_azimuth(*moon_elevation_deg, *moon_azimuth_deg)
                        .as_vec3(),
                    source_irradiance: v3(SOLAR_IRRADIANCE.map(|e| e * moon)),
                    atmosphere: Atmosphere {
                        turbidity: *turbidity,
                        ground_albedo: 0.1,
                    },
                    clouds: None,
                    glow: Some(NightGlow::new(*sky_glow as f32, *stars, *star_seed)),
                },
                MOON_ANGULAR_RADIUS_RAD,
            )
        }
    }
}

/// A physical sky and its source's disk light (none once the disk has set).
fn source_sky(params: PhysicalSkyParams, angular_radius_rad: f32) -> (Sky, Option<Light>) {
    let sky = PhysicalSky::new(params);
    let irradiance = sky.source_irradiance_ground();
    let light = (irradiance.max_element() > 0.0).then_some(Light::Sun {
        dir_to_sun: params.source_dir,
        angular_radius_rad,
        irradiance,
    });
    (Sky::Physical(Box::new(sky)), light)
}

/// One `[[light]]` in render space (positions relative to `origin_world`).
fn build_light(l: &LightDesc, origin_world: DVec3) -> Light {
    let p_render = |p: &[f64; 3]| (DVec3::from(*p) - origin_world).as_vec3();
    match l {
        LightDesc::Sun {
            elevation_deg,
            azimuth_deg,
            irradiance,
            angular_diameter_deg,
        } => Light::Sun {
            dir_to_sun: dir_from_elevation_azimuth(*elevation_deg, *azimuth_deg).as_vec3(),
            angular_radius_rad: (angular_diameter_deg / 2.0).to_radians() as f32,
            irradiance: v3(*irradiance),
        },
        LightDesc::Point {
            position,
            intensity,
        } => Light::Point {
            p: p_render(position),
            intensity: v3(*intensity),
        },
        LightDesc::Spot {
            position,
            direction,
            intensity,
            inner_deg,
            outer_deg,
        } => Light::Spot {
            p: p_render(position),
            dir: DVec3::from(*direction).normalize().as_vec3(),
            intensity: v3(*intensity),
            cos_inner: inner_deg.to_radians().cos() as f32,
            cos_outer: outer_deg.to_radians().cos() as f32,
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A scene with one point light at world (10, 2, 5) under a physical sky
    /// whose sun stands at `sun_elevation_deg`.
    fn desc(sun_elevation_deg: f64) -> SceneDesc {
        toml::from_str(&format!(
            "[camera]\nposition = [0.0, 0.0, 1.6]\n\
             [sky]\nkind = \"physical\"\nsun_elevation_deg = {sun_elevation_deg}\n\
             sun_azimuth_deg = 90.0\nturbidity = 3.0\nground_albedo = 0.2\n\
             [[light]]\nkind = \"point\"\nposition = [10.0, 2.0, 5.0]\nintensity = [1.0, 2.0, 3.0]\n"
        ))
        .expect("test scene parses")
    }

    #[test]
    fn explicit_lights_come_first_in_render_space_then_the_sky_sun_while_it_is_up() {
        let origin = DVec3::new(4.0, -1.0, 1.0);
        let (lights, sky) = build_emitters(&desc(30.0), origin);
        assert!(matches!(sky, Sky::Physical(_)));
        assert_eq!(lights.len(), 2, "{lights:?}");
        assert_eq!(
            lights[0],
            Light::Point {
                p: Vec3::new(6.0, 3.0, 4.0),
                intensity: Vec3::new(1.0, 2.0, 3.0),
            }
        );
        let Light::Sun { dir_to_sun, .. } = lights[1] else {
            panic!("the sky's sun comes last: {lights:?}");
        };
        // Elevation 30°, azimuth 90°: towards +y, half-way up.
        assert!((dir_to_sun - Vec3::new(0.0, 0.866_025_4, 0.5)).length() < 1e-6);
        // Once the sun has set, the sky brings no disk light.
        let (lights, _) = build_emitters(&desc(-10.0), origin);
        assert_eq!(lights.len(), 1, "{lights:?}");
    }
}
