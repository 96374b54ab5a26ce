//! The instance layer of the pure-Rust backends: one accelerator per
//! prototype (its local frame, built once however often it is placed) and
//! the placements, traversed through a top-level BVH over their render-space
//! boxes (the BVH backend) or scanned in order (the brute reference).
//!
//! A ray meets an instance in the prototype's frame: origin and direction go
//! through local_from_render, `tmin`/`tmax` stay (an affine map preserves the
//! ray parameter, so `t` comes back in render units), and the geometric
//! normal goes back with the inverse transpose of render_from_local, i.e.
//! the transpose of local_from_render (negated for a mirroring instance,
//! whose transformed winding turns the other way).

use glam::{Affine3A, Mat3A, Vec3};

use super::bvh::traverse;
use super::bvh_build::{build_nodes, BuildRef, Node};
use super::{Accel, AccelGeometry, Hit, Ray, TriMeshRef};

/// Top-level boxes are padded by this fraction of their largest |coordinate|:
/// the ray's trip into the local frame rounds, the box must not cull a hit.
const BOX_PAD_REL: f32 = 1e-5;

/// One placement as traversal wants it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Placed {
    /// Prototype index.
    proto: u32,
    /// Index of the instance in the geometry (`Hit::inst_id`).
    index: u32,
    /// Render → local.
    local_from_render: Affine3A,
    /// Local normal → render normal (`InstanceRef::normal_to_render`).
    normal_to_render: Mat3A,
}

impl Placed {
    #[inline]
    fn local_ray(&self, ray: &Ray, tmax: f32) -> Ray {
        Ray {
            o: self.local_from_render.transform_point3(ray.o),
            d: self.local_from_render.transform_vector3(ray.d),
            tmin: ray.tmin,
            tmax,
        }
    }
}

/// Prototype accelerators and the placements over them.
#[derive(Clone, Debug)]
pub(crate) struct InstanceLayer<A> {
    protos: Vec<A>,
    items: Vec<Placed>,
    /// BVH over `items` (which are in its leaf order); empty: linear scan.
    nodes: Vec<Node>,
}

impl<A> Default for InstanceLayer<A> {
    fn default() -> Self {
        InstanceLayer {
            protos: Vec::new(),
            items: Vec::new(),
            nodes: Vec::new(),
        }
    }
}

/// Local bounds of a prototype's vertices (None when it has none).
fn local_bounds(meshes: &[TriMeshRef]) -> Option<(Vec3, Vec3)> {
    meshes
        .iter()
        .filter(|m| !m.triangles.is_empty())
        .flat_map(|m| m.positions.iter())
        .fold(None, |b, &p| match b {
            None => Some((p, p)),
            Some((lo, hi)) => Some((lo.min(p), hi.max(p))),
        })
}

/// Render-space box of a local box under `m` (its eight corners), padded.
fn render_bounds(m: Affine3A, lo: Vec3, hi: Vec3) -> (Vec3, Vec3) {
    let mut min = Vec3::splat(f32::INFINITY);
    let mut max = Vec3::splat(f32::NEG_INFINITY);
    for i in 0..8 {
        let pick = |bit: u32, a: f32, b: f32| if i >> bit & 1 == 1 { b } else { a };
        let c = Vec3::new(
            pick(0, lo.x, hi.x),
            pick(1, lo.y, hi.y),
            pick(2, lo.z, hi.z),
        );
        let p = m.transform_point3(c);
        min = min.min(p);
        max = max.max(p);
    }
    let pad = min.abs().max(max.abs()).max_element() * BOX_PAD_REL + f32::MIN_POSITIVE;
    (min - Vec3::splat(pad), max + Vec3::splat(pad))
}

