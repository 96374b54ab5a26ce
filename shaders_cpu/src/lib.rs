//! Everything evaluated at a shading point: BSDFs, the sky, sampling warps,
//! procedural albedo textures,
//! plus `stats`, the chi-square harness their tests (and the renderer's) use.
//!
//! Pure functions of (inputs, sample) → value/pdf: no scene, no I/O, no threads.
//!
//! Direction convention (pbrt's, stated once here): `wo` points toward the
//! viewer, `wi` toward the light, both away from the surface. BSDFs work in a
//! local frame whose z axis is the shading normal; `pdf` is per solid angle.
//! Colours are linear RGB in `glam::Vec3`.

#![warn(missing_docs)]

pub mod bsdf;
pub mod medium;
pub mod sampling;
pub mod sky;
pub mod stats;
pub mod texture;
