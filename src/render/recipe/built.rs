//! A scene built around an origin with its accelerator: the one place
//! `build_scene` and `build_accel` run in sequence (the recipe's frames, and
//! callers that need only the geometry: `town`, `bench`, tests).

use std::time::Instant;

use glam::DVec3;

use super::RecipeError;
use crate::accel::{build_accel_cached, AccelCache, AnyAccel, Backend};
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
        Self::build_full(
            loaded,
            origin,
            backend,
            shading_twin,
            &AccelCache::default(),
        )
    }

    /// As [`BuiltScene::build`], reusing what `cache` holds of the previous
    /// build (its static prototypes' accelerators): the same result.
    pub fn build_cached(
        loaded: &LoadedScene,
        origin: DVec3,
        backend: Backend,
        cache: &AccelCache,
    ) -> Result<BuiltScene, RecipeError> {
        Self::build_full(loaded, origin, backend, true, cache)
    }

    fn build_full(
        loaded: &LoadedScene,
        origin: DVec3,
        backend: Backend,
        shading_twin: bool,
        cache: &AccelCache,
    ) -> Result<BuiltScene, RecipeError> {
        let t = Instant::now();
        let scene = build_scene(loaded, origin).map_err(RecipeError::Scene)?;
        let scene_seconds = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let accel = build_accel_cached(backend, &scene.accel_geometry(), shading_twin, cache)
            .map_err(RecipeError::Accel)?;
        Ok(BuiltScene {
            scene,
            accel,
            scene_seconds,
            accel_seconds: t.elapsed().as_secs_f64(),
        })
    }
}
