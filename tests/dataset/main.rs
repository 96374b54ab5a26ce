//! `parallax dataset` and `verify` through the real binary: the cost
//! estimate, round trips, resume and repair, signals, shards from a batch
//! engine's environment, baseline folders and traceable seeds.

#[path = "../common/mod.rs"]
mod common;

mod baseline_folders;
mod estimate;
mod roundtrip;
mod seeds_traceable;
mod shard_env;
mod signals;
mod verify_repair;
