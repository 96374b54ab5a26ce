//! What every path of a frame sees, built in one place: [`Shading`] owns
//! the frame's lights and compact hit records beside the shading view of
//! its accelerator; [`Shading::context`] lends them to the path tracer as a
//! [`PathContext`], with the sun lobe found once.

use crate::accel::{Accel, ShadingAccel};
use crate::light::LightSet;
use crate::scene::Scene;
use crate::scene::SurfaceTable;

use super::volpath::SunLobe;

/// The per-frame shading data of a scene: built once, shared by every view
/// and thread.
pub struct Shading<'a, A: Accel> {
    scene: &'a Scene,
    /// Paths trace on the backend's fast, not necessarily watertight
    /// variant; ground truth stays on the watertight one.
    accel: ShadingAccel<'a, A>,
    lights: LightSet,
    surfaces: SurfaceTable,
}

impl<'a, A: Accel> Shading<'a, A> {
    /// The shading data of `scene` traced with `accel`, local lights
    /// chosen by a light BVH.
    pub fn new(scene: &'a Scene, accel: &'a A) -> Self {
        Self::with_lights(scene, accel, LightSet::build(scene))
    }

    /// [`Shading::new`] with a light set built otherwise (e.g. another
    /// [`crate::light::LightSelection`]).
    pub fn with_lights(scene: &'a Scene, accel: &'a A, lights: LightSet) -> Self {
        Shading {
            scene,
            accel: ShadingAccel(accel),
            lights,
            surfaces: SurfaceTable::build(scene),
        }
    }

    /// The context of the frame's paths, at most `max_depth` scattering
    /// events each.
    pub fn context(&self, max_depth: u32) -> PathContext<'_, ShadingAccel<'a, A>> {
        PathContext {
            scene: self.scene,
            accel: &self.accel,
            lights: &self.lights,
            surfaces: &self.surfaces,
            max_depth,
            sun_lobe: SunLobe::find(self.scene, &self.lights),
        }
    }
}

/// Scene, accelerator and lights: what a path needs to see
/// ([`Shading::context`]).
pub struct PathContext<'a, A: Accel> {
    /// The frame's scene.
    pub scene: &'a Scene,
    /// Its accelerator.
    pub accel: &'a A,
    /// Its lights.
    pub lights: &'a LightSet,
    /// Its triangles' compact hit records.
    pub surfaces: &'a SurfaceTable,
    /// Maximum number of scattering events.
    pub max_depth: u32,
    /// The sun as the medium's second in-scattering strategy
    /// ([`SunLobe::find`], once per frame), if there is one. Not public:
    /// a context comes from [`Shading::context`] only.
    pub(super) sun_lobe: Option<SunLobe>,
}
