//! The accelerator contract: closest-hit and any-hit queries over triangles and
//! spheres in render space (f32), single and batched.
//!
//! This is the only boundary that knows about traversal backends (Mitsuba 3's
//! `accel.h` split): `embree.rs` (Debian's Embree 3.13.5, feature `embree`),
//! `bvh.rs` (pure-Rust BVH, always built) and `brute.rs` (reference for parity
//! tests). Everything above sees `Ray` in and `Hit` out.
//!
//! Conventions: geometry ids `0..meshes.len()` are the triangle meshes in the
//! order given; all spheres together form geometry id `meshes.len()`, with the
//! sphere index as primitive id. Barycentrics follow Embree: `u` weights vertex
//! 1, `v` weights vertex 2, `1 − u − v` weights vertex 0.

use glam::{Vec3, Vec4};

pub use crate::geometry::Ray;

/// A closest-hit record: cheap to copy; the scene turns it into a surface
/// interaction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Ray parameter of the hit (units of the ray's `d`).
    pub t: f32,
    /// Geometry id (mesh index, or `meshes.len()` for the sphere set).
    pub geom_id: u32,
    /// Primitive id within the geometry (triangle or sphere index).
    pub prim_id: u32,
    /// Barycentric weight of vertex 1 (0 for spheres).
    pub u: f32,
    /// Barycentric weight of vertex 2 (0 for spheres).
    pub v: f32,
    /// Geometric normal, not normalised, any orientation.
    pub n_geo: Vec3,
}

/// One triangle mesh as the accelerator sees it.
#[derive(Clone, Copy, Debug)]
pub struct TriMeshRef<'a> {
    /// Vertex positions, render space.
    pub positions: &'a [Vec3],
    /// Vertex indices, three per triangle.
    pub triangles: &'a [[u32; 3]],
}

/// Everything an accelerator is built over.
#[derive(Clone, Debug, Default)]
pub struct AccelGeometry<'a> {
    /// Triangle meshes; geometry id = index.
    pub meshes: Vec<TriMeshRef<'a>>,
    /// Spheres as (centre xyz, radius w), render space; geometry id `meshes.len()`.
    pub spheres: &'a [Vec4],
}

impl AccelGeometry<'_> {
    /// Geometry id used for the sphere set.
    pub fn sphere_geom_id(&self) -> u32 {
        self.meshes.len() as u32
    }

    /// Total primitive count (triangles plus spheres).
    pub fn primitive_count(&self) -> usize {
        self.meshes.iter().map(|m| m.triangles.len()).sum::<usize>() + self.spheres.len()
    }
}

/// Query interface shared by every backend.
pub trait Accel: Send + Sync {
    /// Closest hit with `ray.tmin <= t <= ray.tmax`, if any.
    fn intersect(&self, ray: &Ray) -> Option<Hit>;
    /// Whether anything is hit with `ray.tmin <= t <= ray.tmax`.
    fn occluded(&self, ray: &Ray) -> bool;
    /// Closest hits for many rays (`hits.len() == rays.len()`); backends may use packets.
    fn intersect_batch(&self, rays: &[Ray], hits: &mut [Option<Hit>]) {
        for (r, h) in rays.iter().zip(hits.iter_mut()) {
            *h = self.intersect(r);
        }
    }
    /// Any-hit for many rays (`out.len() == rays.len()`).
    fn occluded_batch(&self, rays: &[Ray], out: &mut [bool]) {
        for (r, o) in rays.iter().zip(out.iter_mut()) {
            *o = self.occluded(r);
        }
    }
    /// Short backend name for logs and bench output ("embree", "bvh", "brute").
    fn backend_name(&self) -> &'static str;
}
