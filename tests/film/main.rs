//! Image formation on the film: tone mapping, sensor noise, rain streaks,
//! noise decorrelated between views, procedural textures in frames,
//! adaptive sampling.

#[path = "../common/mod.rs"]
mod common;

mod adaptive;
mod noise_decorrelation;
mod rain_streaks;
mod sensor_noise;
mod texture_render;
mod tone;
