//! Turning an accelerator `Hit` on this scene into a `SurfaceInteraction`
//! (Mitsuba's `PreliminaryIntersection` → `SurfaceInteraction3f` split):
//! position with its f32 error bound, geometric and shading normals,
//! material and labels, read from the scene's meshes and spheres.
//!
//! Normals are render-space (= world orientation) unit vectors; `n_geo` follows
//! the triangle winding (or points out of a sphere) and is not flipped here.
//! A hit on an instance is shaded in the prototype's frame and carried to
//! render space (`to_render`): the point and its error bound through the
//! instance transform, normals through its inverse transpose.

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
    let si = triangle_interaction(mesh, p, mesh.tri_material[hit.prim_id as usize], hit);
    match inst {
        None => si,
        Some(inst) => to_render(si, inst),
    }
}

/// An interaction computed in an instance's local frame, in render space:
/// the point's error bound grows by the transform's rounding (pbrt-v4
/// §6.8.6: (1 + γ₃)|M|·e + γ₃(|M|·|p| + |t|)); normals go through the
/// instance's normal map, the shading normal kept on `n_geo`'s side; the
/// instance's labels replace the prototype's.
#[inline]
pub(super) fn to_render(si: SurfaceInteraction, inst: &Instance) -> SurfaceInteraction {
    let m = inst.render_from_local_f32;
    let abs_m = Mat3A::from_cols(
        m.matrix3.x_axis.abs(),
        m.matrix3.y_axis.abs(),
        m.matrix3.z_axis.abs(),
    );
    let p_error = (1.0 + gamma(3)) * abs_m.mul_vec3(si.p_error)
        + gamma(3) * (abs_m.mul_vec3(si.p.abs()) + Vec3::from(m.translation).abs());
    let n_geo = inst.normal_to_render.mul_vec3(si.n_geo).normalize_or(Vec3::Z);
    let n = inst.normal_to_render.mul_vec3(si.n_shading).normalize_or(n_geo);
    SurfaceInteraction {
        p: m.transform_point3(si.p),
        p_error,
        n_geo,
        n_shading: if n.dot(n_geo) < 0.0 { -n } else { n },
        semantic: inst.semantic.unwrap_or(si.semantic),
        instance: inst.instance.unwrap_or(si.instance),
        ..si
    }
}

/// The interaction on triangle `hit.prim_id` of `mesh`, given its vertex
/// positions `p` and material (shared by [`surface_interaction`] and
/// `SurfaceTable`, so both compute the same bits).
#[inline(always)]
pub(super) fn triangle_interaction(
    mesh: &Mesh,
    p: [Vec3; 3],
    material: u32,
    hit: &Hit,
) -> SurfaceInteraction {
    let b = [1.0 - hit.u - hit.v, hit.u, hit.v];
    let p_hit = p[0] * b[0] + p[1] * b[1] + p[2] * b[2];
    let n_geo = (p[1] - p[0])
        .cross(p[2] - p[0])
        .normalize_or(hit.n_geo.normalize_or(Vec3::Z));
    let mut n_shading = n_geo;
    let mut uv = Vec2::ZERO;
    if !mesh.normals.is_empty() || !mesh.uvs.is_empty() {
        let [i0, i1, i2] = mesh.triangles[hit.prim_id as usize].map(|i| i as usize);
        if !mesh.normals.is_empty() {
            let n = mesh.normals[i0] * b[0] + mesh.normals[i1] * b[1] + mesh.normals[i2] * b[2];
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
        p_error: position_error(b, p),
        n_geo,
        n_shading,
        uv,
        material,
        semantic: mesh.semantic,
        instance: mesh.instance,
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
