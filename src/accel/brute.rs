//! Brute-force reference backend: every ray is tested against every primitive
//! with the same routines as the BVH (`prim.rs`), so parity tests isolate the
//! hierarchy. O(n) per ray — tests and tiny scenes only.

use super::instances::InstanceLayer;
use super::prim::WatertightRay;
use super::soup::{occludes, pack_primitives, ClosestSearch, PackedPrim};
use super::{Accel, AccelGeometry, Hit, Ray};

/// Linear scan over all primitives.
#[derive(Clone, Debug)]
pub struct BruteAccel {
    prims: Vec<PackedPrim>,
    instances: InstanceLayer<BruteAccel>,
}

impl BruteAccel {
    /// Copies the primitives of `geo` (indices must be validated, see `build_accel`).
    pub fn build(geo: &AccelGeometry) -> Self {
        BruteAccel {
            prims: pack_primitives(geo),
            instances: InstanceLayer::build(geo, false, BruteAccel::build),
        }
    }
}

impl Accel for BruteAccel {
    fn intersect(&self, ray: &Ray) -> Option<Hit> {
        let mut search = ClosestSearch::new(ray);
        for prim in &self.prims {
            search.test(prim);
        }
        let mut best = search.finish();
        self.instances.intersect(ray, &mut best);
        best
    }

    fn occluded(&self, ray: &Ray) -> bool {
        let wray = WatertightRay::new(ray);
        self.prims.iter().any(|p| occludes(ray, &wray, p)) || self.instances.occluded(ray)
    }

    fn backend_name(&self) -> &'static str {
        "brute"
    }
}
