//! Embree backend (Debian's Embree 3.13.5 through the `embree3` crate) — the
//! only file that names the binding (STYLE.md rule 3).
//!
//! One device and up to two scenes over the same geometries: triangle geometry
//! `i` for mesh `i` and one `SPHERE_POINT` geometry (float4 centre + radius)
//! with id `meshes.len()`, attached by id so Embree's ids are exactly the
//! `mod.rs` conventions. Data is copied once into Embree-owned buffers, so the
//! accelerator borrows nothing. The main scene is built with
//! `RTC_SCENE_FLAG_ROBUST` (watertight on shared edges) and answers every
//! ground-truth query; the optional shading twin is built without it (about a
//! third faster to traverse) and answers the `*_shading` queries of the path
//! pass, where a ray slipping through an edge costs one sample, not a GT pixel.
//! Single rays use `rtcIntersect1`/`rtcOccluded1` with an incoherent context;
//! batches (rows of camera rays, occlusion segments from one camera centre) go
//! through 8-wide packets (`rtcIntersect8`/`rtcOccluded8`) with a coherent
//! context and a valid mask for the tail.
//!
//! Instances: each prototype is a committed child scene of its own (robust,
//! and a non-robust twin for shading), placed by `INSTANCE` geometries with
//! ids `meshes.len() + 1 + k` for instance k. Embree reports an instanced
//! hit's `Ng` in the prototype's frame; `Decode` maps it to render space
//! with the inverse transpose of the instance transform.

use embree3::{
    BufferUsage, BuildQuality, Device, Format, Geometry, GeometryKind, Hit8, IntersectContext,
    Ray as RtcRay, Ray8, RayHit, RayHit8, Scene, SceneFlags, ValidMask, ValidMaskN, INVALID_ID,
};
use std::sync::Arc;

use glam::{Affine3A, Mat3A, Vec3};

use super::embree_cache::PrototypeCache;
use super::{validate_geometry, Accel, AccelError, AccelGeometry, Hit, Ray};

/// Packet width of the batch path.
const LANES: usize = 8;

/// A committed Embree scene over the accelerator geometry.
///
/// `Send + Sync` through `embree3::Scene` (which owns its device handle):
/// Embree allows concurrent queries on a committed scene, and queries take
/// `&self`.
pub struct EmbreeAccel {
    scene: Scene<'static>,
    shading: Option<Scene<'static>>,
    decode: Decode,
    build_seconds: [f64; 2],
    /// Prototype scenes (robust, then shading twins): the instance
    /// geometries of the scenes above point at them (shared with a
    /// `PrototypeCache` when built through one).
    _prototypes: Vec<Arc<Scene<'static>>>,
}

/// What turns an Embree hit into a `Hit`: the id of instance 0 and each
/// instance's local → render normal map.
#[derive(Debug, Default)]
struct Decode {
    inst_base: u32,
    normal_to_render: Vec<Mat3A>,
}

impl Decode {
    /// The `Hit` of a valid Embree hit.
    #[inline]
    fn hit(&self, t: f32, ids: [u32; 3], u: f32, v: f32, ng: [f32; 3]) -> Hit {
        let [geom_id, prim_id, inst] = ids;
        let mut n_geo = Vec3::from(ng);
        let mut inst_id = super::NO_INSTANCE;
        if inst != INVALID_ID {
            inst_id = inst - self.inst_base;
            n_geo = self.normal_to_render[inst_id as usize].mul_vec3(n_geo);
        }
        Hit {
            t,
            geom_id,
            prim_id,
            u,
            v,
            n_geo,
            inst_id,
        }
    }
}

impl std::fmt::Debug for EmbreeAccel {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("EmbreeAccel").finish_non_exhaustive()
    }
}

pub(super) fn embree_error(what: &str, e: embree3::Error) -> AccelError {
    AccelError::Backend(format!("embree: {what}: {e:?}"))
}

