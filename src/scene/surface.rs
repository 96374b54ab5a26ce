//! Turning an accelerator `Hit` on this scene into a `SurfaceInteraction`
//! (Mitsuba's `PreliminaryIntersection` → `SurfaceInteraction3f` split):
//! position with its f32 error bound, geometric and shading normals,
//! material and labels, read from the scene's meshes and spheres.
//!
//! Normals are render-space (= world orientation) unit vectors; `n_geo` follows
//! the triangle winding (or points out of a sphere) and is not flipped here.
//! A hit on an instance is interpolated in the prototype's frame and carried
//! to render space (see `triangle_interaction`).

use glam::{Mat3A, Vec2, Vec3};

use super::{Instance, Mesh, Scene};
use crate::accel::Hit;
use crate::geometry::{gamma, position_error, Ray, SurfaceInteraction};

/// Builds the interaction for `hit` of `ray` in `scene`.
pub fn surface_interaction(scene: &Scene, ray: &Ray, hit: &Hit) -> SurfaceInteraction {
    let Some((mesh, inst)) = scene.hit_mesh(hit) else {
        return sphere_interaction(scene, ray, hit);
    };
    let tri = mesh.triangles[hit.prim_id as usize];
    let p = tri.map(|i| mesh.p_f32[i as usize]);
    triangle_interaction(mesh, p, mesh.tri_material[hit.prim_id as usize], hit, inst)
}

/// The interaction on triangle `hit.prim_id` of `mesh`, given its vertex
/// positions `p` and material (shared by [`surface_interaction`] and
/// `SurfaceTable`, so both compute the same bits). With `inst`, `mesh` is a
/// prototype's and `p` local: the point and its error bound go through the
/// instance transform (pbrt-v4 §6.8.6: (1 + γ₃)|M|·e + γ₃(|M|·|p| + |t|)),
/// the winding normal and each vertex normal through its normal map before
/// interpolating (so the shading normal is the one the flattened mesh's
/// unit vertex normals give), and the instance's labels replace the
/// prototype's.
#[inline(always)]
pub(super) fn triangle_interaction(
    mesh: &Mesh,
    p: [Vec3; 3],
    material: u32,
    hit: &Hit,
    inst: Option<&Instance>,
) -> SurfaceInteraction {
    let b = [1.0 - hit.u - hit.v, hit.u, hit.v];
    let mut p_hit = p[0] * b[0] + p[1] * b[1] + p[2] * b[2];
    let mut p_error = position_error(b, p);
    let mut semantic = mesh.semantic;
    let mut instance = mesh.instance;
    let mut n_cross = (p[1] - p[0]).cross(p[2] - p[0]);
    if let Some(inst) = inst {
        let m = inst.render_from_local_f32;
        let abs_m = Mat3A::from_cols(
            m.matrix3.x_axis.abs(),
            m.matrix3.y_axis.abs(),
            m.matrix3.z_axis.abs(),
        );
        p_error = (1.0 + gamma(3)) * abs_m.mul_vec3(p_error)
            + gamma(3) * (abs_m.mul_vec3(p_hit.abs()) + Vec3::from(m.translation).abs());
        p_hit = m.transform_point3(p_hit);
        n_cross = inst.normal_to_render.mul_vec3(n_cross);
        semantic = inst.semantic.unwrap_or(semantic);
        instance = inst.instance.unwrap_or(instance);
    }
    // `hit.n_geo` is render space on every backend: the fallback needs no map.
    let n_geo = n_cross.normalize_or(hit.n_geo.normalize_or(Vec3::Z));
    let mut n_shading = n_geo;
    let mut uv = Vec2::ZERO;
    if !mesh.normals.is_empty() || !mesh.uvs.is_empty() {
        let [i0, i1, i2] = mesh.triangles[hit.prim_id as usize].map(|i| i as usize);
        if !mesh.normals.is_empty() {
            let nv = |i: usize| match inst {
                None => mesh.normals[i],
                Some(inst) => inst
                    .normal_to_render
                    .mul_vec3(mesh.normals[i])
                    .normalize_or_zero(),
            };
            let n = nv(i0) * b[0] + nv(i1) * b[1] + nv(i2) * b[2];
            if let Some(n) = n.try_normalize() {
                n_shading = if n.dot(n_geo) < 0.0 { -n } else { n };
            }
        }
        if !mesh.uvs.is_empty() {
            uv = mesh.uvs[i0] * b[0] + mesh.uvs[i1] * b[1] + mesh.uvs[i2] * b[2];
        }
    }
    SurfaceInteraction {
        p: p_hit,
        p_error,
        n_geo,
        n_shading,
        uv,
        material,
        semantic,
        instance,
    }
}

/// The interaction on sphere `hit.prim_id` of the scene's sphere set.
pub(super) fn sphere_interaction(scene: &Scene, ray: &Ray, hit: &Hit) -> SurfaceInteraction {
    let s = &scene.spheres[hit.prim_id as usize];
    let c = scene.spheres_f32[hit.prim_id as usize];
    let center = c.truncate();
    // Re-project onto the surface (pbrt-v4 §6.8.5): error ~ gamma(5)·|p|.
    let mut p = ray.at(hit.t);
    let n = (p - center).normalize_or(Vec3::Z);
    p = center + n * c.w;
    let uv = Vec2::new(
        0.5 + n.y.atan2(n.x) / std::f32::consts::TAU,
        n.z.clamp(-1.0, 1.0).acos() / std::f32::consts::PI,
    );
    SurfaceInteraction {
        p,
        p_error: p.abs() * gamma(5) + Vec3::splat(c.w * gamma(5)),
        n_geo: n,
        n_shading: n,
        uv,
        material: s.material,
        semantic: s.semantic,
        instance: s.instance,
    }
}
