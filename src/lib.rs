//! parallax: a CPU path tracer for synthetic stereo driving datasets with exact
//! ground truth. See `../shared/DESIGN.md` for the map of modules.

pub mod accel;
pub mod film;
pub mod geometry;
pub mod light;
pub mod output;
pub mod scene;
