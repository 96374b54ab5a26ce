//! `parallax eval`: metrics against hand-computed values and predictions
//! found in every layout.

#[path = "../common/mod.rs"]
mod common;

mod layouts;
mod metrics;
