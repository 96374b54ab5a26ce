//! Axis-aligned boxes over a ground plane: an analytic scene shared by the
//! exactness and occlusion tests, with f64 slab tests as the reference.

use glam::DVec3;

/// Slab interval in f64 of ray c + t·d through an axis-aligned box.
pub fn slab_interval(c: DVec3, d: DVec3, lo: DVec3, hi: DVec3) -> (f64, f64) {
    let (mut t0, mut t1) = (0.0f64, f64::INFINITY);
    for a in 0..3 {
        let (ta, tb) = ((lo[a] - c[a]) / d[a], (hi[a] - c[a]) / d[a]);
        t0 = t0.max(ta.min(tb));
        t1 = t1.min(ta.max(tb));
    }
    (t0, t1)
}

/// Entry parameter of ray c + t·d into an axis-aligned box.
pub fn slab(c: DVec3, d: DVec3, lo: DVec3, hi: DVec3) -> Option<f64> {
    let (t0, t1) = slab_interval(c, d, lo, hi);
    (t0 <= t1 && t0 > 0.0).then_some(t0)
}

/// Whether ray c + t·d passes within the 1e-5 tolerance of a box edge.
pub fn grazes_box_edge(c: DVec3, d: DVec3) -> bool {
    BOXES.iter().any(|(ctr, s)| {
        let (ctr, h) = (DVec3::from_array(*ctr), DVec3::from_array(*s) * 0.5);
        let (t0, t1) = slab_interval(c, d, ctr - h, ctr + h);
        t0 > 0.0 && (t1 - t0).abs() <= 1e-5 * t0
    })
}

/// Box centres and sizes; values are deliberately not round so that no pixel
/// ray passes exactly through a box edge (a measure-zero tie either side wins).
pub const BOXES: [([f64; 3], [f64; 3]); 3] = [
    ([8.13, -1.07, 1.11], [1.0, 1.5, 2.0]),
    ([14.21, 2.53, 2.07], [3.0, 2.0, 4.0]),
    ([25.37, -4.11, 3.05], [2.0, 6.0, 6.0]),
];

/// The boxes standing over a ground plane z = 0 (so occlusions have a background).
pub fn boxes_scene(width: u32, height: u32) -> String {
    let mut text = super::camera_block(width, height, [0.0, 0.0, 1.65]) + super::GREY_UNDER_SKY;
    text += "\n[[object]]\nkind = \"quad\"\nsize = [20000.0, 20000.0]\nmaterial = \"grey\"\n";
    for (c, s) in BOXES {
        text += &format!(
            "\n[[object]]\nkind = \"box\"\nsize = [{:?}, {:?}, {:?}]\nmaterial = \"grey\"\ntransform = {{ translate = [{:?}, {:?}, {:?}] }}\n",
            s[0], s[1], s[2], c[0], c[1], c[2]
        );
    }
    text
}
