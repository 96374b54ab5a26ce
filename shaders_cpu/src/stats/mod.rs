//! Statistical test helpers for sampling code: a chi-square goodness-of-fit
//! harness over the sphere (Mitsuba 3 `chi2.py` recipe), the chi-square
//! distribution via the regularised incomplete gamma, and a tiny PCG32.
//!
//! Used by this crate's `tests/`; public so the renderer can test its own
//! light and phase-function samplers the same way.

mod chi2;
mod gamma;
mod pcg;
mod quadrature;

pub use chi2::{chi2_test, chi2_test_with, sidak_threshold, Chi2Config, Chi2Result};
pub use gamma::{chi2_sf, ln_gamma, regularized_gamma_p, regularized_gamma_q};
pub use pcg::Pcg32;
