//! Noise must not be correlated between views (GROUND_TRUTH.md "Images and
//! noise"): correlated noise at equal pixel coordinates would be a false
//! zero-disparity signal. A uniform Lambert plane under a sky is rendered at
//! low spp; the residual noise of the left and right images is uncorrelated
//! both at equal coordinates and at the true disparity shift. The image
//! filter is off: filtered, the images keep mostly the shared signal (the
//! plane's shading), and the noise of filtered views is checked by
//! tests/denoise/direct.rs on the difference of two seeds.

use crate::common;

use common::{render, scene_from_toml};
use parallax::accel::Backend;

fn correlation(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len() as f64;
    let (ma, mb) = (a.iter().sum::<f64>() / n, b.iter().sum::<f64>() / n);
    let cov: f64 = a.iter().zip(b).map(|(x, y)| (x - ma) * (y - mb)).sum();
    let va: f64 = a.iter().map(|x| (x - ma).powi(2)).sum();
    let vb: f64 = b.iter().map(|y| (y - mb).powi(2)).sum();
    cov / (va * vb).sqrt()
}

#[test]
fn left_and_right_noise_are_uncorrelated() {
    // Fronto-parallel plane: constant disparity d = f·B/Z, chosen to be 8 px.
    let (w, h) = (128u32, 96u32);
    let f = 64.0 / 30f64.to_radians().tan();
    let z = f * 1.0 / 8.0;
    let text = format!(
        "{}baselines_cm = [100.0]\n[render]\nspp = 1\nmax_depth = 2\nseed = 9\nfilter_indirect = false\n[sky]\nkind = \"gradient\"\nzenith = [0.3, 0.5, 1.0]\nhorizon = [1.0, 1.0, 1.0]\nground = [0.2, 0.2, 0.2]\n[[material]]\nname = \"m\"\nkind = \"diffuse\"\nalbedo = [0.7, 0.7, 0.7]\n[[object]]\nkind = \"quad\"\nsize = [500.0, 500.0]\nmaterial = \"m\"\ntransform = {{ translate = [{z:?}, 0.0, 1.65], rotate_deg = [0.0, -90.0, 0.0] }}\n",
        common::camera_block(w, h, [0.0, 0.0, 1.65])
    );
    let r = render(&scene_from_toml(&text), Backend::default_backend(), 1);
    let (l, rt) = (&r.out.images[0].rgb, &r.out.images[1].rgb);
    let (mut a0, mut b0, mut a8, mut b8) = (vec![], vec![], vec![], vec![]);
    for j in 0..h as usize {
        for i in 8..w as usize {
            a0.push(l[j * w as usize + i].y as f64);
            b0.push(rt[j * w as usize + i].y as f64);
            a8.push(l[j * w as usize + i].y as f64);
            b8.push(rt[j * w as usize + i - 8].y as f64);
        }
    }
    let (c0, c8) = (correlation(&a0, &b0), correlation(&a8, &b8));
    eprintln!("correlation at 0 px {c0:.4}, at the disparity {c8:.4}");
    // n ≈ 11 000: the standard error of ρ for independent noise is ≈ 0.01.
    assert!(c0.abs() < 0.05 && c8.abs() < 0.05);
    // Sanity: the images are noisy at all (otherwise the test proves nothing).
    let (_, se) = common::mean_stderr(&a0);
    assert!(se > 0.0);
}
