//! How much next-event estimation spends on the local lights, from their
//! share of the emitted power: how many candidates a vertex resamples them
//! from, and the probability that a vertex samples them at all (first
//! vertex and later ones apart). Skipping keeps the estimate's mean: the
//! selection pmfs carry the probability.

/// Local lights are resampled from this many candidates at a path's first
/// vertex where they matter (`LightSet::local_candidates`): town03 and
/// town10 night gained about 0.5 and 0.25 dB over 2 candidates at equal CPU (the
/// extra tree walks spent on samples instead).
pub const LOCAL_CANDIDATES: usize = 8;
/// Candidates at the vertices after a path's first where the local lights
/// matter: their light reaches the image through a bounce and the indirect
/// filter, and 8 there cost as many tree walks as the first vertex's for
/// little of its gain.
pub const LOCAL_CANDIDATES_DEEP: usize = 2;

/// Share of the emitted power from which local lights are resampled from
/// `LOCAL_CANDIDATES` / `LOCAL_CANDIDATES_DEEP` (night: nearly all of it; under a storm's overcast
/// they bring 8 %, where the extra BVH walks per vertex cost more than the
/// lamps' noise).
const LOCAL_SHARE_FOR_RIS: f32 = 0.25;
/// Share below which a path's first vertex samples the local lights only
/// with probability share / this (at least `MIN_P_LOCAL`): by day the sun
/// and sky outshine every lamp by 10³–10⁴, and a light BVH walk and shadow
/// ray at every vertex cost time (a fifth of a foggy frame's) for light
/// nobody sees.
const LOCAL_SHARE_FULL: f32 = 0.01;
/// `LOCAL_SHARE_FULL` for the vertices after a path's first: their light
/// reaches the image through one more bounce (and the indirect filter), so
/// the lamps' extra noise there costs the image less than their tree walks
/// and shadow rays cost the frame (a storm's lamps, 8 % of the power, are
/// sampled at a third of those vertices).
const LOCAL_SHARE_FULL_DEEP: f32 = 0.25;
/// Least probability of sampling the local lights at a vertex.
const MIN_P_LOCAL: f32 = 0.1;

/// The local lights' sampling budget.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct LocalBudget {
    /// Candidates at a path's first vertex (1 ..= `LOCAL_CANDIDATES`).
    pub candidates: usize,
    /// Candidates at every vertex after a path's first.
    pub candidates_deep: usize,
    /// Probability that a path's first vertex samples a local light.
    pub p_first: f32,
    /// The same for every later vertex (≤ `p_first`).
    pub p_deep: f32,
}

impl LocalBudget {
    /// The budget for local lights bringing `share` of the emitted power.
    /// `skips`: whether vertices may skip them (the light-tree selection;
    /// the point-independent kinds stay as they were for comparisons).
    /// `same_at_depth`: one probability for every vertex (escaping rays
    /// weigh a local sun by one pmf, whatever vertex they left).
    pub fn new(share: f32, skips: bool, same_at_depth: bool) -> LocalBudget {
        let p_for = |share_full: f32| {
            if skips {
                (share / share_full).clamp(MIN_P_LOCAL, 1.0)
            } else {
                1.0
            }
        };
        let p_first = p_for(LOCAL_SHARE_FULL);
        let resampled = share >= LOCAL_SHARE_FOR_RIS;
        LocalBudget {
            candidates: if resampled { LOCAL_CANDIDATES } else { 1 },
            candidates_deep: if resampled { LOCAL_CANDIDATES_DEEP } else { 1 },
            p_first,
            p_deep: if same_at_depth {
                p_first
            } else {
                p_for(LOCAL_SHARE_FULL_DEEP).min(p_first)
            },
        }
    }

    /// Probability that a vertex after `bounce` scattering events samples
    /// the local lights.
    pub fn p_local(&self, bounce: u32) -> f32 {
        if bounce == 0 {
            self.p_first
        } else {
            self.p_deep
        }
    }
}