impl EmbreeAccel {
    /// Validates and builds the watertight scene and its shading twin (see
    /// [`EmbreeAccel::build_with`]).
    pub fn build(geo: &AccelGeometry) -> Result<EmbreeAccel, AccelError> {
        Self::build_with(geo, true)
    }

    /// Validates and builds the committed watertight scene (high build
    /// quality, spatial splits for triangles) and, when `shading_twin` is set,
    /// a non-robust scene over the same geometry buffers for the `*_shading`
    /// queries (without it they use the watertight scene). Empty meshes are
    /// skipped (their id stays unused).
    pub fn build_with(geo: &AccelGeometry, shading_twin: bool) -> Result<EmbreeAccel, AccelError> {
        Self::build_cached(geo, shading_twin, &PrototypeCache::default())
    }

    /// As [`EmbreeAccel::build_with`], taking every prototype scene whose
    /// meshes are bit for bit those of an earlier build from `cache` (and
    /// leaving the cache holding exactly this build's prototypes): the
    /// static world's prototypes are committed once per sequence. Embree's
    /// builds are deterministic, so the result is the one built fresh.
    pub fn build_cached(
        geo: &AccelGeometry,
        shading_twin: bool,
        cache: &PrototypeCache,
    ) -> Result<EmbreeAccel, AccelError> {
        // Embree does not bounds-check indices: validation is a safety matter here.
        validate_geometry(geo)?;
        let mut cache = cache.lock();
        let device = cache.device()?;
        let mut geometries = geometries(&device, &geo.flat())?;
        let inst_base = geo.sphere_geom_id() + 1;
        let t = std::time::Instant::now();
        // Robust mode is needed: without it Embree 3 lets rays aimed exactly at
        // shared vertices/edges of a closed mesh slip through
        // (`rays_through_shared_edges_and_vertices_never_leak`), which would
        // punch holes into ground-truth depth.
        let protos = cache.prototypes(&device, geo, shading_twin)?;
        let robust_protos: Vec<_> = protos.iter().map(|p| p.0.clone()).collect();
        let robust_insts = instance_geometries(&device, geo, &robust_protos, inst_base)?;
        let flat_len = geometries.len();
        geometries.extend(robust_insts);
        let scene = commit_scene(&device, &geometries, SceneFlags::ROBUST)?;
        let robust_s = t.elapsed().as_secs_f64();
        let t = std::time::Instant::now();
        let mut prototypes = robust_protos;
        let shading = if shading_twin {
            let twins: Vec<_> = protos.iter().filter_map(|p| p.1.clone()).collect();
            let insts = instance_geometries(&device, geo, &twins, inst_base)?;
            prototypes.extend(twins);
            geometries.truncate(flat_len);
            geometries.extend(insts);
            Some(commit_scene(&device, &geometries, SceneFlags::NONE)?)
        } else {
            None
        };
        let normal_to_render = geo.instances.iter().map(|i| i.normal_to_render()).collect();
        Ok(EmbreeAccel {
            scene,
            shading,
            decode: Decode {
                inst_base,
                normal_to_render,
            },
            build_seconds: [robust_s, t.elapsed().as_secs_f64()],
            _prototypes: prototypes,
        })
    }

    /// Seconds spent committing (building the BVH of) the watertight scene
    /// and the shading twin (0 without one).
    pub fn build_seconds(&self) -> [f64; 2] {
        self.build_seconds
    }

    /// The scene shading queries go to.
    fn shading_scene(&self) -> &Scene<'static> {
        self.shading.as_ref().unwrap_or(&self.scene)
    }

    /// Closest hits through 8-wide packets with an explicit coherence hint
    /// (`true` for primary rays of a tile, `false` for scattered rays).
    pub fn intersect_batch_with(&self, rays: &[Ray], hits: &mut [Option<Hit>], coherent: bool) {
        intersect_packets(&self.scene, &self.decode, rays, hits, coherent);
    }

    /// Any-hit through 8-wide packets with an explicit coherence hint.
    pub fn occluded_batch_with(&self, rays: &[Ray], out: &mut [bool], coherent: bool) {
        occluded_packets(&self.scene, rays, out, coherent);
    }
}

