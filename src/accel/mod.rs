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
//!
//! Two-level instancing: a prototype is a list of triangle meshes in its own
//! local frame, stored once; an instance places one prototype by an affine
//! render_from_local map. A hit on an instance carries `inst_id` (the
//! instance's index) with `geom_id`/`prim_id` naming the mesh and triangle
//! inside the prototype; `t` is the render-space ray's parameter (affine maps
//! preserve it) and `n_geo` is in render space. Flat hits have
//! `inst_id == NO_INSTANCE`. (`instances.rs` is the layer the pure-Rust
//! backends share.)

mod brute;
mod bvh;
mod bvh_build;
#[cfg(feature = "embree")]
mod embree;
#[cfg(feature = "embree")]
mod embree_cache;
mod instances;
mod prim;
mod soup;

use std::fmt;
use std::str::FromStr;

use glam::{Affine3A, Vec3, Vec4};

pub use crate::geometry::Ray;
pub use brute::BruteAccel;
pub use bvh::BvhAccel;
#[cfg(feature = "embree")]
pub use embree::EmbreeAccel;
#[cfg(feature = "embree")]
pub use embree_cache::PrototypeCache;

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
    /// Geometric normal, not normalised, any orientation; render space.
    pub n_geo: Vec3,
    /// Index of the instance hit, or [`NO_INSTANCE`] for flat geometry.
    pub inst_id: u32,
}

/// `Hit::inst_id` of a hit on flat (not instanced) geometry.
pub const NO_INSTANCE: u32 = u32::MAX;

impl InstanceRef {
    /// The map of winding normals from local to render space: the inverse
    /// transpose times the sign of the determinant, so a mirrored instance
    /// reports the normal its flattened triangles' winding gives.
    pub fn normal_to_render(&self) -> glam::Mat3A {
        let m = self.local_from_render.matrix3;
        let sign = if m.determinant() < 0.0 { -1.0 } else { 1.0 };
        m.transpose() * sign
    }
}

/// One placement of a prototype.
#[derive(Clone, Copy, Debug)]
pub struct InstanceRef {
    /// Index into `AccelGeometry::prototypes`.
    pub prototype: u32,
    /// Local → render space (rounded from the scene's f64 map).
    pub render_from_local: Affine3A,
    /// Render → local space (the f64 inverse, rounded).
    pub local_from_render: Affine3A,
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
    /// Prototypes: each a list of triangle meshes in its local frame.
    pub prototypes: Vec<Vec<TriMeshRef<'a>>>,
    /// Placements of the prototypes; `Hit::inst_id` = index.
    pub instances: &'a [InstanceRef],
}

impl<'a> AccelGeometry<'a> {
    /// Geometry id used for the sphere set.
    pub fn sphere_geom_id(&self) -> u32 {
        self.meshes.len() as u32
    }

    /// Total primitive count (triangles plus spheres), prototypes counted once.
    pub fn primitive_count(&self) -> usize {
        let proto: usize = self
            .prototypes
            .iter()
            .flatten()
            .map(|m| m.triangles.len())
            .sum();
        self.meshes.iter().map(|m| m.triangles.len()).sum::<usize>() + self.spheres.len() + proto
    }

