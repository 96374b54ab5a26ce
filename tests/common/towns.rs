//! The shipped towns: their names and parameter files.

use std::path::{Path, PathBuf};

use parallax::town::{load_town, TownDesc};

/// Every town shipped in `scenes/`.
pub const TOWNS: [&str; 8] = [
    "town01", "town02", "town03", "town04", "town05", "town06", "town07", "town10",
];

/// `scenes/NAME.toml` of the repository.
pub fn town_file(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("scenes/{name}.toml"))
}

/// The parsed town file `scenes/NAME.toml` (panics with the loader's message).
pub fn town(name: &str) -> TownDesc {
    load_town(&town_file(name)).unwrap_or_else(|e| panic!("{e}"))
}
