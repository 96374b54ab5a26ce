//! Parity of the accelerator backends: the pure-Rust BVH against the brute-force
//! scan (same primitive routines, so any difference is a traversal bug), Embree
//! against the BVH (independent implementations), any-hit against closest-hit,
//! batches against single rays, and watertightness on shared edges/vertices;
//! instanced geometry against the same flattened (`accel_parity/instances.rs`).
//!
//! Scenes are random triangle soups plus spheres from a fixed-seed SplitMix64,
//! so every run tests the same rays.

use glam::{Vec3, Vec4};
use parallax::accel::{
    build_accel, validate_geometry, Accel, AccelError, AccelGeometry, AnyAccel, Backend, Hit, Ray,
    TriMeshRef,
};

#[path = "accel_parity/instances.rs"]
mod instances;

/// SplitMix64: tiny, deterministic, good enough for test geometry.
struct Rng(u64);

impl Rng {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in [0, 1).
    fn f(&mut self) -> f32 {
        (self.next_u64() >> 40) as f32 / (1u64 << 24) as f32
    }
    fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.f()
    }
    fn vec(&mut self, lo: f32, hi: f32) -> Vec3 {
        Vec3::new(self.range(lo, hi), self.range(lo, hi), self.range(lo, hi))
    }
    fn dir(&mut self) -> Vec3 {
        loop {
            let v = self.vec(-1.0, 1.0);
            let l = v.length_squared();
            if l > 1e-4 && l <= 1.0 {
                return v / l.sqrt();
            }
        }
    }
}

/// Owned geometry: a random soup (one mesh), a tessellated closed box (second
/// mesh, shared vertices) and random spheres.
struct TestScene {
    soup_positions: Vec<Vec3>,
    soup_triangles: Vec<[u32; 3]>,
    closed: (Vec<Vec3>, Vec<[u32; 3]>),
    spheres: Vec<Vec4>,
}

impl TestScene {
    fn random(seed: u64, triangle_count: usize, sphere_count: usize) -> TestScene {
        let mut rng = Rng(seed);
        let mut soup_positions = Vec::new();
        let mut soup_triangles = Vec::new();
        for i in 0..triangle_count {
            let centre = rng.vec(-5.0, 5.0);
            let size = rng.range(0.05, 1.5);
            let mut p: Vec<Vec3> = (0..3).map(|_| centre + size * rng.vec(-1.0, 1.0)).collect();
            // Every seventh triangle is axis-aligned (flat roads, walls): flat boxes.
            if i % 7 == 0 {
                let axis = i % 3;
                for q in &mut p {
                    q[axis] = centre[axis];
                }
            }
            let base = soup_positions.len() as u32;
            soup_positions.extend(p);
            soup_triangles.push([base, base + 1, base + 2]);
        }
        let spheres = (0..sphere_count)
            .map(|_| rng.vec(-5.0, 5.0).extend(rng.range(0.05, 0.8)))
            .collect();
        TestScene {
            soup_positions,
            soup_triangles,
            closed: tessellated_box(Vec3::new(-1.3, -0.7, -1.1), Vec3::new(1.7, 1.1, 0.9), 6),
            spheres,
        }
    }

    fn geometry(&self) -> AccelGeometry<'_> {
        AccelGeometry {
            meshes: vec![
                TriMeshRef {
                    positions: &self.soup_positions,
                    triangles: &self.soup_triangles,
                },
                TriMeshRef {
                    positions: &self.closed.0,
                    triangles: &self.closed.1,
                },
            ],
            spheres: &self.spheres,
            ..Default::default()
        }
    }
}

