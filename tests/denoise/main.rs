//! The image-space filters (denoiser) through the whole renderer: the fog
//! in-scattering filter, the indirect-light filter and the direct-light
//! filter.

#[path = "../common/mod.rs"]
mod common;

mod direct;
mod fog;
mod indirect;
