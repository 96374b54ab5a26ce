//! Shared set-up for integration tests: inline scenes, one-call frame renders,
//! and (in submodules) the real binary, dataset trees, light passes, towns.
//! Every test binary (tests/SUBJECT/main.rs) includes this module with
//! `#[path = "../common/mod.rs"] mod common;`.
// Each binary uses a subset of the helpers; the rest would warn as dead code.
#![allow(dead_code)]

pub mod boxes;
pub mod cli;
pub mod dataset;
pub mod fixtures;
pub mod light;
pub mod readback;
pub mod towns;
pub mod triangle;

use std::path::Path;

use parallax::accel::{Accel, AnyAccel, Backend};
use parallax::camera::StereoRig;
use parallax::denoise::ViewInputs;
use parallax::film::Film;
use parallax::integrator::path::PixelSum;
use parallax::integrator::{RenderCamera, Shading};
use parallax::render::recipe::{
    BuiltScene, FrameRecipe, FrameSource, FrameSpec, Overrides, PreparedFrame,
};
use parallax::render::FrameOutput;
use parallax::sampler::{SampleStream, StreamKey};
use parallax::scene::{parse_scene_str, LoadedScene, Scene};

/// Parses an inline scene (OBJ paths resolve against `tests/`).
pub fn scene_from_toml(text: &str) -> LoadedScene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/inline.toml");
    parse_scene_str(text, &path).unwrap_or_else(|e| panic!("inline scene: {e}"))
}

/// Everything of one rendered frame.
pub struct Rendered {
    pub rig: StereoRig,
    pub scene: Scene,
    pub accel: AnyAccel,
    pub out: FrameOutput,
}

/// The default baselines in metres (GROUND_TRUTH.md "Stereo rig"), rendered
/// by every scene that sets no `baselines_cm`.
pub const DEFAULT_BASELINES_M: [f64; 5] = [0.10, 0.54, 1.0, 2.0, 3.0];

/// Right camera centre of baseline `b` metres for a level rig looking along
/// +x: C_R = C_L + B·x_L, with the image x axis x_L = world −y (image right
/// is the world's −y when looking along +x with z up).
pub fn level_right_centre(c_left: glam::DVec3, b: f64) -> glam::DVec3 {
    c_left + glam::DVec3::new(0.0, -b, 0.0)
}

/// Builds and renders `loaded` with `spp` samples (0 = ground truth only).
pub fn render(loaded: &LoadedScene, backend: Backend, spp: u32) -> Rendered {
    let spec = FrameSpec {
        overrides: Overrides {
            spp: Some(spp),
            seed: Some(loaded.desc.render.seed.unwrap_or(1)),
            ..Overrides::default()
        },
        backend,
        ..FrameSpec::default()
    };
    let recipe = FrameRecipe::new(FrameSource::scene(loaded.clone()), &spec).expect("recipe");
    let prepared = recipe.prepare().expect("scene builds");
    let out = prepared.render(&|_, _| {}).out;
    let PreparedFrame { rig, built, .. } = prepared;
    let BuiltScene { scene, accel, .. } = built;
    // Every test scene must render without a NaN or infinite sample (the
    // renderer drops them from the pixel means, which would hide the bug).
    assert_eq!(out.stats.non_finite_samples, 0, "non-finite samples");
    Rendered {
        rig,
        scene,
        accel,
        out,
    }
}

/// The left view of `r` rebuilt sample by sample from `PathContext::li`
/// with the frame's streams (`spp`, `seed`, `max_depth`): the plain film and
/// the denoiser's inputs (fog light, light on the first surface).
pub fn rebuild_left(r: &Rendered, spp: u32, seed: u64, max_depth: u32) -> (Film, ViewInputs) {
    let scene = &r.scene;
    let shading = Shading::new(scene, &r.accel);
    let ctx = shading.context(max_depth);
    let cam = RenderCamera::new(&r.rig.left, scene.origin_world);
    let key = StreamKey {
        seed,
        frame: 0,
        view: 0,
    };
    let (wu, hu) = (r.rig.left.intrinsics.width, r.rig.left.intrinsics.height);
    let (w, h) = (wu as usize, hu as usize);
    let mut film = Film::new(w, h);
    let mut fog = ViewInputs::new(w, h);
    for j in 0..hu {
        for i in 0..wu {
            let mut sum = PixelSum::default();
            let mut rays = 0;
            for s in 0..spp {
                let mut stream = SampleStream::new(key, i, j, s);
                let ray = cam.jittered_ray(i, j, &mut stream);
                let hit = ctx.accel.intersect(&ray);
                let li = ctx.li_from_hit(ray, hit, cam.cone(ray.d), &mut stream, &mut rays);
                assert!(
                    li.l.is_finite(),
                    "non-finite sample {s} at pixel ({i}, {j})"
                );
                sum.add(&li);
            }
            let k = j as usize * w + i as usize;
            let n = spp as f32;
            film.rgb[k] = sum.l / n;
            fog.set_mean(k, &sum.denoise, n);
        }
    }
    (film, fog)
}

/// Renders an inline scene seen by a level rig of `size` pixels at
/// [0, 0, 1.5] m looking along +x with one 54 cm baseline: `[render]` with
/// `spp` (at least 1 in the file; 0 renders ground truth only), `max_depth`,
/// `seed` and the lines `render_keys`, then `body`.
pub fn render_inline(
    body: &str,
    size: (u32, u32),
    (spp, seed, max_depth): (u32, u64, u32),
    render_keys: &str,
    backend: Backend,
) -> Rendered {
    let text = format!(
        "{}baselines_cm = [54.0]\n[render]\nspp = {}\nmax_depth = {max_depth}\nseed = {seed}\n{render_keys}{body}",
        camera_block(size.0, size.1, [0.0, 0.0, 1.5]),
        spp.max(1)
    );
    render(&scene_from_toml(&text), backend, spp)
}

