//! TEMPORARY stub (replaced by the film helper's module at merge).
use glam::Vec3;
/// Linear radiance film.
#[derive(Clone, Debug)]
pub struct Film {
    /// Width.
    pub width: u32,
    /// Height.
    pub height: u32,
    /// Pixels.
    pub rgb: Vec<Vec3>,
}
/// Exposure.
pub fn auto_exposure(_f: &Film) -> f32 {
    1.0
}
