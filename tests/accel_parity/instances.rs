//! Two-level instancing on every backend: a prototype (a closed tessellated
//! box and a small soup) placed by rotated, non-uniformly scaled, mirrored
//! and far-translated instances, against the same triangles flattened into
//! render space. Instanced hits come back with the instance index, the
//! prototype's mesh and triangle ids, render-space t and normals.

use glam::{Affine3A, DAffine3, DMat3, DVec3, Vec3};
use parallax::accel::{
    Accel, AccelGeometry, Backend, Hit, InstanceRef, Ray, TriMeshRef, NO_INSTANCE,
};

use super::{all_backends, assert_hits_agree, build, tessellated_box, Rng};

/// A prototype of two meshes, its placements, and the same flattened.
struct Placed {
    proto: [(Vec<Vec3>, Vec<[u32; 3]>); 2],
    instances: Vec<InstanceRef>,
    /// Flattened: instance k's mesh g is flat mesh 2k + g.
    flat: Vec<(Vec<Vec3>, Vec<[u32; 3]>)>,
    /// A flat mesh of its own (geometry id 0 in the instanced geometry).
    ground: (Vec<Vec3>, Vec<[u32; 3]>),
}

fn transforms() -> Vec<DAffine3> {
    let rot = |x: f64, y: f64, z: f64| {
        DMat3::from_rotation_z(z) * DMat3::from_rotation_y(y) * DMat3::from_rotation_x(x)
    };
    vec![
        DAffine3::from_translation(DVec3::new(0.0, 0.0, 6.0)),
        DAffine3 {
            matrix3: rot(0.3, -0.5, 1.1) * DMat3::from_diagonal(DVec3::new(2.0, 0.5, 1.3)),
            translation: DVec3::new(4.0, -3.0, 1.0),
        },
        // Mirrored (negative determinant).
        DAffine3 {
            matrix3: rot(0.0, 0.2, -0.7) * DMat3::from_diagonal(DVec3::new(-1.0, 1.5, 0.8)),
            translation: DVec3::new(-4.5, 2.0, -1.0),
        },
        DAffine3 {
            matrix3: rot(1.2, 0.4, 0.0) * 0.4,
            translation: DVec3::new(-2.0, -4.0, 3.0),
        },
    ]
}

impl Placed {
    fn new() -> Placed {
        let mut rng = Rng(11);
        let closed = tessellated_box(Vec3::new(-1.0, -0.8, -0.6), Vec3::new(0.9, 1.2, 0.7), 4);
        let mut soup = (Vec::new(), Vec::new());
        for _ in 0..40 {
            let c = rng.vec(-2.0, 2.0);
            let base = soup.0.len() as u32;
            soup.0.extend((0..3).map(|_| c + 0.6 * rng.vec(-1.0, 1.0)));
            soup.1.push([base, base + 1, base + 2]);
        }
        let proto = [closed, soup];
        let mut instances = Vec::new();
        let mut flat = Vec::new();
        for x in transforms() {
            instances.push(InstanceRef {
                prototype: 0,
                render_from_local: x.as_affine3a(),
                local_from_render: x.inverse().as_affine3a(),
            });
            for (p, t) in &proto {
                let moved = p
                    .iter()
                    .map(|&v| x.transform_point3(v.as_dvec3()).as_vec3());
                flat.push((moved.collect(), t.clone()));
            }
        }
        let g = 9.0;
        let ground = (
            vec![
                Vec3::new(-g, -g, -3.0),
                Vec3::new(g, -g, -3.0),
                Vec3::new(g, g, -3.0),
                Vec3::new(-g, g, -3.0),
            ],
            vec![[0, 1, 2], [0, 2, 3]],
        );
        Placed {
            proto,
            instances,
            flat,
            ground,
        }
    }

    fn instanced(&self) -> AccelGeometry<'_> {
        AccelGeometry {
            meshes: vec![mesh(&self.ground)],
            spheres: &[],
            prototypes: vec![self.proto.iter().map(mesh).collect()],
            instances: &self.instances,
        }
    }

    fn flattened(&self) -> AccelGeometry<'_> {
        AccelGeometry {
            meshes: std::iter::once(&self.ground)
                .chain(&self.flat)
                .map(mesh)
                .collect(),
            ..Default::default()
        }
    }
}

/// An instanced hit renamed to the flattened geometry's ids.
fn as_flat(h: Hit) -> Hit {
    if h.inst_id == NO_INSTANCE {
        return h;
    }
    Hit {
        geom_id: 1 + 2 * h.inst_id + h.geom_id,
        inst_id: NO_INSTANCE,
        ..h
    }
}

type OwnedMesh = (Vec<Vec3>, Vec<[u32; 3]>);

fn mesh(m: &OwnedMesh) -> TriMeshRef<'_> {
    TriMeshRef {
        positions: &m.0,
        triangles: &m.1,
    }
}