/// A ground of 4 m tiles with their tops at z = 0, from x = 2 m to 42 m
/// and y = −16 m to 16 m (the tiles of `ground_tile_pixels`): tile
/// (ix, iy) is a 0.2 m box of material m((ix + iy) mod 2), of diffuse
/// albedo `albedo[0]` or `albedo[1]`.
pub fn checker_ground(albedo: [f64; 2]) -> String {
    let mut s = String::new();
    for (k, a) in albedo.iter().enumerate() {
        s += &format!(
            "[[material]]\nname = \"m{k}\"\nkind = \"diffuse\"\nalbedo = [{a:?}, {a:?}, {a:?}]\n"
        );
    }
    for ix in 0..10i32 {
        for iy in -4..4 {
            let m = (ix + iy).rem_euclid(2);
            let (x, y) = (2.0 + 4.0 * ix as f64 + 2.0, 4.0 * iy as f64 + 2.0);
            s += &format!(
                "[[object]]\nkind = \"box\"\nsize = [4.0, 4.0, 0.2]\nmaterial = \"m{m}\"\ntransform = {{ translate = [{x:?}, {y:?}, -0.1] }}\n"
            );
        }
    }
    s
}

/// Left-view pixels on a ground of 4 m tiles at z = 0 spanning x = 2–42 m
/// and y = −16–16 m, nearer than `max_depth_z` metres, as (index,
/// `key(tile)`) for tile (ix, iy) counted from that corner: those whose
/// 4 neighbours' centres lie on tiles of the same key.
pub fn ground_tile_pixels<K: Copy + PartialEq>(
    r: &Rendered,
    max_depth_z: f64,
    key: impl Fn((i64, i64)) -> K,
) -> Vec<(usize, K)> {
    let cam = RenderCamera::new(&r.rig.left, r.scene.origin_world);
    let (w, h) = (
        cam.intrinsics.width as usize,
        cam.intrinsics.height as usize,
    );
    let z = &r.out.left.depth_z;
    let at = |i: usize, j: usize| -> Option<K> {
        let zz = z[j * w + i];
        if !zz.is_finite() || zz > max_depth_z {
            return None;
        }
        let p = r.scene.origin_world + cam.center + cam.dir(i as f64 + 0.5, j as f64 + 0.5) * zz;
        (p.z.abs() < 0.05 && (2.0..42.0).contains(&p.x) && p.y.abs() < 16.0).then(|| {
            key((
                ((p.x - 2.0) / 4.0).floor() as i64,
                ((p.y + 16.0) / 4.0).floor() as i64,
            ))
        })
    };
    let mut out = Vec::new();
    for j in 1..h - 1 {
        for i in 1..w - 1 {
            let Some(c) = at(i, j) else { continue };
            let same = [(i - 1, j), (i + 1, j), (i, j - 1), (i, j + 1)]
                .iter()
                .all(|&(a, b)| at(a, b) == Some(c));
            if same {
                out.push((j * w + i, c));
            }
        }
    }
    out
}

/// A camera block for a level rig at `position` looking along +x.
pub fn camera_block(width: u32, height: u32, position: [f64; 3]) -> String {
    format!(
        "[camera]\nwidth = {width}\nheight = {height}\nhfov_deg = 60.0\nposition = [{:?}, {:?}, {:?}]\n",
        position[0], position[1], position[2]
    )
}

/// A 16×9 scene of the one OBJ `m.obj` (beside the scene file) under
/// [`GREY_UNDER_SKY`]; `material` replaces the OBJ's own MTL materials.
pub fn obj_scene(material: Option<&str>) -> String {
    let material = material.map_or(String::new(), |m| format!("material = \"{m}\"\n"));
    format!(
        "{}{GREY_UNDER_SKY}[[object]]\nkind = \"obj\"\nfile = \"m.obj\"\n{material}",
        camera_block(16, 9, [0.0, 0.0, 1.5])
    )
}

/// Mean and standard error of a sample.
pub fn mean_stderr(v: &[f64]) -> (f64, f64) {
    let n = v.len() as f64;
    let mean = v.iter().sum::<f64>() / n;
    let var = v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, (var / n).sqrt())
}

/// A grey diffuse material under a white constant sky.
pub const GREY_UNDER_SKY: &str = r#"
[sky]
kind = "constant"
le = [1.0, 1.0, 1.0]
[[material]]
name = "grey"
kind = "diffuse"
albedo = [0.5, 0.5, 0.5]
"#;

/// A rendered view's first-surface images as the denoiser takes them.
pub fn aux(aov: &parallax::render::AovImages) -> parallax::denoise::SurfaceAux<'_> {
    parallax::denoise::SurfaceAux {
        albedo: &aov.albedo,
        normal: &aov.normal,
    }
}

/// Pixels of a `w` × `h` view (row-major) whose 3 × 3 neighbourhood lies
/// inside the image and where `same(centre, neighbour)` holds for all nine.
pub fn interior(w: usize, h: usize, same: impl Fn(usize, usize) -> bool) -> Vec<usize> {
    (0..w * h)
        .filter(|&k| {
            let (i, j) = (k % w, k / w);
            i > 0
                && j > 0
                && i + 1 < w
                && j + 1 < h
                && (j - 1..=j + 1).all(|jj| (i - 1..=i + 1).all(|ii| same(k, jj * w + ii)))
        })
        .collect()
}
