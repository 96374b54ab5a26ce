//! Ground truth: exact depth, disparity and occlusion on analytic boxes and
//! the street, untouched by weather and rain, and frames that are a pure
//! function of (scene, seed, frame).

#[path = "../common/mod.rs"]
mod common;

mod determinism;
mod exactness;
mod facade;
mod instancing;
mod occlusion;
mod people;
mod rain;
mod static_tiles;
mod street;
mod traced;
mod vegetation;
mod vehicles;
mod weather;
