//! Lights: the sun (a directional light with the sun's angular size), point and
//! spot lights, and emissive triangles found from materials; light selection
//! for next-event estimation.
//!
//! Directions are render space (= world orientation, z up). Sampling returns
//! radiance arriving at the shading point and a pdf per solid angle.

use glam::Vec3;

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
