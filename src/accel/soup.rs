//! The flat primitive list the pure-Rust backends traverse, and the per-ray
//! closest-hit search state they share.
//!
//! Every flat triangle and sphere of an `AccelGeometry` (instances are
//! `instances.rs`'s) becomes one `PackedPrim`
//! holding its own vertex positions (no index indirection in the hot loop) and
//! its (geometry id, primitive id) from the `mod.rs` conventions. The closest
//! search keeps `tmax` shrinking as hits are found, so later tests are cheaper.

use glam::{Vec3, Vec4};

use super::prim::{intersect_sphere, intersect_triangle, triangle_normal, TriHit, WatertightRay};
use super::{AccelGeometry, Hit, Ray};

/// One primitive with its data inlined: a triangle (`p` = its three vertices)
/// or a sphere (`p[0]` = centre, `p[1].x` = radius).
#[derive(Clone, Copy, Debug)]
pub(crate) struct PackedPrim {
    /// Vertex positions, or centre and radius for a sphere.
    pub p: [Vec3; 3],
    /// Geometry id (mesh index, or the sphere set's id).
    pub geom_id: u32,
    /// Primitive id within the geometry.
    pub prim_id: u32,
    /// Whether this is a sphere.
    pub is_sphere: bool,
}

impl PackedPrim {
    /// Axis-aligned bounds (min, max).
    pub fn bounds(&self) -> (Vec3, Vec3) {
        if self.is_sphere {
            let r = Vec3::splat(self.p[1].x);
            (self.p[0] - r, self.p[0] + r)
        } else {
            let [a, b, c] = self.p;
            (a.min(b).min(c), a.max(b).max(c))
        }
    }

    fn sphere(&self) -> Vec4 {
        self.p[0].extend(self.p[1].x)
    }
}

/// Flattens `geo` into packed primitives in id order (meshes, then spheres).
/// Indices must already be validated.
pub(crate) fn pack_primitives(geo: &AccelGeometry) -> Vec<PackedPrim> {
    let mut prims = Vec::with_capacity(geo.flat().primitive_count());
    for (geom_id, mesh) in geo.meshes.iter().enumerate() {
        prims.extend(
            mesh.triangles
                .iter()
                .enumerate()
                .map(|(prim_id, tri)| PackedPrim {
                    p: tri.map(|i| mesh.positions[i as usize]),
                    geom_id: geom_id as u32,
                    prim_id: prim_id as u32,
                    is_sphere: false,
                }),
        );
    }
    let sphere_geom_id = geo.sphere_geom_id();
    prims.extend(
        geo.spheres
            .iter()
            .enumerate()
            .map(|(prim_id, s)| PackedPrim {
                p: [s.truncate(), Vec3::new(s.w, 0.0, 0.0), Vec3::ZERO],
                geom_id: sphere_geom_id,
                prim_id: prim_id as u32,
                is_sphere: true,
            }),
    );
    prims
}

/// What was hit so far: the triangle barycentrics (zero for spheres).
#[derive(Clone, Copy, Debug)]
struct BestHit {
    hit: TriHit,
    prim: PackedPrim,
}

/// Closest-hit search over any sequence of primitives for one ray.
pub(crate) struct ClosestSearch {
    ray: Ray,
    wray: WatertightRay,
    best: Option<BestHit>,
}

impl ClosestSearch {
    /// Starts a search for `ray`.
    #[inline]
    pub fn new(ray: &Ray) -> Self {
        ClosestSearch {
            ray: *ray,
            wray: WatertightRay::new(ray),
            best: None,
        }
    }

    /// Current upper bound on t (shrinks with every accepted hit).
    #[inline]
    pub fn tmax(&self) -> f32 {
        self.wray.tmax
    }

    /// Tests one primitive and keeps it if it is at least as close as the best.
    #[inline]
    pub fn test(&mut self, prim: &PackedPrim) {
        let hit = if prim.is_sphere {
            let ray = Ray {
                tmax: self.wray.tmax,
                ..self.ray
            };
            intersect_sphere(&ray, prim.sphere()).map(|t| TriHit { t, u: 0.0, v: 0.0 })
        } else {
            intersect_triangle(&self.wray, prim.p[0], prim.p[1], prim.p[2])
        };
        if let Some(hit) = hit {
            self.wray.tmax = hit.t;
            self.best = Some(BestHit { hit, prim: *prim });
        }
    }

    /// The closest hit found, with its geometric normal.
    #[inline]
    pub fn finish(self) -> Option<Hit> {
        self.best.map(|b| {
            let n_geo = if b.prim.is_sphere {
                // Embree's sphere normal: hit point minus centre, unnormalised.
                self.ray.at(b.hit.t) - b.prim.p[0]
            } else {
                triangle_normal(b.prim.p[0], b.prim.p[1], b.prim.p[2])
            };
            Hit {
                t: b.hit.t,
                geom_id: b.prim.geom_id,
                prim_id: b.prim.prim_id,
                u: b.hit.u,
                v: b.hit.v,
                n_geo,
                inst_id: super::NO_INSTANCE,
            }
        })
    }
}

/// Any-hit test of one primitive against a prepared ray.
#[inline]
pub(crate) fn occludes(ray: &Ray, wray: &WatertightRay, prim: &PackedPrim) -> bool {
    if prim.is_sphere {
        intersect_sphere(ray, prim.sphere()).is_some()
    } else {
        intersect_triangle(wray, prim.p[0], prim.p[1], prim.p[2]).is_some()
    }
}