/// A closed box whose six faces are `n`×`n` grids sharing vertices along the
/// box edges, slightly rotated so no face is axis-aligned.
fn tessellated_box(lo: Vec3, hi: Vec3, n: u32) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let mut key_to_index = std::collections::HashMap::new();
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    let rot = glam::Quat::from_euler(glam::EulerRot::XYZ, 0.3, -0.2, 0.1);
    let mut vertex = |c: [u32; 3]| -> u32 {
        *key_to_index.entry(c).or_insert_with(|| {
            let f = Vec3::new(c[0] as f32, c[1] as f32, c[2] as f32) / n as f32;
            positions.push(rot * (lo + f * (hi - lo)));
            positions.len() as u32 - 1
        })
    };
    for axis in 0..3 {
        for side in [0, n] {
            for i in 0..n {
                for j in 0..n {
                    let corner = |di: u32, dj: u32| {
                        let mut c = [0u32; 3];
                        c[axis] = side;
                        c[(axis + 1) % 3] = i + di;
                        c[(axis + 2) % 3] = j + dj;
                        c
                    };
                    let (a, b, c, d) = (
                        vertex(corner(0, 0)),
                        vertex(corner(1, 0)),
                        vertex(corner(1, 1)),
                        vertex(corner(0, 1)),
                    );
                    triangles.push([a, b, c]);
                    triangles.push([a, c, d]);
                }
            }
        }
    }
    (positions, triangles)
}

/// Rays of every kind the renderer issues: from outside, from inside the
/// closed box, segments, and rays starting on a triangle.
fn random_rays(scene: &TestScene, seed: u64, count: usize) -> Vec<Ray> {
    let mut rng = Rng(seed);
    (0..count)
        .map(|i| match i % 4 {
            0 => Ray::new(rng.vec(-8.0, 8.0), rng.dir()),
            1 => Ray::new(rng.vec(-0.5, 0.5), rng.dir() * rng.range(0.2, 3.0)),
            2 => Ray::segment(rng.vec(-6.0, 6.0), rng.dir(), rng.range(0.1, 6.0)),
            _ => {
                let tri = scene.soup_triangles
                    [(rng.next_u64() % scene.soup_triangles.len() as u64) as usize];
                let (u, v) = (rng.f() * 0.5, rng.f() * 0.5);
                let [p0, p1, p2] = tri.map(|k| scene.soup_positions[k as usize]);
                Ray::new((1.0 - u - v) * p0 + u * p1 + v * p2, rng.dir())
            }
        })
        .collect()
}

fn build(backend: Backend, geo: &AccelGeometry) -> AnyAccel {
    build_accel(backend, geo).unwrap_or_else(|e| panic!("{backend}: {e}"))
}

/// Agreement of two closest hits: same t within `rel_tol` (divided by the
/// incidence cosine, plus a tiny absolute slack near t = 0), and the same primitive unless the hits are
/// coincident (shared edges, overlapping triangles). Returns whether the ids
/// matched.
fn assert_hits_agree(a: Option<Hit>, b: Option<Hit>, ray: &Ray, rel_tol: f32, what: &str) -> bool {
    match (a, b) {
        (None, None) => true,
        (Some(a), Some(b)) => {
            // A hit-point error δ across the surface moves t by δ / cos θ: grazing
            // hits are ill-conditioned for any algorithm, so scale by 1 / cos θ.
            let cos = a.n_geo.normalize().dot(ray.d.normalize()).abs().max(1e-3);
            let tol = rel_tol * a.t.abs().max(b.t.abs()) / cos + 1e-6;
            assert!(
                (a.t - b.t).abs() <= tol,
                "{what}: {a:?} vs {b:?} for {ray:?}",
            );
            let same = (a.geom_id, a.prim_id) == (b.geom_id, b.prim_id);
            if same {
                let cos = a.n_geo.normalize().dot(b.n_geo.normalize());
                assert!(
                    cos > 0.9999,
                    "{what}: normals {} vs {} for {ray:?}",
                    a.n_geo,
                    b.n_geo
                );
                assert!(
                    (a.u - b.u).abs() < 1e-3 && (a.v - b.v).abs() < 1e-3,
                    "{what}: barycentrics ({}, {}) vs ({}, {})",
                    a.u,
                    a.v,
                    b.u,
                    b.v
                );
            }
            same
        }
        (a, b) => panic!("{what}: {a:?} vs {b:?} for {ray:?}"),
    }
}

#[test]
fn bvh_matches_brute_force_on_random_soup() {
    let scene = TestScene::random(1, 3000, 60);
    let geo = scene.geometry();
    let (bvh, brute) = (build(Backend::Bvh, &geo), build(Backend::Brute, &geo));
    let rays = random_rays(&scene, 2, 8000);
    let mut hits = 0;
    let mut id_mismatches = 0;
    for ray in &rays {
        let (a, b) = (bvh.intersect(ray), brute.intersect(ray));
        hits += a.is_some() as usize;
        // Same routines on the same primitive give bit-identical t.
        if !assert_hits_agree(a, b, ray, 0.0, "bvh vs brute") {
            id_mismatches += 1;
        }
        assert_eq!(
            bvh.occluded(ray),
            brute.occluded(ray),
            "occluded for {ray:?}"
        );
    }
    assert!(hits > rays.len() / 3, "test scene too sparse: {hits} hits");
    assert!(
        id_mismatches < rays.len() / 100,
        "{id_mismatches} coincident-hit id mismatches"
    );
}

