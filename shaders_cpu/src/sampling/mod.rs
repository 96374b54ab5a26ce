//! Sampling warps, local frames and MIS weights.
//!
//! Every warp maps a uniform sample `u ∈ [0,1)²` to a domain and has a matching
//! pdf (per solid angle for directions, per unit area for the disk). Formulas
//! follow pbrt-v4 ch. 2 (Monte Carlo) and appendix A.5 (sampling multiple
//! dimensions); frames follow Duff et al. 2017.

mod color;
mod frame;
mod mis;
mod trig;
mod warps;

pub use color::luminance;
pub use frame::Frame;
pub use mis::{balance_heuristic, power_heuristic};
pub use trig::sin_cos_turns;
pub use warps::{
    cosine_hemisphere_pdf, sample_cosine_hemisphere, sample_uniform_cone,
    sample_uniform_disk_concentric, sample_uniform_disk_polar, sample_uniform_hemisphere,
    sample_uniform_sphere, sample_uniform_triangle, uniform_cone_pdf, uniform_hemisphere_pdf,
    uniform_sphere_pdf,
};
