//! Image formation on the film: tone mapping, sensor noise, rain streaks,
//! noise decorrelated between views, procedural textures in frames.

#[path = "../common/mod.rs"]
mod common;

mod noise_decorrelation;
mod rain_streaks;
mod sensor_noise;
mod texture_render;
mod tone;