#[test]
fn any_hit_agrees_with_closest_hit_on_segments() {
    let scene = TestScene::random(3, 2000, 40);
    let geo = scene.geometry();
    let mut rng = Rng(4);
    let rays: Vec<Ray> = (0..4000)
        .map(|_| Ray::segment(rng.vec(-6.0, 6.0), rng.dir(), rng.range(0.05, 4.0)))
        .collect();
    for backend in all_backends() {
        let accel = build(backend, &geo);
        let mut batch = vec![false; rays.len()];
        accel.occluded_batch(&rays, &mut batch);
        let mut blocked = 0;
        for (ray, &batched) in rays.iter().zip(&batch) {
            let closest = accel.intersect(ray);
            assert_eq!(
                accel.occluded(ray),
                closest.is_some(),
                "{backend} for {ray:?}"
            );
            assert_eq!(batched, closest.is_some(), "{backend} batch for {ray:?}");
            blocked += closest.is_some() as usize;
        }
        assert!(
            blocked > 200 && blocked < rays.len() - 200,
            "{backend}: {blocked} blocked"
        );
    }
}

#[test]
fn batch_matches_single_rays() {
    let scene = TestScene::random(5, 2000, 40);
    let geo = scene.geometry();
    // 1003 rays: not a multiple of the packet width, so the tail mask is used.
    let rays = random_rays(&scene, 6, 1003);
    for backend in all_backends() {
        let accel = build(backend, &geo);
        let mut hits = vec![None; rays.len()];
        accel.intersect_batch(&rays, &mut hits);
        for (ray, &batched) in rays.iter().zip(&hits) {
            assert_hits_agree(batched, accel.intersect(ray), ray, 1e-6, backend.name());
        }
    }
}

#[cfg(feature = "embree")]
#[test]
fn embree_matches_bvh_on_random_soup() {
    let scene = TestScene::random(7, 3000, 60);
    let geo = scene.geometry();
    let (embree, bvh) = (build(Backend::Embree, &geo), build(Backend::Bvh, &geo));
    // Rays that start on a surface are left out: whether the surface itself is
    // hit at t ≈ 0 is rounding-dependent and differs between the two tests.
    let rays: Vec<Ray> = random_rays(&scene, 8, 12000)
        .into_iter()
        .enumerate()
        .filter(|(i, _)| i % 4 != 3)
        .map(|(_, r)| r)
        .collect();
    let mut id_mismatches = 0;
    for ray in &rays {
        if !assert_hits_agree(
            embree.intersect(ray),
            bvh.intersect(ray),
            ray,
            1e-6,
            "embree vs bvh",
        ) {
            id_mismatches += 1;
        }
    }
    assert!(
        id_mismatches < rays.len() / 100,
        "{id_mismatches} coincident-hit id mismatches"
    );
}

/// The path pass's shading queries (Embree: the non-robust twin scene) find
/// the same hits as the watertight queries ground truth uses.
#[cfg(feature = "embree")]
#[test]
fn embree_shading_twin_matches_watertight_scene() {
    let scene = TestScene::random(11, 3000, 60);
    let geo = scene.geometry();
    let embree = build(Backend::Embree, &geo);
    // Rays starting on a surface are left out (t ≈ 0 hits are rounding-dependent).
    let rays: Vec<Ray> = random_rays(&scene, 12, 8000)
        .into_iter()
        .enumerate()
        .filter(|(i, _)| i % 4 != 3)
        .map(|(_, r)| r)
        .collect();
    let mut batch = vec![None; rays.len()];
    embree.intersect_batch_shading(&rays, &mut batch);
    let (mut id_mismatches, mut hits) = (0, 0);
    for (ray, &batched) in rays.iter().zip(&batch) {
        let shading = embree.intersect_shading(ray);
        assert_hits_agree(batched, shading, ray, 1e-6, "shading batch vs single");
        assert_eq!(embree.occluded_shading(ray), shading.is_some());
        hits += shading.is_some() as usize;
        if !assert_hits_agree(
            shading,
            embree.intersect(ray),
            ray,
            1e-6,
            "shading vs watertight",
        ) {
            id_mismatches += 1;
        }
    }
    assert!(hits > rays.len() / 4, "only {hits} hits");
    assert!(
        id_mismatches < rays.len() / 100,
        "{id_mismatches} coincident-hit id mismatches"
    );
}