    /// The flat part (meshes and spheres) as a geometry of its own.
    pub(crate) fn flat(&self) -> AccelGeometry<'a> {
        AccelGeometry {
            meshes: self.meshes.clone(),
            spheres: self.spheres,
            ..AccelGeometry::default()
        }
    }

    /// Prototype `p` as a geometry of its own (its meshes, no spheres).
    pub(crate) fn prototype(&self, p: usize) -> AccelGeometry<'a> {
        AccelGeometry {
            meshes: self.prototypes[p].clone(),
            ..AccelGeometry::default()
        }
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
    /// [`Accel::intersect`] for shading rays: a backend may answer from a faster
    /// structure that is not watertight (a ray aimed exactly at a shared edge
    /// may slip through), which only costs a path a rare, unbiased-looking
    /// miss. Ground truth never calls it.
    fn intersect_shading(&self, ray: &Ray) -> Option<Hit> {
        self.intersect(ray)
    }
    /// [`Accel::occluded`] for shading rays (see [`Accel::intersect_shading`]).
    fn occluded_shading(&self, ray: &Ray) -> bool {
        self.occluded(ray)
    }
    /// [`Accel::intersect_batch`] for shading rays (see [`Accel::intersect_shading`]).
    fn intersect_batch_shading(&self, rays: &[Ray], hits: &mut [Option<Hit>]) {
        self.intersect_batch(rays, hits)
    }
    /// [`Accel::occluded_batch`] for shading rays (see [`Accel::intersect_shading`]).
    fn occluded_batch_shading(&self, rays: &[Ray], out: &mut [bool]) {
        for (r, o) in rays.iter().zip(out.iter_mut()) {
            *o = self.occluded_shading(r);
        }
    }
}

/// The view of an accelerator the path pass traces with: every query goes to
/// the backend's shading variant ([`Accel::intersect_shading`] and friends),
/// so a watertight accelerator and its faster twin are one object.
#[derive(Clone, Copy, Debug)]
pub struct ShadingAccel<'a, A>(pub &'a A);

impl<A: Accel> Accel for ShadingAccel<'_, A> {
    #[inline]
    fn intersect(&self, ray: &Ray) -> Option<Hit> {
        self.0.intersect_shading(ray)
    }

    #[inline]
    fn occluded(&self, ray: &Ray) -> bool {
        self.0.occluded_shading(ray)
    }

    fn intersect_batch(&self, rays: &[Ray], hits: &mut [Option<Hit>]) {
        self.0.intersect_batch_shading(rays, hits)
    }

    fn occluded_batch(&self, rays: &[Ray], out: &mut [bool]) {
        self.0.occluded_batch_shading(rays, out)
    }

    fn backend_name(&self) -> &'static str {
        self.0.backend_name()
    }
}

/// Which traversal backend to build.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Backend {
    /// Embree 3 (feature `embree`).
    Embree,
    /// The pure-Rust binned-SAH BVH.
    Bvh,
    /// Linear scan over every primitive (reference for tests).
    Brute,
}

impl Backend {
    /// Embree when the `embree` feature is compiled in, else the BVH.
    pub fn default_backend() -> Backend {
        if cfg!(feature = "embree") {
            Backend::Embree
        } else {
            Backend::Bvh
        }
    }

    /// The name used on the command line and in logs.
    pub fn name(self) -> &'static str {
        match self {
            Backend::Embree => "embree",
            Backend::Bvh => "bvh",
            Backend::Brute => "brute",
        }
    }
}

impl fmt::Display for Backend {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Backend {
    type Err = AccelError;

    fn from_str(s: &str) -> Result<Backend, AccelError> {
        match s {
            "embree" => Ok(Backend::Embree),
            "bvh" => Ok(Backend::Bvh),
            "brute" => Ok(Backend::Brute),
            other => Err(AccelError::UnknownBackend(other.to_string())),
        }
    }
}

/// Why an accelerator could not be built.
#[derive(Clone, Debug, PartialEq)]
pub enum AccelError {
    /// A backend name that is not "embree", "bvh" or "brute".
    UnknownBackend(String),
    /// Embree was requested but the crate was built without feature `embree`.
    EmbreeUnavailable,
    /// A triangle references a vertex past the end of its mesh.
    IndexOutOfRange {
        /// Mesh index.
        geom_id: u32,
        /// Triangle index within the mesh.
        prim_id: u32,
    },
    /// A vertex position, sphere centre or radius is NaN/infinite, or a radius is negative.
    InvalidGeometry {
        /// Geometry id (mesh index or the sphere set's id).
        geom_id: u32,
        /// Vertex index (meshes) or sphere index.
        index: u32,
    },
    /// The backend itself failed (message from the library).
    Backend(String),
}

impl fmt::Display for AccelError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            AccelError::UnknownBackend(s) => {
                write!(
                    f,
                    "unknown accelerator backend {s:?} (expected embree, bvh or brute)"
                )
            }
            AccelError::EmbreeUnavailable => {
                write!(f, "the embree backend was requested but parallax was built without feature `embree`")
            }
            AccelError::IndexOutOfRange { geom_id, prim_id } => {
                write!(
                    f,
                    "mesh {geom_id}, triangle {prim_id}: vertex index out of range"
                )
            }
            AccelError::InvalidGeometry { geom_id, index } => {
                write!(
                    f,
                    "geometry {geom_id}, element {index}: non-finite position or invalid radius"
                )
            }
            AccelError::Backend(msg) => f.write_str(msg),
        }
    }
}

