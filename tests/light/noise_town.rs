//! Noise of local-light selection on a night town frame (many emissive
//! triangles: street lamps, vehicle lights, lit windows): RMSE of equal-spp
//! left-view luminance against a high-spp reference, for the light BVH, the
//! point-independent power/uniform mix and uniform selection. A measurement,
//! not a pass/fail check beyond the BVH beating uniform selection; run with
//! `cargo test --release --test light_noise_town -- --ignored --nocapture`.

use crate::common::light;

use std::path::Path;

use parallax::light::LightSelection;
use parallax::town::{load_town, load_town_frame, town_path, CameraConfig};
use parallax::weather::{apply, draw_params, Weather};

#[test]
#[ignore = "slow measurement (minutes)"]
fn bvh_selection_lowers_noise_on_night_town() {
    let (w, h, spp, spp_ref, seed) = (96, 54, 16, 2048, 7u64);
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let path = town_path("town03", &root.join("scenes"));
    let desc = load_town(&path).expect("town03 loads");
    let mut loaded =
        load_town_frame(&desc, seed, 0, CameraConfig::Normal, &path).expect("frame 0 builds");
    apply(&mut loaded.desc, &draw_params(Weather::Night, seed));
    loaded.desc.camera.width = w;
    loaded.desc.camera.height = h;
    let b = light::build(&loaded);
    let depth = loaded.desc.render.max_depth;
    // Uniform selection for the reference: a bias in the BVH's selection
    // must not make the BVH's own pass look closer to it.
    let reference = light::render_left(&b, LightSelection::Uniform, spp_ref, depth, 99);
    let ref_noise =
        (reference.var_of_mean.iter().sum::<f64>() / reference.mean.len() as f64).sqrt();
    let mean = reference.image_mean().0;
    eprintln!(
        "town03 frame 0 night {w}x{h}, max_depth {depth}; reference uniform {spp_ref} spp: \
mean luminance {mean:.5}, its own rms noise {ref_noise:.5}, {:.1} s",
        reference.seconds
    );
    eprintln!("| selection | spp | RMSE | RMSE / mean | seconds |");
    let mut rmse = Vec::new();
    for (name, sel) in [
        ("bvh", LightSelection::Bvh),
        ("power+uniform", LightSelection::Power),
        ("uniform", LightSelection::Uniform),
    ] {
        let pass = light::render_left(&b, sel, spp, depth, seed);
        let e = pass.rmse(&reference.mean);
        eprintln!(
            "| {name} | {spp} | {e:.5} | {:.3} | {:.1} |",
            e / mean,
            pass.seconds
        );
        rmse.push(e);
    }
    assert!(rmse[0] < rmse[2], "bvh {} vs uniform {}", rmse[0], rmse[2]);
}
