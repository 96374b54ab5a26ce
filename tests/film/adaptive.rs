//! Adaptive sampling (`render --adaptive`, src/render/adaptive.rs): the
//! same budget of pixels × spp samples per view, shared by a pilot pass's
//! per-pixel error. A frame whose left half is a constant sky (every sample
//! exact) and whose right half is a textured, bumped wall (sub-pixel detail:
//! real noise) must come out unbiased, with its samples moved to the wall,
//! exactly the budget spent, the same bytes on 1 and 2 threads, and never
//! adaptive in reference mode.

use crate::common;

use common::scene_from_toml;
use parallax::film::Film;
use parallax::render::recipe::{FrameRecipe, FrameSource, FrameSpec, Overrides};
use parallax::render::FrameOutput;
use parallax::scene::LoadedScene;

const W: u32 = 96;
const H: u32 = 54;

/// Sky on the image's left (world +y), a wall 5 m ahead on its right.
fn half_wall(filter: bool) -> LoadedScene {
    scene_from_toml(&format!(
        "{}baselines_cm = [10.0]\n[render]\nspp = 16\nmax_depth = 3\nfilter_indirect = {filter}\n\
         [sky]\nkind = \"constant\"\nle = [1.0, 1.0, 1.0]\n\
         [[material]]\nname = \"m\"\nkind = \"diffuse\"\nalbedo = [0.6, 0.6, 0.6]\n\
         texture = {{ kind = \"asphalt\", seed = 3, bump = 2.0 }}\n\
         [[object]]\nkind = \"quad\"\nsize = [400.0, 400.0]\nmaterial = \"m\"\n\
         transform = {{ translate = [5.0, -200.0, 1.65], rotate_deg = [0.0, -90.0, 0.0] }}\n",
        common::camera_block(W, H, [0.0, 0.0, 1.65])
    ))
}

/// Renders `loaded` at `spp` with sample seed `seed`.
fn render(
    loaded: &LoadedScene,
    spp: u32,
    seed: u64,
    adaptive: bool,
    reference: bool,
) -> FrameOutput {
    let spec = FrameSpec {
        overrides: Overrides {
            spp: Some(spp),
            seed: Some(seed),
            ..Overrides::default()
        },
        adaptive,
        reference,
        ..FrameSpec::default()
    };
    let recipe = FrameRecipe::new(FrameSource::scene(loaded.clone()), &spec).expect("recipe");
    assert_eq!(recipe.settings.adaptive, adaptive && !reference);
    recipe.prepare().expect("builds").render(&|_, _| {}).out
}

/// Luminance of the left view's wall and sky pixels (by exact depth; the
/// two columns at the edge between them are in neither).
fn wall_and_sky(out: &FrameOutput) -> (Vec<f64>, Vec<f64>) {
    let film: &Film = &out.images[0];
    let z = |i: usize, j: usize| out.left.depth_z[j * W as usize + i];
    let (mut wall, mut sky) = (vec![], vec![]);
    for j in 0..H as usize {
        for i in 1..W as usize - 1 {
            let px = film.get(i, j);
            let y = (0.2126 * px.x + 0.7152 * px.y + 0.0722 * px.z) as f64;
            let finite = [z(i - 1, j), z(i, j), z(i + 1, j)].map(f64::is_finite);
            match finite {
                [true, true, true] => wall.push(y),
                [false, false, false] => sky.push(y),
                _ => {}
            }
        }
    }
    (wall, sky)
}

fn mean(v: &[f64]) -> f64 {
    v.iter().sum::<f64>() / v.len() as f64
}

fn mse(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y).powi(2)).sum::<f64>() / a.len() as f64
}

