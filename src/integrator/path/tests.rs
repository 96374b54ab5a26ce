//! Splitting a path at its first vertex must not change it: tracing the
//! chunk's coherent shadow rays together in packets and then finishing each
//! path gives the same bits as `li_from_hit` tracing them one by one.

use std::path::Path;

use glam::Vec3;

use crate::accel::{build_accel, Accel, Backend, Ray};
use crate::camera::StereoRig;
use crate::integrator::{RenderCamera, Shading};
use crate::sampler::{SampleStream, StreamKey};
use crate::scene::{build_scene, load_scene};

#[test]
fn batched_first_shadows_give_the_same_bits_as_path_by_path() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/street.toml");
    let loaded = load_scene(&path).expect("street.toml loads");
    let rig = StereoRig::from_desc(&loaded.desc.camera);
    let scene = build_scene(&loaded, rig.left.center_world).expect("street builds");
    let accel = build_accel(Backend::default_backend(), &scene.accel_geometry()).expect("accel");
    let shading = Shading::new(&scene, &accel);
    let ctx = shading.context(5);
    let cam = RenderCamera::new(&rig.left, scene.origin_world);
    let key = StreamKey {
        seed: 5,
        frame: 0,
        view: 0,
    };
    let (w, h) = (cam.intrinsics.width, cam.intrinsics.height);
    // A sparse grid of pixels over the whole image, two samples each.
    let pixels: Vec<(u32, u32, u32)> = (0..24)
        .flat_map(|j| (0..32).flat_map(move |i| (0..2).map(move |s| (i, j, s))))
        .map(|(i, j, s)| (i * w / 32, j * h / 24, s))
        .collect();
    let camera_ray = |&(i, j, _): &(u32, u32, u32)| {
        let d = cam
            .dir(i as f64 + 0.5, j as f64 + 0.5)
            .as_vec3()
            .normalize();
        Ray::new(cam.center_f32(), d)
    };
    let stream = |&(i, j, s): &(u32, u32, u32)| SampleStream::new(key, i, j, s);

    let one_by_one: Vec<Vec3> = pixels
        .iter()
        .map(|px| {
            let ray = camera_ray(px);
            ctx.li_from_hit(
                ray,
                ctx.accel.intersect(&ray),
                cam.cone(ray.d),
                &mut stream(px),
                &mut 0,
            )
            .l
        })
        .collect();

    let mut streams: Vec<SampleStream> = pixels.iter().map(stream).collect();
    let mut starts: Vec<_> = pixels
        .iter()
        .zip(&mut streams)
        .map(|(px, st)| {
            let ray = camera_ray(px);
            ctx.start_path(ray, ctx.accel.intersect(&ray), cam.cone(ray.d), st, &mut 0)
        })
        .collect();
    let (mut rays, mut slots) = (Vec::new(), Vec::new());
    for (p, start) in starts.iter().enumerate() {
        start.collect_coherent(p, &mut rays, &mut slots);
    }
    let mut occluded = vec![false; rays.len()];
    ctx.accel.occluded_batch(&rays, &mut occluded);
    let n_blocked = occluded.iter().filter(|&&o| o).count();
    // The street has sunlit and shadowed points: both answers occur.
    assert!(
        n_blocked > 0 && n_blocked < rays.len(),
        "{n_blocked} of {}",
        rays.len()
    );
    for ((&(p, item), &o), ray) in slots.iter().zip(&occluded).zip(&rays) {
        // Packets answer as single rays do.
        assert_eq!(o, ctx.accel.occluded(ray));
        starts[p as usize].set_occluded(item, o);
    }
    let batched: Vec<Vec3> = starts
        .into_iter()
        .zip(&mut streams)
        .map(|(start, st)| ctx.finish_path(start, st, &mut 0).l)
        .collect();
    for (k, (a, b)) in one_by_one.iter().zip(&batched).enumerate() {
        assert_eq!(
            a.to_array().map(f32::to_bits),
            b.to_array().map(f32::to_bits),
            "path {k}"
        );
    }
}
