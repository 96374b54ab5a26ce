//! The image-space filters (denoiser) through the whole renderer: the fog
//! in-scattering filter and the indirect-light filter.

#[path = "../common/mod.rs"]
mod common;

mod fog;
mod indirect;