/// Closest hits of `rays` on `scene` through 8-wide packets.
fn intersect_packets(
    scene: &Scene,
    decode: &Decode,
    rays: &[Ray],
    hits: &mut [Option<Hit>],
    coherent: bool,
) {
    assert_eq!(
        rays.len(),
        hits.len(),
        "intersect_batch: rays and hits differ in length"
    );
    let mut ctx = context(coherent);
    // One packet for the whole batch, refilled lane by lane: building a
    // fresh one per 8 rays cost more (a memset and a move of ~600 bytes)
    // than the lanes themselves.
    let mut rayhit = RayHit8 {
        ray: Ray8::empty(),
        hit: Hit8::default(),
    };
    for (ray_chunk, hit_chunk) in rays.chunks(LANES).zip(hits.chunks_mut(LANES)) {
        let valid = load_lanes(&mut rayhit.ray, ray_chunk);
        let valid = &valid.0;
        // Embree writes ids only on a hit.
        rayhit.hit.geomID = [INVALID_ID; LANES];
        rayhit.hit.instID[0] = [INVALID_ID; LANES];
        scene.intersect8(&mut ctx, &mut rayhit, valid);
        for (lane, out) in hit_chunk.iter_mut().enumerate() {
            let h = &rayhit.hit;
            *out = (h.geomID[lane] != INVALID_ID).then(|| {
                decode.hit(
                    rayhit.ray.tfar[lane],
                    [h.geomID[lane], h.primID[lane], h.instID[0][lane]],
                    h.u[lane],
                    h.v[lane],
                    [h.Ng_x[lane], h.Ng_y[lane], h.Ng_z[lane]],
                )
            });
        }
    }
}

/// Any-hit of `rays` on `scene` through 8-wide packets.
fn occluded_packets(scene: &Scene, rays: &[Ray], out: &mut [bool], coherent: bool) {
    assert_eq!(
        rays.len(),
        out.len(),
        "occluded_batch: rays and out differ in length"
    );
    let mut ctx = context(coherent);
    let mut packet = Ray8::empty();
    for (ray_chunk, out_chunk) in rays.chunks(LANES).zip(out.chunks_mut(LANES)) {
        let valid = load_lanes(&mut packet, ray_chunk);
        let valid = &valid.0;
        scene.occluded8(&mut ctx, &mut packet, valid);
        for (lane, o) in out_chunk.iter_mut().enumerate() {
            // Embree marks an occluded ray by setting tfar to −∞.
            *o = packet.tfar[lane] == f32::NEG_INFINITY;
        }
    }
}

fn context(coherent: bool) -> IntersectContext {
    if coherent {
        IntersectContext::coherent()
    } else {
        IntersectContext::incoherent()
    }
}

/// An 8-lane valid mask at a 32-byte boundary: Embree's 8-wide queries
/// read it with aligned AVX loads, and `ValidMaskN` alone is aligned to 16
/// only, so where it fell on the stack decided whether a packet query
/// crashed (it did once a path's state grew by a few bytes).
#[repr(C, align(32))]
struct ValidMask8(ValidMaskN<LANES>);

/// Writes up to 8 rays into the lanes of `packet` (SoA) and returns the
/// valid mask: lanes past the end are masked off, so Embree neither reads
/// nor writes them and their stale contents do not matter.
#[inline]
fn load_lanes(packet: &mut Ray8, rays: &[Ray]) -> ValidMask8 {
    let mut lanes = [ValidMask::Invalid; LANES];
    for (lane, r) in rays.iter().enumerate() {
        packet.org_x[lane] = r.o.x;
        packet.org_y[lane] = r.o.y;
        packet.org_z[lane] = r.o.z;
        packet.dir_x[lane] = r.d.x;
        packet.dir_y[lane] = r.d.y;
        packet.dir_z[lane] = r.d.z;
        packet.tnear[lane] = r.tmin;
        packet.tfar[lane] = r.tmax;
        lanes[lane] = ValidMask::Valid;
    }
    ValidMask8(ValidMaskN::new(lanes))
}

