//! Dataset generation at scale (DESIGN.md "Scale", DATASET.md): a
//! configuration (`config`, `presets`) becomes a job list that is a pure
//! function of it (`plan`), split by `shard`; `root` prepares the root;
//! `run` renders and writes each
//! frame whole (`frame`), appending a manifest line (`manifest`) and skipping
//! complete frames on resume; `verify` proves a root whole and `repair`
//! mends it; `progress` and `signals` make long runs observable and stoppable.

pub mod calibrate;
pub mod config;
pub mod estimate;
pub mod frame;
pub mod layouts;
pub mod manifest;
pub mod ownership;
pub mod plan;
pub mod presets;
pub mod progress;
#[cfg(test)]
mod registry_walk;
pub mod repair;
pub mod root;
pub mod run;
pub mod shard;
pub mod signals;
pub mod verify;

pub use config::{load_config, parse_config, ConfigError, DatasetConfig};
pub use plan::{plan, Job};
pub use progress::RunSummary;
pub use run::{run_dataset, DatasetError, RunOptions};
pub use shard::Shard;
pub use signals::StopGuard;
pub use verify::{verify_dataset, VerifyReport};