#[test]
fn rays_through_shared_edges_and_vertices_never_leak() {
    let (positions, triangles) =
        tessellated_box(Vec3::new(-1.0, -2.0, -0.5), Vec3::new(2.0, 1.0, 1.5), 8);
    let geo = AccelGeometry {
        meshes: vec![TriMeshRef {
            positions: &positions,
            triangles: &triangles,
        }],
        spheres: &[],
        ..Default::default()
    };
    let inside = positions.iter().copied().sum::<Vec3>() / positions.len() as f32;
    // Aim exactly at every vertex and at every edge midpoint, from inside and
    // back along the same line from outside: a closed surface is always hit.
    let mut targets: Vec<Vec3> = positions.clone();
    for t in &triangles {
        for e in 0..3 {
            targets.push(0.5 * (positions[t[e] as usize] + positions[t[(e + 1) % 3] as usize]));
        }
    }
    for backend in all_backends() {
        let accel = build(backend, &geo);
        for &target in &targets {
            let from_inside = Ray::new(inside, target - inside);
            let hit = accel.intersect(&from_inside);
            assert!(
                hit.is_some_and(|h| (h.t - 1.0).abs() < 1e-4),
                "{backend}: leak towards {target}"
            );
            assert!(
                accel.occluded(&from_inside),
                "{backend}: any-hit leak towards {target}"
            );
            let outside = inside + 3.0 * (target - inside);
            let from_outside = Ray::segment(outside, inside - outside, 1.0);
            let hit = accel.intersect(&from_outside);
            assert!(
                hit.is_some_and(|h| (h.t - 2.0 / 3.0).abs() < 1e-4),
                "{backend}: leak through {target} from outside: {hit:?}"
            );
            assert!(
                accel.occluded(&from_outside),
                "{backend}: any-hit leak through {target}"
            );
        }
    }
}

#[test]
fn concurrent_queries_match_serial_queries() {
    fn assert_send_sync<T: Send + Sync>() {}
    assert_send_sync::<AnyAccel>();
    let scene = TestScene::random(9, 2000, 40);
    let geo = scene.geometry();
    let rays = random_rays(&scene, 10, 4000);
    for backend in all_backends() {
        let accel = build(backend, &geo);
        let serial: Vec<Option<Hit>> = rays.iter().map(|r| accel.intersect(r)).collect();
        let mut parallel = vec![None; rays.len()];
        let half = rays.len() / 2;
        let (lo, hi) = parallel.split_at_mut(half);
        std::thread::scope(|s| {
            let accel = &accel;
            s.spawn(|| accel.intersect_batch(&rays[..half], lo));
            s.spawn(|| {
                for (r, h) in rays[half..].iter().zip(hi.iter_mut()) {
                    *h = accel.intersect(r);
                }
            });
        });
        for ((ray, &a), &b) in rays.iter().zip(&serial).zip(&parallel) {
            assert_hits_agree(a, b, ray, 1e-6, backend.name());
        }
    }
}

#[test]
fn empty_geometry_misses_everything() {
    let geo = AccelGeometry::default();
    let empty_mesh = AccelGeometry {
        meshes: vec![TriMeshRef {
            positions: &[],
            triangles: &[],
        }],
        spheres: &[],
        ..Default::default()
    };
    let rays = [
        Ray::new(Vec3::ZERO, Vec3::Z),
        Ray::segment(Vec3::ONE, -Vec3::ONE, 5.0),
    ];
    for g in [&geo, &empty_mesh] {
        for backend in all_backends() {
            let accel = build(backend, g);
            let mut hits = [Some(dummy_hit()); 2];
            accel.intersect_batch(&rays, &mut hits);
            assert_eq!(hits, [None, None], "{backend}");
            assert!(rays
                .iter()
                .all(|r| accel.intersect(r).is_none() && !accel.occluded(r)));
        }
    }
}

