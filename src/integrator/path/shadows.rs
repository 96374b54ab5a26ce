//! A vertex's next-event shadow rays held back so a chunk of paths can
//! trace the coherent ones (towards the sun) together as packets.

use glam::Vec3;

use super::MAX_SHADOW;
use crate::accel::{Accel, Ray};

/// A vertex's NEE shadow rays, each with the contribution (throughput
/// included) it adds to the path's radiance when unoccluded. Rays towards a
/// directional light are marked coherent: a chunk of paths may trace those
/// together in packets and record the answers (`set_occluded`) before the
/// set is resolved.
pub(in crate::integrator) struct PendingShadows {
    len: usize,
    items: [(Ray, Vec3); MAX_SHADOW],
    /// Bit k: item k goes towards a directional light.
    coherent: u8,
    /// Bit k: item k's occlusion is already known ...
    known: u8,
    /// ... and bit k says whether it is occluded.
    blocked: u8,
}

impl PendingShadows {
    /// No pending shadow rays.
    pub fn new() -> Self {
        PendingShadows {
            len: 0,
            items: [(Ray::new(Vec3::ZERO, Vec3::Z), Vec3::ZERO); MAX_SHADOW],
            coherent: 0,
            known: 0,
            blocked: 0,
        }
    }

    pub(super) fn push(&mut self, shadow: Ray, contribution: Vec3, coherent: bool) {
        self.items[self.len] = (shadow, contribution);
        self.coherent |= (coherent as u8) << self.len;
        self.len += 1;
    }

    /// The coherent rays not yet answered, with their item index.
    pub(super) fn coherent_rays(&self) -> impl Iterator<Item = (usize, &Ray)> {
        let todo = self.coherent & !self.known;
        self.items[..self.len]
            .iter()
            .enumerate()
            .filter(move |(k, _)| todo >> k & 1 != 0)
            .map(|(k, (ray, _))| (k, ray))
    }

    /// Records whether item `k`'s shadow ray is occluded.
    pub(super) fn set_occluded(&mut self, k: usize, occluded: bool) {
        self.known |= 1 << k;
        self.blocked = self.blocked & !(1 << k) | (occluded as u8) << k;
    }

    /// Tests every pending shadow ray in order (unless already answered) and
    /// adds the unoccluded contributions to `l`; leaves the set empty.
    /// Returns the part added by coherent rays (the sun's), which the
    /// denoiser keeps out of the direct light it filters.
    pub fn resolve(&mut self, accel: &impl Accel, l: &mut Vec3) -> Vec3 {
        let mut coherent = Vec3::ZERO;
        for (k, (shadow, contribution)) in self.items[..self.len].iter().enumerate() {
            let occluded = if self.known >> k & 1 != 0 {
                self.blocked >> k & 1 != 0
            } else {
                accel.occluded(shadow)
            };
            if !occluded {
                *l += *contribution;
                if self.coherent >> k & 1 != 0 {
                    coherent += *contribution;
                }
            }
        }
        self.len = 0;
        self.coherent = 0;
        self.known = 0;
        self.blocked = 0;
        coherent
    }
}
