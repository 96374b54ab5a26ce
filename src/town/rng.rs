//! The town generator's random streams: the sampler's keyed `Rng`, and the
//! purpose tags that keep the streams of the generator's parts apart.

pub use crate::sampler::rng::Rng;

/// Purpose tags keeping the streams of different generators apart.
pub mod tag {
    /// Buildings of a block.
    pub const BLOCK: u64 = 1;
    /// Vegetation of a block or street.
    pub const TREES: u64 = 2;
    /// One traffic slot (occupancy, body type, paint).
    pub const SLOT: u64 = 3;
    /// The ego vehicle's lane and start.
    pub const EGO: u64 = 4;
    /// Street furniture.
    pub const FURNITURE: u64 = 5;
    /// Pedestrians.
    pub const PEDESTRIAN: u64 = 6;
    /// Lit windows of a building.
    pub const LIT_WINDOWS: u64 = 7;
    /// Pedestrians crossing at a junction.
    pub const CROSSER: u64 = 8;
    /// Background vehicles of a drive (start, body, moves).
    pub const TRAFFIC: u64 = 9;
    /// Cars parked along the kerbs.
    pub const PARKED: u64 = 10;
}
