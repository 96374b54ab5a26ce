//! `SurfaceTable`: a compact per-triangle copy of what a hit needs (vertex
//! positions and material) so that turning a path vertex's `Hit` into a
//! `SurfaceInteraction` costs one cold cache line instead of three dependent
//! misses (index → vertices, plus the material array). Embree in robust mode
//! traverses its own vertex copies in the BVH leaves, so the scene's arrays are
//! always cold when a hit comes back.
//!
//! The interaction is computed by the same code as [`surface_interaction`], so
//! both give the same bits.

use glam::Vec3;

use super::huge::HugeArray;
use super::surface::{sphere_interaction, triangle_interaction};
use super::Scene;
use crate::accel::{Hit, NO_INSTANCE};
use crate::geometry::{Ray, SurfaceInteraction};

#[cfg(doc)]
use super::surface_interaction;

/// One triangle's vertex positions and material, 48 bytes, 16-aligned.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(16))]
struct TriangleRecord {
    p: [Vec3; 3],
    material: u32,
}

/// Per-triangle records of every mesh of a scene, built once per frame.
#[derive(Clone, Debug, Default)]
pub struct SurfaceTable {
    /// Index of each flat mesh's first record.
    first: Vec<usize>,
    /// Per prototype, index of each of its meshes' first record (after
    /// the flat meshes' records).
    proto_first: Vec<Vec<usize>>,
    /// On huge pages: vertices read them at random (see `huge.rs`).
    records: HugeArray<TriangleRecord>,
}

impl SurfaceTable {
    /// Copies positions and materials of every triangle of `scene`.
    pub fn build(scene: &Scene) -> Self {
        let mut first = Vec::with_capacity(scene.meshes.len());
        let mut total = 0;
        for mesh in &scene.meshes {
            first.push(total);
            total += mesh.triangles.len();
        }
        let mut proto_first = Vec::with_capacity(scene.prototypes.len());
        for p in &scene.prototypes {
            let mut f = Vec::with_capacity(p.meshes.len());
            for mesh in &p.meshes {
                f.push(total);
                total += mesh.triangles.len();
            }
            proto_first.push(f);
        }
        let meshes = scene
            .meshes
            .iter()
            .chain(scene.prototypes.iter().flat_map(|p| &p.meshes));
        let records = meshes.flat_map(|mesh| {
            mesh.triangles
                .iter()
                .zip(&mesh.tri_material)
                .map(|(tri, &material)| TriangleRecord {
                    p: tri.map(|i| mesh.p_f32[i as usize]),
                    material,
                })
        });
        SurfaceTable {
            first,
            proto_first,
            records: HugeArray::from_exact_iter(total, records),
        }
    }

    /// Asks the CPU to start loading `hit`'s record (both cache lines a
    /// 48-byte record may straddle); a hint only, results never change.
    #[inline]
    pub fn prefetch(&self, scene: &Scene, hit: &Hit) {
        let Some(r) = self
            .first_record(scene, hit)
            .and_then(|f| self.records.get(f + hit.prim_id as usize))
        else {
            return;
        };
        #[cfg(target_arch = "x86_64")]
        {
            use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
            let first_byte = (r as *const TriangleRecord).cast::<i8>();
            // SAFETY: prefetching is a hint that never faults; both addresses
            // lie inside the record.
            unsafe {
                _mm_prefetch::<_MM_HINT_T0>(first_byte);
                _mm_prefetch::<_MM_HINT_T0>(
                    first_byte.add(std::mem::size_of::<TriangleRecord>() - 1),
                );
            }
        }
        #[cfg(not(target_arch = "x86_64"))]
        let _ = r;
    }

    /// The interaction for `hit` of `ray`: equal to `surface_interaction(scene, ray, hit)`
    /// for the scene this table was built from.
    #[inline]
    pub fn interaction(&self, scene: &Scene, ray: &Ray, hit: &Hit) -> SurfaceInteraction {
        let geom = hit.geom_id as usize;
        if hit.inst_id != NO_INSTANCE {
            let inst = &scene.instances[hit.inst_id as usize];
            let p = inst.prototype as usize;
            let r = &self.records[self.proto_first[p][geom] + hit.prim_id as usize];
            let mesh = &scene.prototypes[p].meshes[geom];
            triangle_interaction(mesh, r.p, r.material, hit, Some(inst))
        } else if geom < scene.meshes.len() {
            let r = &self.records[self.first[geom] + hit.prim_id as usize];
            triangle_interaction(&scene.meshes[geom], r.p, r.material, hit, None)
        } else {
            sphere_interaction(scene, ray, hit)
        }
    }

    /// Index of the first record of the mesh `hit` lies on (None: a sphere).
    #[inline]
    fn first_record(&self, scene: &Scene, hit: &Hit) -> Option<usize> {
        let geom = hit.geom_id as usize;
        if hit.inst_id == NO_INSTANCE {
            return self.first.get(geom).copied();
        }
        let p = scene.instances.get(hit.inst_id as usize)?.prototype as usize;
        self.proto_first.get(p)?.get(geom).copied()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::{build_accel, Accel, Backend};
    use crate::camera::StereoRig;
    use crate::scene::{build_scene, load_scene, surface_interaction};

    #[test]
    fn table_interaction_equals_surface_interaction_bit_for_bit() {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/street.toml");
        let loaded = load_scene(&path).expect("street scene loads");
        let rig = StereoRig::from_desc(&loaded.desc.camera);
        let scene = build_scene(&loaded, rig.left.center_world).expect("street scene builds");
        let accel = build_accel(Backend::Bvh, &scene.accel_geometry()).expect("accel builds");
        let table = SurfaceTable::build(&scene);
        let mut hits = 0;
        for k in 0..4000 {
            // Directions spread over the forward hemisphere and a little below the horizon.
            let a = k as f32 * 2.399_963;
            let z = -0.4 + 0.8 * (k as f32 + 0.5) / 4000.0;
            let r = (1.0 - z * z).sqrt();
            let ray = Ray::new(Vec3::ZERO, Vec3::new(r * a.cos(), r * a.sin(), z));
            let Some(hit) = accel.intersect(&ray) else {
                continue;
            };
            hits += 1;
            let ours = table.interaction(&scene, &ray, &hit);
            let reference = surface_interaction(&scene, &ray, &hit);
            assert_eq!(format!("{ours:?}"), format!("{reference:?}"), "ray {k}");
        }
        assert!(hits > 1000, "only {hits} rays hit the street");
    }
}
