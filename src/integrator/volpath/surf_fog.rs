//! Bookkeeping of `DenoiseSample::l_surf` (issue 4): the part of a split
//! camera sample whose first event is a Lambertian surface vertex x1 and
//! whose next event is a medium scatter. Its mean is β(x1)·ρ(x1)·E_fog/π
//! with E_fog the fog-scattered irradiance at x1, smooth over surfaces, so
//! the denoiser (`crate::denoise`, its surface component) filters the
//! ratio l_surf / (β·ρ).

use glam::Vec3;

/// The split's state along one path.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct SurfFog {
    /// β(x1)·ρ(x1) once x1 is a Lambertian first vertex.
    pub rho: Vec3,
    /// The next segment after x1 is the one to watch.
    armed: bool,
    /// Path radiance when that segment began.
    from: Option<Vec3>,
    /// Path radiance when it ended without a collision.
    to: Option<Vec3>,
}

impl SurfFog {
    /// Records the first surface vertex: `rho` is β·albedo when x1 is
    /// Lambertian (None: not tracked). Call before the next segment starts.
    pub fn at_first_vertex(&mut self, rho: Option<Vec3>) {
        if let Some(r) = rho {
            self.rho = r;
            self.armed = true;
        }
    }

    /// At the start of a segment with the path radiance `l`; whether this
    /// is the segment right after x1.
    pub fn segment_start(&mut self, l: Vec3) -> bool {
        let after_x1 = std::mem::take(&mut self.armed);
        if after_x1 {
            self.from = Some(l);
        }
        after_x1
    }

    /// The segment after x1 reached its surface or the sky without a
    /// collision: what follows is not fog light on x1.
    pub fn segment_passed(&mut self, l: Vec3) {
        self.to = Some(l);
    }

    /// The fog light on x1 given the path's final radiance `l`.
    pub fn l_surf(&self, l: Vec3) -> Vec3 {
        self.from.map_or(Vec3::ZERO, |a| self.to.unwrap_or(l) - a)
    }
}