impl std::error::Error for AccelError {}

/// Checks what every backend relies on: triangle indices in range (Embree does
/// not bounds-check), finite positions, finite non-negative radii.
pub fn validate_geometry(geo: &AccelGeometry) -> Result<(), AccelError> {
    for (p, proto) in geo.prototypes.iter().enumerate() {
        validate_meshes(proto).map_err(|e| match e {
            AccelError::InvalidGeometry { geom_id, index } => AccelError::Backend(format!(
                "prototype {p}, mesh {geom_id}, vertex {index}: non-finite position"
            )),
            AccelError::IndexOutOfRange { geom_id, prim_id } => AccelError::Backend(format!(
                "prototype {p}, mesh {geom_id}, triangle {prim_id}: vertex index out of range"
            )),
            other => other,
        })?;
    }
    for (i, inst) in geo.instances.iter().enumerate() {
        let finite = inst.render_from_local.is_finite() && inst.local_from_render.is_finite();
        if inst.prototype as usize >= geo.prototypes.len() || !finite {
            return Err(AccelError::Backend(format!(
                "instance {i}: prototype {} of {} or a non-finite transform",
                inst.prototype,
                geo.prototypes.len()
            )));
        }
    }
    validate_meshes(&geo.meshes)?;
    if let Some(index) = geo.spheres.iter().position(|s| !s.is_finite() || s.w < 0.0) {
        return Err(AccelError::InvalidGeometry {
            geom_id: geo.sphere_geom_id(),
            index: index as u32,
        });
    }
    Ok(())
}

fn validate_meshes(meshes: &[TriMeshRef]) -> Result<(), AccelError> {
    for (geom_id, mesh) in meshes.iter().enumerate() {
        let geom_id = geom_id as u32;
        if let Some(index) = mesh.positions.iter().position(|p| !p.is_finite()) {
            return Err(AccelError::InvalidGeometry {
                geom_id,
                index: index as u32,
            });
        }
        let n = mesh.positions.len();
        if let Some(prim_id) = mesh
            .triangles
            .iter()
            .position(|t| t.iter().any(|&i| i as usize >= n))
        {
            return Err(AccelError::IndexOutOfRange {
                geom_id,
                prim_id: prim_id as u32,
            });
        }
    }
    Ok(())
}

/// The accelerator the scene stores: one variant per backend, so hot loops
/// dispatch with a match instead of a virtual call.
#[derive(Debug)]
pub enum AnyAccel {
    /// Embree 3.
    #[cfg(feature = "embree")]
    Embree(EmbreeAccel),
    /// Pure-Rust BVH.
    Bvh(BvhAccel),
    /// Brute-force reference.
    Brute(BruteAccel),
}

/// Forwards one expression to whichever backend `$self` holds.
macro_rules! dispatch {
    ($self:expr, $a:ident => $e:expr) => {
        match $self {
            #[cfg(feature = "embree")]
            AnyAccel::Embree($a) => $e,
            AnyAccel::Bvh($a) => $e,
            AnyAccel::Brute($a) => $e,
        }
    };
}

