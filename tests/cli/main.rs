//! The command line through the real binary: bad input, any working
//! directory, `render -o` over an existing directory, filters off,
//! `preview`, `stats` and `bench`.

#[path = "../common/mod.rs"]
mod common;

mod any_directory;
mod bad_input;
mod bench;
mod closed_pipe;
mod denoiser;
mod embree_build;
mod filter;
mod preview;
mod reference;
mod render_output_dir;
mod stats;
mod trajectory;
