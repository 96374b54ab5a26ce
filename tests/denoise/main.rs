//! The image-space filters (denoiser) through the whole renderer: the fog
//! in-scattering filter, the indirect-light filter and the direct-light
//! filter, and the auxiliary images for an external denoiser.

#[path = "../common/mod.rs"]
mod common;

mod aov;
mod direct;
mod fog;
mod glass;
mod highlight;
mod indirect;
mod oidn;
mod openness;
mod shade;
