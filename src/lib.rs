//! parallax: a CPU path tracer for synthetic stereo driving datasets with exact
//! ground truth. See `../shared/DESIGN.md` for the map of modules; their
//! layering (which module may use which) is the table in `layers.rs`.

#![warn(missing_docs)]

pub mod accel;
pub mod bench;
pub mod camera;
pub mod cli;
pub mod dataset;
pub mod denoise;
pub mod eval;
pub mod film;
pub mod geometry;
pub mod integrator;
pub mod light;
pub mod material;
pub mod output;
pub mod preview;
pub mod render;
pub mod sampler;
pub mod scene;
pub mod stats;
pub mod town;
pub mod weather;

#[cfg(test)]
mod layers;