#[test]
fn adaptive_is_unbiased_and_moves_samples_to_the_noisy_half() {
    let scene = half_wall(false);
    let (reference, _) = wall_and_sky(&render(&scene, 256, 7, false, false));
    let uniform = render(&scene, 16, 1, false, false);
    let (u_wall, u_sky) = wall_and_sky(&uniform);
    let (u2_wall, _) = wall_and_sky(&render(&scene, 16, 2, false, false));
    let adaptive = render(&scene, 16, 1, true, false);
    let (a_wall, a_sky) = wall_and_sky(&adaptive);
    assert!(
        u_wall.len() > 1000 && u_sky.len() > 1000,
        "both halves in view"
    );
    // The sky is exact in any pixel however many samples it has.
    let sky_off = u_sky
        .iter()
        .chain(&a_sky)
        .fold(0.0f64, |a, &y| a.max((y - 1.0).abs()));
    assert!(sky_off < 1e-5, "sky off by {sky_off}");
    // The budget: pixels × spp per view (two views), not a sample more.
    let budget = 2 * (W * H) as u64 * 16;
    assert_eq!(uniform.stats.samples, budget);
    assert_eq!(adaptive.stats.samples, budget);
    // Per-pixel noise of a 16-spp uniform render from two seeds: the
    // image mean's standard error. Adaptive has as many samples in all,
    // so its error bar is no wider.
    let n = u_wall.len() as f64;
    let var_px = mse(&u_wall, &u2_wall) / 2.0;
    let se = (var_px / n).sqrt();
    let (m_ref, m_u, m_a) = (mean(&reference), mean(&u_wall), mean(&a_wall));
    eprintln!("wall mean: reference {m_ref:.5} uniform {m_u:.5} adaptive {m_a:.5} (se {se:.5})");
    assert!(
        se > 1e-4,
        "the wall must be noisy for the test to mean anything"
    );
    assert!(
        (m_a - m_u).abs() < 4.0 * (2.0f64).sqrt() * se,
        "adaptive vs uniform"
    );
    assert!(
        (m_a - m_ref).abs() < 4.0 * se,
        "adaptive vs the 256-spp reference"
    );
    // The sky's samples went to the wall: its error against the reference
    // falls to about 16/26 of the uniform one's (sky pixels keep the
    // minimum 6 of 16; the wall shares the rest).
    let (e_u, e_a) = (mse(&u_wall, &reference), mse(&a_wall, &reference));
    eprintln!(
        "wall MSE: uniform {e_u:.3e} adaptive {e_a:.3e} ({:.2}×)",
        e_a / e_u
    );
    assert!(
        e_a < 0.8 * e_u,
        "adaptive wall MSE {e_a:.3e} vs uniform {e_u:.3e}"
    );
}

#[test]
fn adaptive_with_the_filters_keeps_the_mean() {
    // Filtered, the denoiser reads means and variances over each pixel's
    // own count: a wrong count would scale the wall's filtered light.
    let scene = half_wall(true);
    let (u_wall, _) = wall_and_sky(&render(&scene, 16, 1, false, false));
    let (u2_wall, _) = wall_and_sky(&render(&scene, 16, 2, false, false));
    let (a_wall, _) = wall_and_sky(&render(&scene, 16, 1, true, false));
    let se = (mse(&u_wall, &u2_wall) / 2.0 / u_wall.len() as f64).sqrt();
    let (m_u, m_a) = (mean(&u_wall), mean(&a_wall));
    eprintln!("filtered wall mean: uniform {m_u:.5} adaptive {m_a:.5} (se {se:.5})");
    assert!((m_a - m_u).abs() < 4.0 * (2.0f64).sqrt() * se.max(1e-4));
}

#[test]
fn adaptive_bytes_do_not_depend_on_threads() {
    let scene = half_wall(true);
    let on = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("pool")
            .install(|| render(&scene, 8, 5, true, false))
    };
    let (one, two) = (on(1), on(2));
    assert_eq!(one.images, two.images, "1 vs 2 threads");
    // Left and right views allocate on their own pilots: different images.
    assert_ne!(one.images[0].rgb, one.images[1].rgb);
}

#[test]
fn reference_mode_is_never_adaptive() {
    let scene = half_wall(false);
    let plain = render(&scene, 8, 4, false, true);
    let asked = render(&scene, 8, 4, true, true);
    assert_eq!(plain.images, asked.images);
    // And reference mode is the plain uniform render (filters off here).
    assert_eq!(render(&scene, 8, 4, false, false).images, plain.images);
}
