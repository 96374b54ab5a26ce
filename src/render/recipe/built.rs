//! A scene built around an origin with its accelerator: the one place
//! `build_scene` and `build_accel` run in sequence (the recipe's frames, and
//! callers that need only the geometry: `town`, `bench`, tests).

use std::time::Instant;

use glam::DVec3;

use super::RecipeError;
use crate::accel::{build_accel, AccelError, AnyAccel, Backend};
use crate::scene::{build_scene, LoadedScene, Scene};

/// A scene built around an origin and its accelerator: the one place
/// `build_scene` and `build_accel` run in sequence.
pub struct BuiltScene {
    /// The scene (f32 coordinates relative to `scene.origin_world`).
    pub scene: Scene,
    /// Its accelerator.
    pub accel: AnyAccel,
    /// Seconds to build the scene.
    pub scene_seconds: f64,
    /// Seconds to build the accelerator.
    pub accel_seconds: f64,
}

impl BuiltScene {
    /// Builds `loaded` around `origin` (world metres) on `backend`.
    pub fn build(
        loaded: &LoadedScene,
        origin: DVec3,
        backend: Backend,
    ) -> Result<BuiltScene, RecipeError> {
        Self::build_with(loaded, origin, backend, true)
    }

    /// As [`BuiltScene::build`]; Embree without its shading twin when
    /// `shading_twin` is off (paths then trace the watertight scene).
    pub fn build_with(
        loaded: &LoadedScene,
        origin: DVec3,
        backend: Backend,
        shading_twin: bool,
    ) -> Result<BuiltScene, RecipeError> {
        let t = Instant::now();
        let scene = build_scene(loaded, origin).map_err(RecipeError::Scene)?;
        let scene_seconds = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let accel = accel_for(backend, shading_twin, &scene.accel_geometry())
            .map_err(RecipeError::Accel)?;
        Ok(BuiltScene {
            scene,
            accel,
            scene_seconds,
            accel_seconds: t.elapsed().as_secs_f64(),
        })
    }
}

/// The backend's accelerator, Embree without its twin if so asked.
fn accel_for(
    backend: Backend,
    shading_twin: bool,
    geo: &crate::accel::AccelGeometry,
) -> Result<AnyAccel, AccelError> {
    #[cfg(feature = "embree")]
    if backend == Backend::Embree && !shading_twin {
        return crate::accel::EmbreeAccel::build_with(geo, false).map(AnyAccel::Embree);
    }
    #[cfg(not(feature = "embree"))]
    let _ = shading_twin; // only Embree has a twin
    build_accel(backend, geo)
}