fn rays(count: usize) -> Vec<Ray> {
    let mut rng = Rng(12);
    (0..count)
        .map(|i| match i % 3 {
            0 => Ray::new(rng.vec(-9.0, 9.0), rng.dir()),
            1 => Ray::new(Vec3::new(0.0, 0.0, 6.0) + rng.vec(-0.3, 0.3), rng.dir()),
            _ => Ray::segment(rng.vec(-7.0, 7.0), rng.dir(), rng.range(0.5, 8.0)),
        })
        .collect()
}

#[test]
fn instanced_geometry_hits_what_the_flattened_geometry_hits_on_every_backend() {
    let scene = Placed::new();
    let flat = build(Backend::Bvh, &scene.flattened());
    let rays = rays(6000);
    for backend in all_backends() {
        let inst = build(backend, &scene.instanced());
        let (mut hits, mut on_instances, mut id_mismatches, mut occ_mismatches) = (0, 0, 0, 0);
        let mut batch = vec![None; rays.len()];
        inst.intersect_batch(&rays, &mut batch);
        for (ray, batched) in rays.iter().zip(&batch) {
            let a = inst.intersect(ray);
            assert_eq!(&a, batched, "{backend}: batch vs single for {ray:?}");
            hits += a.is_some() as usize;
            on_instances += a.is_some_and(|h| h.inst_id != NO_INSTANCE) as usize;
            let what = format!("{backend} instanced vs flat");
            if !assert_hits_agree(a.map(as_flat), flat.intersect(ray), ray, 2e-5, &what) {
                id_mismatches += 1;
            }
            occ_mismatches += (inst.occluded(ray) != flat.occluded(ray)) as usize;
        }
        assert!(
            on_instances > rays.len() / 4,
            "{backend}: {on_instances} instance hits"
        );
        assert!(hits > on_instances, "{backend}: the ground is never hit");
        assert!(
            id_mismatches < rays.len() / 200,
            "{backend}: {id_mismatches} id mismatches"
        );
        assert!(
            occ_mismatches < rays.len() / 500,
            "{backend}: {occ_mismatches} occluded mismatches"
        );
    }
}

#[test]
fn bvh_matches_brute_force_bit_for_bit_on_instances() {
    let scene = Placed::new();
    let geo = scene.instanced();
    let (bvh, brute) = (build(Backend::Bvh, &geo), build(Backend::Brute, &geo));
    for ray in &rays(6000) {
        let (a, b) = (bvh.intersect(ray), brute.intersect(ray));
        assert_eq!(
            a.map(|h| (h.t, h.inst_id)),
            b.map(|h| (h.t, h.inst_id)),
            "{ray:?}"
        );
        assert_eq!(bvh.occluded(ray), brute.occluded(ray), "{ray:?}");
    }
}

#[test]
fn instance_hit_has_analytic_t_and_render_space_normal() {
    // A unit quad in the local xy plane (normal +z), stretched ×3 along x,
    // turned 90° about x (local +z → render −y) and moved to y = 5.
    let quad = (
        vec![
            Vec3::new(-0.5, -0.5, 0.0),
            Vec3::new(0.5, -0.5, 0.0),
            Vec3::new(0.5, 0.5, 0.0),
            Vec3::new(-0.5, 0.5, 0.0),
        ],
        vec![[0u32, 1, 2], [0, 2, 3]],
    );
    let x = Affine3A::from_translation(Vec3::new(0.0, 5.0, 0.0))
        * Affine3A::from_rotation_x(std::f32::consts::FRAC_PI_2)
        * Affine3A::from_scale(Vec3::new(3.0, 1.0, 1.0));
    let instances = [InstanceRef {
        prototype: 0,
        render_from_local: x,
        local_from_render: x.inverse(),
    }];
    let geo = AccelGeometry {
        prototypes: vec![vec![TriMeshRef {
            positions: &quad.0,
            triangles: &quad.1,
        }]],
        instances: &instances,
        ..Default::default()
    };
    for backend in all_backends() {
        let accel = build(backend, &geo);
        // x = 1.2 is inside only because of the ×3 stretch; d has length 2.
        let hit = accel
            .intersect(&Ray::new(
                Vec3::new(1.2, 0.0, 0.1),
                Vec3::new(0.0, 2.0, 0.0),
            ))
            .unwrap_or_else(|| panic!("{backend}: missed"));
        assert_eq!(hit.inst_id, 0, "{backend}");
        assert!((hit.t - 2.5).abs() < 1e-5, "{backend}: t = {}", hit.t);
        let n = hit.n_geo.normalize();
        assert!(
            (n - Vec3::new(0.0, -1.0, 0.0)).length() < 1e-5,
            "{backend}: n = {n}"
        );
        assert!(accel
            .intersect(&Ray::new(Vec3::new(1.6, 0.0, 0.1), Vec3::Y))
            .is_none());
        assert!(!accel.occluded(&Ray::segment(Vec3::new(1.2, 0.0, 0.1), Vec3::Y, 4.9)));
        assert!(accel.occluded(&Ray::segment(Vec3::new(1.2, 0.0, 0.1), Vec3::Y, 5.1)));
    }
}
