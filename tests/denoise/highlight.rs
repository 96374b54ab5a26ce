//! A sun's highlight on a glossy surface: the brightest few pixels of a
//! frame, sharp and nearly noise-free. The direct-light filter takes a
//! glossy first surface's light (`DenoiseSample::l_direct`) but leaves the
//! sun's next-event estimate as traced, as at a Lambertian one; filtered,
//! the highlight's sub-pixel spread reads as noise and is smeared into its
//! neighbours. A copper sphere (GGX α 0.04) 4 m ahead, a small sun behind
//! the camera, a dim sky.

use crate::common;

use common::{render_inline, Rendered};
use parallax::accel::Backend;

const W: u32 = 64;
const H: u32 = 36;

const SCENE: &str = "[sky]\nkind = \"constant\"\nle = [0.2, 0.2, 0.2]\n\
     [[light]]\nkind = \"sun\"\nelevation_deg = 20.0\nazimuth_deg = 180.0\n\
     irradiance = [900.0, 900.0, 900.0]\nangular_diameter_deg = 0.1\n\
     [[material]]\nname = \"copper\"\nkind = \"conductor\"\npreset = \"copper\"\nroughness = 0.2\n\
     [[object]]\nkind = \"sphere\"\nradius = 1.0\nmaterial = \"copper\"\n\
     transform = { translate = [4.0, 0.0, 1.5] }\n";

fn render(filter: bool) -> Rendered {
    let key = if filter {
        ""
    } else {
        "filter_indirect = false\n"
    };
    render_inline(SCENE, (W, H), (16, 3, 4), key, Backend::Bvh)
}

fn green(r: &Rendered) -> Vec<f64> {
    r.out.images[0].rgb.iter().map(|c| c.y as f64).collect()
}

#[test]
fn a_sun_highlight_on_metal_keeps_its_pixels_through_the_filter() {
    // Same sample streams: the filter only moves light between pixels.
    let (on, off) = (green(&render(true)), green(&render(false)));
    let peak = (0..off.len())
        .max_by(|&a, &b| off[a].total_cmp(&off[b]))
        .expect("pixels");
    let median = {
        let mut v = off.clone();
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    assert!(
        off[peak] > 1000.0 * median,
        "a highlight: peak {} median {median}",
        off[peak]
    );
    let (pi, pj) = ((peak % W as usize) as i64, (peak / W as usize) as i64);
    let (mut moved, mut light) = (0.0, 0.0);
    for j in pj - 3..=pj + 3 {
        for i in pi - 3..=pi + 3 {
            let k = (j * W as i64 + i) as usize;
            moved += (on[k] - off[k]).abs();
            light += off[k];
        }
    }
    assert!(
        moved < 0.02 * light,
        "the filter moved {moved} of the highlight's {light} (peak at {pi}, {pj})"
    );
    // The filter did run: the sphere's dim sky reflection is smoothed.
    let changed = on.iter().zip(&off).filter(|(a, b)| a != b).count();
    assert!(changed > 50, "{changed} pixels changed by the filter");
}