/// Embree geometries (with their ids) for every non-empty mesh and the sphere set.
pub(super) fn geometries(
    device: &Device,
    geo: &AccelGeometry,
) -> Result<Vec<(Geometry<'static>, u32)>, AccelError> {
    let mut out = Vec::with_capacity(geo.meshes.len() + 1);
    for (geom_id, mesh) in geo.meshes.iter().enumerate() {
        if mesh.triangles.is_empty() || mesh.positions.is_empty() {
            continue;
        }
        let geometry = triangle_geometry(device, mesh.positions, mesh.triangles)?;
        out.push((geometry, geom_id as u32));
    }
    if !geo.spheres.is_empty() {
        let mut builder = device
            .create_geometry(GeometryKind::SPHERE_POINT)
            .map_err(|e| embree_error("sphere geometry", e))?;
        let mut view = builder
            .set_new_buffer::<[f32; 4]>(
                BufferUsage::VERTEX,
                0,
                Format::FLOAT4,
                16,
                geo.spheres.len(),
            )
            .map_err(|e| embree_error("sphere buffer", e))?;
        for (dst, s) in view.iter_mut().zip(geo.spheres) {
            *dst = s.to_array();
        }
        out.push((builder.commit(), geo.sphere_geom_id()));
    }
    Ok(out)
}