#[test]
fn sphere_hits_report_sphere_ids_and_outward_normal() {
    let spheres = [Vec4::new(0.0, 0.0, 5.0, 1.0), Vec4::new(0.0, 0.0, 9.0, 2.0)];
    let positions = [
        Vec3::new(-1.0, -1.0, 20.0),
        Vec3::new(1.0, -1.0, 20.0),
        Vec3::new(0.0, 1.0, 20.0),
    ];
    let triangles = [[0, 1, 2]];
    let geo = AccelGeometry {
        meshes: vec![TriMeshRef {
            positions: &positions,
            triangles: &triangles,
        }],
        spheres: &spheres,
        ..Default::default()
    };
    for backend in all_backends() {
        let accel = build(backend, &geo);
        let hit = accel.intersect(&Ray::new(Vec3::ZERO, Vec3::Z)).unwrap();
        assert_eq!((hit.geom_id, hit.prim_id), (1, 0), "{backend}");
        assert!((hit.t - 4.0).abs() < 1e-5, "{backend}: t = {}", hit.t);
        assert!(
            hit.n_geo.normalize().dot(-Vec3::Z) > 0.9999,
            "{backend}: n = {}",
            hit.n_geo
        );
        // Past the first sphere: the second, then the triangle.
        let mut ray = Ray::new(Vec3::ZERO, Vec3::Z);
        ray.tmin = 6.5;
        let hit = accel.intersect(&ray).unwrap();
        assert_eq!((hit.geom_id, hit.prim_id), (1, 1), "{backend}");
        assert!((hit.t - 7.0).abs() < 1e-5, "{backend}: t = {}", hit.t);
        ray.tmin = 11.5;
        let hit = accel.intersect(&ray).unwrap();
        assert_eq!((hit.geom_id, hit.prim_id), (0, 0), "{backend}");
        assert!((hit.t - 20.0).abs() < 1e-5 && hit.n_geo.normalize().dot(Vec3::Z) > 0.9999);
    }
}

#[test]
fn backend_names_round_trip_and_bad_input_errors() {
    for b in [Backend::Embree, Backend::Bvh, Backend::Brute] {
        assert_eq!(b.to_string().parse::<Backend>(), Ok(b));
    }
    assert!(matches!(
        "optix".parse::<Backend>(),
        Err(AccelError::UnknownBackend(_))
    ));
    let positions = [Vec3::ZERO, Vec3::X, Vec3::Y];
    let bad_index = [[0, 1, 2], [0, 1, 3]];
    let geo = AccelGeometry {
        meshes: vec![TriMeshRef {
            positions: &positions,
            triangles: &bad_index,
        }],
        spheres: &[],
        ..Default::default()
    };
    let expected = AccelError::IndexOutOfRange {
        geom_id: 0,
        prim_id: 1,
    };
    assert_eq!(validate_geometry(&geo), Err(expected.clone()));
    for backend in all_backends() {
        assert_eq!(build_accel(backend, &geo).err(), Some(expected.clone()));
    }
    let bad_sphere = [Vec4::new(0.0, 0.0, 0.0, -1.0)];
    let geo = AccelGeometry {
        meshes: Vec::new(),
        spheres: &bad_sphere,
        ..Default::default()
    };
    assert_eq!(
        validate_geometry(&geo),
        Err(AccelError::InvalidGeometry {
            geom_id: 0,
            index: 0
        })
    );
    #[cfg(not(feature = "embree"))]
    assert_eq!(
        build_accel(Backend::Embree, &AccelGeometry::default()).err(),
        Some(AccelError::EmbreeUnavailable)
    );
}

fn all_backends() -> Vec<Backend> {
    let mut b = vec![Backend::Bvh, Backend::Brute];
    if cfg!(feature = "embree") {
        b.push(Backend::Embree);
    }
    b
}

fn dummy_hit() -> Hit {
    Hit {
        t: 1.0,
        geom_id: 0,
        prim_id: 0,
        u: 0.0,
        v: 0.0,
        n_geo: Vec3::Z,
        inst_id: parallax::accel::NO_INSTANCE,
    }
}