impl Accel for AnyAccel {
    #[inline]
    fn intersect(&self, ray: &Ray) -> Option<Hit> {
        dispatch!(self, a => a.intersect(ray))
    }

    #[inline]
    fn occluded(&self, ray: &Ray) -> bool {
        dispatch!(self, a => a.occluded(ray))
    }

    fn intersect_batch(&self, rays: &[Ray], hits: &mut [Option<Hit>]) {
        dispatch!(self, a => a.intersect_batch(rays, hits))
    }

    fn occluded_batch(&self, rays: &[Ray], out: &mut [bool]) {
        dispatch!(self, a => a.occluded_batch(rays, out))
    }

    fn backend_name(&self) -> &'static str {
        dispatch!(self, a => a.backend_name())
    }

    #[inline]
    fn intersect_shading(&self, ray: &Ray) -> Option<Hit> {
        dispatch!(self, a => a.intersect_shading(ray))
    }

    #[inline]
    fn occluded_shading(&self, ray: &Ray) -> bool {
        dispatch!(self, a => a.occluded_shading(ray))
    }

    fn intersect_batch_shading(&self, rays: &[Ray], hits: &mut [Option<Hit>]) {
        dispatch!(self, a => a.intersect_batch_shading(rays, hits))
    }

    fn occluded_batch_shading(&self, rays: &[Ray], out: &mut [bool]) {
        dispatch!(self, a => a.occluded_batch_shading(rays, out))
    }
}

/// Validates `geo` and builds the requested backend over it. The result owns
/// copies of the data (it does not borrow `geo`).
pub fn build_accel(backend: Backend, geo: &AccelGeometry) -> Result<AnyAccel, AccelError> {
    validate_geometry(geo)?;
    match backend {
        #[cfg(feature = "embree")]
        Backend::Embree => Ok(AnyAccel::Embree(EmbreeAccel::build(geo)?)),
        #[cfg(not(feature = "embree"))]
        Backend::Embree => Err(AccelError::EmbreeUnavailable),
        Backend::Bvh => Ok(AnyAccel::Bvh(BvhAccel::build(geo))),
        Backend::Brute => Ok(AnyAccel::Brute(BruteAccel::build(geo))),
    }
}

/// What accelerator builds keep for the next build of the same static
/// world: Embree's committed prototype scenes (`PrototypeCache`); the
/// pure-Rust backends keep nothing. Send + Sync; one build at a time uses it.
#[derive(Debug, Default)]
pub struct AccelCache {
    #[cfg(feature = "embree")]
    embree: PrototypeCache,
}

impl AccelCache {
    /// Prototype scenes held (Embree; 0 otherwise).
    pub fn prototypes(&self) -> usize {
        #[cfg(feature = "embree")]
        return self.embree.len();
        #[cfg(not(feature = "embree"))]
        0
    }

    /// Prototype scenes the last build took from the cache (Embree; 0 otherwise).
    pub fn reused(&self) -> usize {
        #[cfg(feature = "embree")]
        return self.embree.reused();
        #[cfg(not(feature = "embree"))]
        0
    }
}

/// As [`build_accel`], reusing what `cache` holds of earlier builds (the
/// result is the one [`build_accel`] gives); `shading_twin` as in
/// [`EmbreeAccel::build_with`].
pub fn build_accel_cached(
    backend: Backend,
    geo: &AccelGeometry,
    shading_twin: bool,
    cache: &AccelCache,
) -> Result<AnyAccel, AccelError> {
    #[cfg(feature = "embree")]
    if backend == Backend::Embree {
        // `build_cached` validates the geometry itself.
        let a = EmbreeAccel::build_cached(geo, shading_twin, &cache.embree)?;
        return Ok(AnyAccel::Embree(a));
    }
    let _ = (shading_twin, cache);
    build_accel(backend, geo)
}