/// An instance geometry (id `inst_base + k`) per placement of a non-empty
/// prototype, over the committed prototype scenes `protos`.
fn instance_geometries(
    device: &Device,
    geo: &AccelGeometry,
    protos: &[Arc<Scene<'static>>],
    inst_base: u32,
) -> Result<Vec<(Geometry<'static>, u32)>, AccelError> {
    let empty: Vec<bool> = geo
        .prototypes
        .iter()
        .map(|ms| ms.iter().all(|m| m.triangles.is_empty()))
        .collect();
    let mut out = Vec::with_capacity(geo.instances.len());
    for (k, inst) in geo.instances.iter().enumerate() {
        if empty[inst.prototype as usize] {
            continue;
        }
        let mut builder = device
            .create_geometry(GeometryKind::INSTANCE)
            .map_err(|e| embree_error("instance geometry", e))?;
        builder.set_instanced_scene(&protos[inst.prototype as usize]);
        builder.set_transform(0, &column_major(inst.render_from_local));
        out.push((builder.commit(), inst_base + k as u32));
    }
    Ok(out)
}

/// A 4×4 column-major matrix of an affine map (Embree's transform format).
fn column_major(m: Affine3A) -> [f32; 16] {
    let c = m.to_cols_array();
    [
        c[0], c[1], c[2], 0.0, c[3], c[4], c[5], 0.0, c[6], c[7], c[8], 0.0, c[9], c[10], c[11],
        1.0,
    ]
}

/// Commits a scene over `geometries` with `flags`, at medium build quality:
/// high quality adds spatial splits, whose builder in Debian's Embree 3.13.5
/// aborts on an assertion for some towns (its binning and its split disagree
/// in floating point; fixed upstream in Embree 4).
pub(super) fn commit_scene(
    device: &Device,
    geometries: &[(Geometry<'static>, u32)],
    flags: SceneFlags,
) -> Result<Scene<'static>, AccelError> {
    let mut scene = device
        .create_scene()
        .map_err(|e| embree_error("scene", e))?;
    scene.set_flags(flags);
    scene.set_build_quality(BuildQuality::MEDIUM);
    for (geometry, geom_id) in geometries {
        scene.attach_geometry_by_id(geometry, *geom_id);
    }
    scene.commit();
    Ok(scene)
}

fn triangle_geometry(
    device: &Device,
    positions: &[Vec3],
    triangles: &[[u32; 3]],
) -> Result<Geometry<'static>, AccelError> {
    let mut builder = device
        .create_geometry(GeometryKind::TRIANGLE)
        .map_err(|e| embree_error("triangle geometry", e))?;
    builder.set_build_quality(BuildQuality::MEDIUM);
    builder
        .set_new_buffer::<[f32; 3]>(BufferUsage::VERTEX, 0, Format::FLOAT3, 12, positions.len())
        .map_err(|e| embree_error("vertex buffer", e))?
        .iter_mut()
        .zip(positions)
        .for_each(|(dst, p)| *dst = p.to_array());
    builder
        .set_new_buffer::<[u32; 3]>(BufferUsage::INDEX, 0, Format::UINT3, 12, triangles.len())
        .map_err(|e| embree_error("index buffer", e))?
        .copy_from_slice(triangles);
    Ok(builder.commit())
}

fn single_ray(r: &Ray) -> RtcRay {
    RtcRay::segment(r.o.to_array(), r.d.to_array(), r.tmin, r.tmax)
}

/// Closest hit of one ray on `scene` (incoherent context).
#[inline]
fn intersect_one(scene: &Scene, decode: &Decode, ray: &Ray) -> Option<Hit> {
    let mut ctx = IntersectContext::incoherent();
    let mut rayhit = RayHit::from_ray(single_ray(ray));
    scene.intersect(&mut ctx, &mut rayhit);
    let h = &rayhit.hit;
    h.is_valid().then(|| {
        decode.hit(
            rayhit.ray.tfar,
            [h.geomID, h.primID, h.instID[0]],
            h.u,
            h.v,
            [h.Ng_x, h.Ng_y, h.Ng_z],
        )
    })
}

/// Any-hit of one ray on `scene` (incoherent context).
#[inline]
fn occluded_one(scene: &Scene, ray: &Ray) -> bool {
    let mut ctx = IntersectContext::incoherent();
    scene.occluded(&mut ctx, &mut single_ray(ray))
}

impl Accel for EmbreeAccel {
    fn intersect(&self, ray: &Ray) -> Option<Hit> {
        intersect_one(&self.scene, &self.decode, ray)
    }

    fn occluded(&self, ray: &Ray) -> bool {
        occluded_one(&self.scene, ray)
    }

    fn intersect_batch(&self, rays: &[Ray], hits: &mut [Option<Hit>]) {
        self.intersect_batch_with(rays, hits, true);
    }

    fn occluded_batch(&self, rays: &[Ray], out: &mut [bool]) {
        // Ground truth's occlusion segments share the right camera's centre
        // and run along a row: coherent.
        self.occluded_batch_with(rays, out, true);
    }

    fn backend_name(&self) -> &'static str {
        "embree"
    }

    fn intersect_shading(&self, ray: &Ray) -> Option<Hit> {
        intersect_one(self.shading_scene(), &self.decode, ray)
    }

    fn occluded_shading(&self, ray: &Ray) -> bool {
        occluded_one(self.shading_scene(), ray)
    }

    fn intersect_batch_shading(&self, rays: &[Ray], hits: &mut [Option<Hit>]) {
        intersect_packets(self.shading_scene(), &self.decode, rays, hits, true);
    }

    fn occluded_batch_shading(&self, rays: &[Ray], out: &mut [bool]) {
        // The path pass batches only shadow rays towards one directional
        // light from neighbouring points: coherent.
        occluded_packets(self.shading_scene(), rays, out, true);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn eight_lane_masks_sit_on_the_boundary_avx_loads_need() {
        let rays = [Ray::new(glam::Vec3::ZERO, glam::Vec3::X); 3];
        let mut packet = Ray8::empty();
        // A few masks at different stack depths, as the packet loops make them.
        let masks: Vec<ValidMask8> = (0..5).map(|_| load_lanes(&mut packet, &rays)).collect();
        let one = load_lanes(&mut packet, &rays);
        for m in masks.iter().chain([&one]) {
            let at = &m.0 as *const ValidMaskN<LANES> as usize;
            assert_eq!(at % 32, 0, "mask at {at:#x}");
        }
    }
}
