//! `parallax preview` through the real binary on a tiny render (a box on a
//! ground quad under a constant sky, 32×18, spp 1): the colour-coded maps
//! carry the documented colours where the ground truth says so, and bad input
//! exits 2 naming the path without writing anything.

use crate::common;

use std::fs;
use std::path::Path;

use common::cli::parallax_status;
use common::fixtures::analytic_text;
use parallax::output::{read_exr_f32_gray, read_pfm_gray, read_png_gray8, read_png_rgb8};
use parallax::preview::colormap::{semantic_colour, turbo, INVALID};
use parallax::preview::maps::zoom_for;
use parallax::preview::OCC_TINT;

const W: usize = 32;
const H: usize = 18;

/// Renders the tiny scene with baselines 54 and 300 cm into `dir/render`.
fn tiny_render(dir: &Path) -> std::path::PathBuf {
    let text = analytic_text("box_on_ground", (W as u32, H as u32), &[54.0, 300.0]);
    let scene = dir.join("scene.toml");
    fs::write(&scene, text).unwrap();
    let out = dir.join("render");
    let (code, err) = parallax_status(&[
        "render",
        scene.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    out
}

/// The map pixel (x, y) of a preview PNG (top-left canvas pixel of its zoomed block).
struct Preview {
    w: usize,
    h: usize,
    rgb: Vec<u8>,
}

impl Preview {
    fn open(path: &Path) -> Preview {
        let (w, h, rgb) = read_png_rgb8(path).unwrap();
        Preview { w, h, rgb }
    }
    fn at(&self, x: usize, y: usize) -> [u8; 3] {
        let z = zoom_for(W);
        let i = ((y * z) * self.w + x * z) * 3;
        [self.rgb[i], self.rgb[i + 1], self.rgb[i + 2]]
    }
    /// Dark pixels below the zoomed map: the legend's text.
    fn legend_ink(&self) -> usize {
        let top = H * zoom_for(W);
        self.rgb[top * self.w * 3..]
            .chunks(3)
            .filter(|c| c.iter().all(|&v| v < 64))
            .count()
    }
}

#[test]
fn preview_of_a_tiny_render_shows_the_documented_colours() {
    let d = tempfile::tempdir().unwrap();
    let render = tiny_render(d.path());
    let out = d.path().join("pv");
    let (code, err) = parallax_status(&[
        "preview",
        render.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(
        fs::read_dir(&out).unwrap().count(),
        8,
        "4 left maps + 2 per baseline"
    );
    let (_, _, depth) = read_exr_f32_gray(&render.join("left/depth/000000.exr")).unwrap();
    let (_, _, semantic) = read_png_gray8(&render.join("left/semantic/000000.png")).unwrap();
    let (_, _, left) = read_png_rgb8(&render.join("left/rgb/000000.png")).unwrap();
    let sem = Preview::open(&out.join("000000_semantic.png"));
    let dep = Preview::open(&out.join("000000_depth.png"));
    assert!(sem.w >= W * zoom_for(W) && sem.h > H * zoom_for(W));
    let (mut sky, mut occluded) = (0, 0);
    for y in 0..H {
        for x in 0..W {
            let i = y * W + x;
            // Semantic: CARLA's colour of the class; sky is (70, 130, 180).
            assert_eq!(sem.at(x, y), semantic_colour(semantic[i]), "({x}, {y})");
            if semantic[i] == parallax::scene::semantic::SKY {
                assert_eq!(sem.at(x, y), [70, 130, 180]);
                sky += 1;
            }
            // Depth: black exactly where there is no depth (sky).
            assert_eq!(dep.at(x, y) == INVALID, !depth[i].is_finite(), "({x}, {y})");
        }
    }
    assert!(
        sky > 0 && sky < W * H,
        "the view shows sky and ground: {sky}"
    );
    for b in ["baseline_054", "baseline_300"] {
        let (_, _, disp) = read_pfm_gray(&render.join(format!("{b}/disp/000000.pfm"))).unwrap();
        let (_, _, occ) = read_png_gray8(&render.join(format!("{b}/occ/000000.png"))).unwrap();
        let dp = Preview::open(&out.join(format!("000000_{b}_disp.png")));
        let op = Preview::open(&out.join(format!("000000_{b}_occ.png")));
        let max = disp
            .iter()
            .cloned()
            .filter(|d| d.is_finite())
            .fold(0.0, f32::max);
        for y in 0..H {
            for x in 0..W {
                let i = y * W + x;
                let d = disp[i];
                // Disparity: black for 0 (sky); the largest is turbo's red end.
                assert_eq!(dp.at(x, y) == INVALID, d == 0.0, "{b} ({x}, {y})");
                if d == max {
                    assert_eq!(dp.at(x, y), turbo(1.0));
                }
                // Occlusion: the left image, occluded pixels (c + tint) / 2.
                let c = [left[3 * i], left[3 * i + 1], left[3 * i + 2]];
                let want = if occ[i] == 0 {
                    c
                } else {
                    occluded += 1;
                    [0, 1, 2].map(|k| ((c[k] as u16 + OCC_TINT[k] as u16) / 2) as u8)
                };
                assert_eq!(op.at(x, y), want, "{b} ({x}, {y})");
            }
        }
        assert!(
            dp.legend_ink() > 200,
            "{b}: no legend text under the disparity map"
        );
    }
    assert!(occluded > 0, "the box occludes part of the ground");
    assert!(sem.legend_ink() > 200 && dep.legend_ink() > 200);
}

#[test]
fn preview_bad_inputs_exit_2_naming_the_path_and_write_nothing() {
    let d = tempfile::tempdir().unwrap();
    let render = tiny_render(d.path());
    let r = render.to_str().unwrap();
    let out = d.path().join("pv");
    let o = out.to_str().unwrap();
    let fails = |args: &[&str], needles: &[&str]| {
        let (code, err) = parallax_status(args);
        assert_eq!(code, 2, "{args:?}: {err}");
        for n in needles {
            assert!(err.contains(n), "stderr does not name `{n}`: {err}");
        }
        assert!(!out.exists(), "{args:?}: a failed run wrote {o}");
    };
    fails(
        &["preview", "/no/such/render", "-o", o],
        &["/no/such/render"],
    );
    fails(
        &["preview", r, "--frame", "3", "-o", o],
        &["left/depth/000003.exr"],
    );
    fails(
        &["preview", r, "--frame", "x", "-o", o],
        &["--frame", "'x'"],
    );
    // A corrupt map names its file, even with every other map readable.
    let sem = render.join("left/semantic/000000.png");
    fs::write(&sem, b"not a png").unwrap();
    fails(&["preview", r, "-o", o], &[sem.to_str().unwrap()]);
}
