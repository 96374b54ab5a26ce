//! Committed Embree prototype scenes kept from one accelerator build to the
//! next (issue 21: the static world is built once per sequence).
//!
//! A prototype's BVH depends only on its meshes in its local frame, not on
//! the frame's render origin, so the frames of one sequence share every
//! static prototype. Entries are keyed by a 128-bit hash of the meshes'
//! exact bits (positions and indices; never by names, and no copy of the
//! data kept): a cached scene is used only for geometry identical to what it
//! was built from, and Embree's builds are deterministic, so a cached build
//! gives the bytes a fresh one gives. After
//! each build the cache keeps exactly that build's prototypes, so it holds
//! one frame's worth at most (the previous frame's, for the next one).

use std::collections::hash_map::DefaultHasher;
use std::collections::HashMap;
use std::hash::{Hash, Hasher};
use std::sync::{Arc, Mutex, MutexGuard};

use embree3::{Device, Scene, SceneFlags};

use super::embree::{commit_scene, embree_error, geometries};
use super::{AccelError, AccelGeometry, TriMeshRef};

/// Prototype scenes shared between Embree builds on one device.
#[derive(Default)]
pub struct PrototypeCache {
    inner: Mutex<Inner>,
}

impl std::fmt::Debug for PrototypeCache {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let n = self.inner.lock().map(|i| i.entries.len()).unwrap_or(0);
        f.debug_struct("PrototypeCache")
            .field("prototypes", &n)
            .finish()
    }
}

impl PrototypeCache {
    /// Number of prototypes held (those of the last build).
    pub fn len(&self) -> usize {
        self.lock().entries.len()
    }

    /// How many prototype scenes the last build took from the cache.
    pub fn reused(&self) -> usize {
        self.lock().reused
    }

    /// Whether the cache holds nothing.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Exclusive access for one build (builds through one cache serialise).
    pub(super) fn lock(&self) -> MutexGuard<'_, Inner> {
        // A panic mid-build leaves only complete entries behind.
        self.inner.lock().unwrap_or_else(|e| e.into_inner())
    }
}

/// The robust scene of a prototype and its shading twin (if built).
pub(super) type Pair = (Arc<Scene<'static>>, Option<Arc<Scene<'static>>>);

/// The cache's device and entries.
#[derive(Default)]
pub(super) struct Inner {
    device: Option<Device>,
    /// Committed scenes by the hash of their meshes' bits.
    entries: HashMap<[u64; 2], Pair>,
    reused: usize,
}

impl Inner {
    /// The device every build through this cache uses (instances must live
    /// on their prototypes' device).
    pub(super) fn device(&mut self) -> Result<Device, AccelError> {
        if self.device.is_none() {
            self.device = Some(Device::new().map_err(|e| embree_error("device", e))?);
        }
        Ok(self.device.clone().expect("device was just created"))
    }

    /// The committed scenes of every prototype of `geo` (with shading twins
    /// when `twin`), taken from the cache or built; afterwards the cache
    /// holds exactly these. Prototypes with the same bits in one build share
    /// one scene. None are built for a geometry without instances.
    pub(super) fn prototypes(
        &mut self,
        device: &Device,
        geo: &AccelGeometry,
        twin: bool,
    ) -> Result<Vec<Pair>, AccelError> {
        self.reused = 0;
        if geo.instances.is_empty() {
            self.entries.clear();
            return Ok(Vec::new());
        }
        let mut old = std::mem::take(&mut self.entries);
        let mut out = Vec::with_capacity(geo.prototypes.len());
        for p in 0..geo.prototypes.len() {
            let hash = hash_meshes(&geo.prototypes[p]);
            let mut scenes = match self.entries.remove(&hash) {
                Some(s) => s,
                None => match old.remove(&hash) {
                    Some(s) => {
                        self.reused += 1;
                        s
                    }
                    None => (commit(device, geo, p, SceneFlags::ROBUST)?, None),
                },
            };
            if twin && scenes.1.is_none() {
                scenes.1 = Some(commit(device, geo, p, SceneFlags::NONE)?);
            }
            out.push(scenes.clone());
            self.entries.insert(hash, scenes);
        }
        Ok(out)
    }
}

/// Prototype `p` of `geo` committed with `flags`.
fn commit(
    device: &Device,
    geo: &AccelGeometry,
    p: usize,
    flags: SceneFlags,
) -> Result<Arc<Scene<'static>>, AccelError> {
    let g = geometries(device, &geo.prototype(p))?;
    Ok(Arc::new(commit_scene(device, &g, flags)?))
}

