//! The point-independent choice of one local light (half by power, half
//! uniform) for equiangular sampling in a medium: the same number gives the
//! same light at every point of a segment, so the light is chosen once and
//! only sampled at the points.

use glam::{Vec2, Vec3};

use super::{sample_entry, Entry, Light, LightSet};
use crate::light::LightSample;
use crate::scene::Scene;

/// A local light chosen by [`LightSet::select_global`].
#[derive(Clone, Copy, Debug)]
pub struct GlobalLight {
    /// Index among the local lights.
    idx: usize,
    /// Its selection pmf.
    pmf: f32,
}

impl LightSet {
    /// Chooses one local light with `u_select` ∈ [0, 1), independently of
    /// any point; None when there are none or it cannot be chosen.
    pub fn select_global(&self, u_select: f32) -> Option<GlobalLight> {
        if self.entries.is_empty() {
            return None;
        }
        let idx = self.select(u_select);
        let pmf = self.pmf[idx];
        (pmf > 0.0).then_some(GlobalLight { idx, pmf })
    }

    /// Position of a chosen point or spot light (None for emitters with
    /// an extent): where equiangular sampling centres its distances,
    /// whatever a spot's cone lights.
    pub fn delta_position(&self, light: GlobalLight) -> Option<Vec3> {
        match self.entries[light.idx] {
            Entry::Explicit(Light::Point { p, .. } | Light::Spot { p, .. }) => Some(p),
            _ => None,
        }
    }

    /// Samples a chosen light as seen from `p` (its pdf includes the
    /// selection pmf).
    pub fn sample_chosen(
        &self,
        scene: &Scene,
        light: GlobalLight,
        p: Vec3,
        u: Vec2,
    ) -> Option<LightSample> {
        sample_entry(
            scene,
            &self.emitters,
            &self.entries[light.idx],
            light.pmf,
            p,
            u,
        )
    }
}
