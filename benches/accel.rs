//! Primary-ray throughput of the accelerator backends: single rays against
//! 8-wide batches on a synthetic terrain (a 400×400-quad height field, 320k
//! triangles) seen by a pinhole camera, 128×128 rays per iteration.
//! Run: `cargo bench --bench accel`.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use glam::Vec3;
use parallax::accel::{build_accel, Accel, AccelGeometry, Backend, Hit, Ray, TriMeshRef};

const GRID: u32 = 400;
const IMAGE: u32 = 128;

fn terrain() -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let n = GRID + 1;
    let positions = (0..n * n)
        .map(|k| {
            let (x, z) = ((k % n) as f32 * 0.25 - 50.0, (k / n) as f32 * 0.25);
            Vec3::new(x, 0.3 * (0.7 * x).sin() * (0.5 * z).cos(), z)
        })
        .collect();
    let mut triangles = Vec::with_capacity((2 * GRID * GRID) as usize);
    for j in 0..GRID {
        for i in 0..GRID {
            let a = j * n + i;
            triangles.push([a, a + 1, a + n + 1]);
            triangles.push([a, a + n + 1, a + n]);
        }
    }
    (positions, triangles)
}

/// Camera 1.6 m above the terrain looking down the +z axis, tilted 15° down.
fn primary_rays() -> Vec<Ray> {
    let o = Vec3::new(0.0, 1.6, 0.0);
    let (s, c) = 15f32.to_radians().sin_cos();
    (0..IMAGE * IMAGE)
        .map(|k| {
            let x = ((k % IMAGE) as f32 + 0.5) / IMAGE as f32 * 2.0 - 1.0;
            let y = ((k / IMAGE) as f32 + 0.5) / IMAGE as f32 * 2.0 - 1.0;
            let d_cam = Vec3::new(x, -y, 1.5);
            Ray::new(
                o,
                Vec3::new(
                    d_cam.x,
                    d_cam.y * c - d_cam.z * s,
                    d_cam.y * s + d_cam.z * c,
                ),
            )
        })
        .collect()
}

fn bench_primary(cr: &mut Criterion) {
    let (positions, triangles) = terrain();
    let geo = AccelGeometry {
        meshes: vec![TriMeshRef {
            positions: &positions,
            triangles: &triangles,
        }],
        spheres: &[],
        ..Default::default()
    };
    let rays = primary_rays();
    let mut hits: Vec<Option<Hit>> = vec![None; rays.len()];
    let mut group = cr.benchmark_group("primary");
    group
        .sample_size(10)
        .throughput(Throughput::Elements(rays.len() as u64));
    let mut backends = vec![Backend::Bvh];
    if cfg!(feature = "embree") {
        backends.insert(0, Backend::Embree);
    }
    for backend in backends {
        let accel = build_accel(backend, &geo).expect("build");
        group.bench_function(BenchmarkId::new("single", backend), |b| {
            b.iter(|| {
                for (r, h) in rays.iter().zip(hits.iter_mut()) {
                    *h = accel.intersect(r);
                }
            })
        });
        group.bench_function(BenchmarkId::new("packet8", backend), |b| {
            b.iter(|| accel.intersect_batch(&rays, &mut hits))
        });
    }
    group.finish();
}

criterion_group!(benches, bench_primary);
criterion_main!(benches);