/// Two independent 64-bit hashes (SipHash with fixed keys, the second
/// salted) of every position's bits and every index of `meshes`, in order,
/// fed to both in one pass over the data, in blocks.
fn hash_meshes(meshes: &[TriMeshRef]) -> [u64; 2] {
    let mut f = Feed {
        h: [0u8, 1].map(|salt| {
            let mut h = DefaultHasher::new();
            (salt, meshes.len()).hash(&mut h);
            h
        }),
        buf: Vec::with_capacity(BLOCK + 16),
    };
    for m in meshes {
        f.word(m.positions.len() as u32);
        f.word(m.triangles.len() as u32);
        for c in m.positions.iter().flat_map(|p| p.to_array()) {
            f.word(c.to_bits());
        }
        for &i in m.triangles.iter().flatten() {
            f.word(i);
        }
    }
    f.flush();
    f.h.map(|h| h.finish())
}

/// Bytes per block handed to the hashers.
const BLOCK: usize = 4096;

/// Words gathered into blocks for the two hashers.
struct Feed {
    h: [DefaultHasher; 2],
    buf: Vec<u8>,
}

impl Feed {
    #[inline]
    fn word(&mut self, w: u32) {
        self.buf.extend_from_slice(&w.to_le_bytes());
        if self.buf.len() >= BLOCK {
            self.flush();
        }
    }

    fn flush(&mut self) {
        for h in &mut self.h {
            h.write(&self.buf);
        }
        self.buf.clear();
    }
}

#[cfg(test)]
mod tests {
    use glam::{Affine3A, Vec3};

    use super::*;
    use crate::accel::Accel;
    use crate::accel::{EmbreeAccel, InstanceRef, Ray};

    /// Two prototypes (a unit quad at z = `z0` and one at z = `z1`), each
    /// placed once, side by side.
    fn hits(z: [f32; 2], cache: &PrototypeCache) -> Vec<Option<f32>> {
        let p = |z: f32| {
            vec![
                Vec3::new(0.0, 0.0, z),
                Vec3::new(1.0, 0.0, z),
                Vec3::new(1.0, 1.0, z),
                Vec3::new(0.0, 1.0, z),
            ]
        };
        let (p0, p1) = (p(z[0]), p(z[1]));
        let tris = [[0u32, 1, 2], [0, 2, 3]];
        let inst = |proto: u32, x: f32| {
            let m = Affine3A::from_translation(Vec3::new(x, 0.0, 0.0));
            InstanceRef {
                prototype: proto,
                render_from_local: m,
                local_from_render: m.inverse(),
            }
        };
        let instances = [inst(0, 0.0), inst(1, 2.0)];
        let geo = AccelGeometry {
            prototypes: vec![
                vec![TriMeshRef {
                    positions: &p0,
                    triangles: &tris,
                }],
                vec![TriMeshRef {
                    positions: &p1,
                    triangles: &tris,
                }],
            ],
            instances: &instances,
            ..AccelGeometry::default()
        };
        let a = EmbreeAccel::build_cached(&geo, true, cache).unwrap();
        [0.5f32, 2.5]
            .iter()
            .map(|&x| {
                let r = Ray::new(Vec3::new(x, 0.5, 10.0), Vec3::new(0.0, 0.0, -1.0));
                let h = a.intersect(&r).map(|h| h.t);
                assert_eq!(h, a.intersect_shading(&r).map(|h| h.t));
                h
            })
            .collect()
    }

    /// Hit distances equal to `want` up to Embree's f32 rounding (its
    /// kernels differ per instruction set: 9 comes out as 8.999999 on AVX2).
    fn assert_hits(got: Vec<Option<f32>>, want: [f32; 2]) {
        assert!(
            got.iter()
                .zip(want)
                .all(|(g, w)| g.is_some_and(|g| (g - w).abs() <= 4e-6 * w)),
            "{got:?} vs {want:?}"
        );
    }

    #[test]
    fn cached_prototypes_are_reused_only_for_identical_bits() {
        let cache = PrototypeCache::default();
        assert_hits(hits([1.0, 2.0], &cache), [9.0, 8.0]);
        assert_eq!((cache.len(), cache.reused()), (2, 0));
        // Same geometry again: both scenes come from the cache.
        assert_hits(hits([1.0, 2.0], &cache), [9.0, 8.0]);
        assert_eq!(cache.reused(), 2);
        // The second prototype moved by 0.25 m: rebuilt, and its
        // hit is the new one, not the cached scene's.
        let z = 2.0f32 + 0.25;
        assert_hits(hits([1.0, z], &cache), [9.0, 10.0 - z]);
        assert_eq!((cache.len(), cache.reused()), (2, 1));
        // Swapped order: matched by content, not by index.
        assert_hits(hits([z, 1.0], &cache), [10.0 - z, 9.0]);
        assert_eq!(cache.reused(), 2);
        // Fresh builds agree with the cached ones.
        let fresh = PrototypeCache::default();
        assert_eq!(hits([z, 1.0], &fresh), hits([z, 1.0], &cache));
    }
}