impl<A: Accel> InstanceLayer<A> {
    /// Builds every prototype of `geo` with `build_proto` and places the
    /// instances; with `tree` they get a top-level BVH, else a linear scan.
    /// Instances of empty prototypes are left out (they can never be hit).
    pub fn build(
        geo: &AccelGeometry,
        tree: bool,
        build_proto: impl Fn(&AccelGeometry) -> A,
    ) -> Self {
        if geo.instances.is_empty() {
            return InstanceLayer::default();
        }
        let protos = (0..geo.prototypes.len())
            .map(|p| build_proto(&geo.prototype(p)))
            .collect();
        let bounds: Vec<_> = geo.prototypes.iter().map(|m| local_bounds(m)).collect();
        let mut items = Vec::with_capacity(geo.instances.len());
        let mut refs = Vec::with_capacity(geo.instances.len());
        for (i, inst) in geo.instances.iter().enumerate() {
            let Some((lo, hi)) = bounds[inst.prototype as usize] else {
                continue;
            };
            let (min, max) = render_bounds(inst.render_from_local, lo, hi);
            refs.push(BuildRef {
                min,
                max,
                index: items.len() as u32,
            });
            items.push(Placed {
                proto: inst.prototype,
                index: i as u32,
                local_from_render: inst.local_from_render,
                normal_to_render: inst.normal_to_render(),
            });
        }
        let mut nodes = Vec::new();
        if tree && !refs.is_empty() {
            nodes = build_nodes(&mut refs);
            items = refs.iter().map(|r| items[r.index as usize]).collect();
        }
        InstanceLayer {
            protos,
            items,
            nodes,
        }
    }

    /// Whether there is nothing to hit.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }

    /// Replaces `best` by the closest instance hit at or before it (or
    /// before `ray.tmax` when there is none yet).
    #[inline]
    pub fn intersect(&self, ray: &Ray, best: &mut Option<Hit>) {
        if self.is_empty() {
            return;
        }
        let t_start = best.map_or(ray.tmax, |h| h.t);
        let mut tmax = t_start;
        let mut visit = |items: &[Placed]| {
            for it in items {
                let local = it.local_ray(ray, tmax);
                if let Some(h) = self.protos[it.proto as usize].intersect(&local) {
                    tmax = h.t;
                    *best = Some(Hit {
                        n_geo: it.normal_to_render.mul_vec3(h.n_geo),
                        inst_id: it.index,
                        ..h
                    });
                }
            }
            Some(tmax)
        };
        if self.nodes.is_empty() {
            visit(&self.items);
        } else {
            traverse(&self.nodes, &self.items, ray, t_start, visit);
        }
    }

    /// Whether any instance is hit within the ray's interval.
    #[inline]
    pub fn occluded(&self, ray: &Ray) -> bool {
        if self.is_empty() {
            return false;
        }
        let test =
            |it: &Placed| self.protos[it.proto as usize].occluded(&it.local_ray(ray, ray.tmax));
        if self.nodes.is_empty() {
            return self.items.iter().any(test);
        }
        let mut hit = false;
        traverse(&self.nodes, &self.items, ray, ray.tmax, |items| {
            hit = items.iter().any(test);
            (!hit).then_some(ray.tmax)
        });
        hit
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn render_bounds_contain_rotated_corners_with_padding() {
        let m = Affine3A::from_rotation_z(0.5) * Affine3A::from_scale(Vec3::new(2.0, 1.0, 3.0));
        let (lo, hi) = (Vec3::new(-1.0, -1.0, 0.0), Vec3::ONE);
        let (min, max) = render_bounds(m, lo, hi);
        for c in [lo, hi, Vec3::new(-1.0, 1.0, 0.0), Vec3::new(1.0, -1.0, 1.0)] {
            let p = m.transform_point3(c);
            assert!(
                p.cmpgt(min).all() && p.cmplt(max).all(),
                "{p} outside {min}..{max}"
            );
        }
        // Tight up to the padding: the rotated x extent is 2cos(0.5) + sin(0.5).
        let want = 2.0 * 0.5f32.cos() + 0.5f32.sin();
        assert!((max.x - want).abs() < 1e-4, "{} vs {want}", max.x);
    }
}
