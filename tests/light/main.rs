//! Light transport against closed forms: furnaces, local lights, media, the
//! physical sky and wet surfaces; the light BVH's selection and its noise.

#[path = "../common/mod.rs"]
mod common;

mod analytic_furnace;
mod analytic_lights;
mod bump_furnace;
mod bvh;
mod cut;
mod media_analytic;
mod noise_town;
mod sky_physical_furnace;
mod tiny_sun;
mod wet_surfaces;
