//! The value checks of scene validation, each naming the scene file and the
//! key path: finite, positive, in a range, within the coordinate limit.
//! Numbers in messages are printed compactly (`desc::num`: `1e308`, not
//! 309 digits).

use std::path::Path;

use super::desc::num;
use super::load::{SceneError, SceneErrorKind};
use super::mesh::MAX_COORD_M;

/// Checks of values of one scene file.
pub(super) struct V<'a> {
    /// The scene file named in every error.
    pub file: &'a Path,
}

impl V<'_> {
    pub fn err(&self, key: impl Into<String>, msg: impl Into<String>) -> SceneError {
        SceneError::at(self.file, SceneErrorKind::Invalid, key, msg)
    }
    pub fn finite(&self, key: &str, v: &[f64]) -> Result<(), SceneError> {
        match v.iter().find(|x| !x.is_finite()) {
            Some(x) => Err(self.err(key, format!("value {x} is not a finite number"))),
            None => Ok(()),
        }
    }
    pub fn positive(&self, key: &str, v: &[f64]) -> Result<(), SceneError> {
        self.finite(key, v)?;
        match v.iter().find(|&&x| x <= 0.0) {
            Some(&x) => Err(self.err(key, format!("must be > 0, got {}", num(x)))),
            None => Ok(()),
        }
    }
    /// `v` in [lo, hi]; `hi = f64::MAX` means no upper limit.
    pub fn range(&self, key: &str, v: &[f64], lo: f64, hi: f64) -> Result<(), SceneError> {
        self.finite(key, v)?;
        let allowed = if hi == f64::MAX {
            format!("≥ {}", num(lo))
        } else {
            format!("in [{}, {}]", num(lo), num(hi))
        };
        match v.iter().find(|&&x| x < lo || x > hi) {
            Some(&x) => Err(self.err(key, format!("must be {allowed}, got {}", num(x)))),
            None => Ok(()),
        }
    }
    /// Positions, sizes and offsets: finite and within ±`MAX_COORD_M`, the
    /// limit OBJ vertices obey (beyond it f32 geometry loses all precision).
    pub fn coord(&self, key: &str, v: &[f64]) -> Result<(), SceneError> {
        self.finite(key, v)?;
        match v.iter().find(|x| x.abs() > MAX_COORD_M) {
            Some(&x) => Err(self.err(
                key,
                format!(
                    "{} is beyond the coordinate limit of ±{} m",
                    num(x),
                    num(MAX_COORD_M)
                ),
            )),
            None => Ok(()),
        }
    }
    /// Sizes and radii: > 0 and within the coordinate limit.
    pub fn length(&self, key: &str, v: &[f64]) -> Result<(), SceneError> {
        self.positive(key, v)?;
        self.coord(key, v)
    }
}
