//! Rays and robust ray origins in render space: `Ray`, exact ray–primitive
//! distances, f32 error bounds and offsets, and `SurfaceInteraction` (a
//! surface point and the rays leaving it). Geometry reads nothing above it:
//! the scene turns accelerator hits into interactions.
//!
//! Render space is world space translated so that the frame's reference camera
//! sits at the origin (STYLE.md rule 6): positions there are small, so f32
//! traversal keeps its precision kilometres from the world origin.

mod exact;
mod interaction;
mod offset;

pub use exact::{ray_plane_t, ray_sphere_t};
pub use interaction::{FrontOrigin, SurfaceInteraction};
pub use offset::{gamma, offset_ray_origin, position_error};

use glam::Vec3;

/// A ray in render space (f32), as the accelerators consume it.
///
/// Hits are accepted for `tmin <= t <= tmax`; `d` need not be normalised
/// (t is then measured in units of `d`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    /// Origin, render space, metres.
    pub o: Vec3,
    /// Direction, render space.
    pub d: Vec3,
    /// Smallest accepted parameter.
    pub tmin: f32,
    /// Largest accepted parameter (`f32::INFINITY` for an unbounded ray).
    pub tmax: f32,
}

impl Ray {
    /// An unbounded ray starting exactly at `o`.
    pub fn new(o: Vec3, d: Vec3) -> Self {
        Ray {
            o,
            d,
            tmin: 0.0,
            tmax: f32::INFINITY,
        }
    }

    /// A ray from `o` towards `d` accepting hits for t in `[0, tmax]`.
    pub fn segment(o: Vec3, d: Vec3, tmax: f32) -> Self {
        Ray {
            o,
            d,
            tmin: 0.0,
            tmax,
        }
    }

    /// The point at parameter `t`.
    pub fn at(&self, t: f32) -> Vec3 {
        self.o + self.d * t
    }
}
