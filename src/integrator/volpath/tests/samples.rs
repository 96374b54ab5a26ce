//! A segment's samples drawn set by set where they are used
//! (`SegmentSamples`) are the numbers of the fixed layout every segment
//! has drawn: at the bounce's base dimension free flight, phase and
//! roulette; then the local light's set, the choice set, two distant sets;
//! the local roulette's set sixth. Whatever the order of the draws and the
//! stream's dimension before each.

use glam::Vec2;

use crate::integrator::volpath::segment::SegmentSamples;
use crate::integrator::volpath::{VOL_DIMS, VOL_DIMS_PER_BOUNCE};
use crate::sampler::{SampleStream, StreamKey};

/// The fixed layout's seven 4D sets of a segment after `bounces` events.
fn layout(stream: &mut SampleStream, bounces: u32) -> [[f32; 4]; 7] {
    stream.set_dimension(VOL_DIMS + bounces * VOL_DIMS_PER_BOUNCE);
    std::array::from_fn(|_| stream.next_4d())
}

#[test]
fn lazily_drawn_sets_are_the_fixed_layouts_numbers() {
    let key = StreamKey {
        seed: 7,
        frame: 3,
        view: 1,
    };
    for (i, bounces) in [(0u32, 0u32), (5, 1), (11, 4)] {
        let mut s = SampleStream::new(key, i, 2 * i + 1, 3 + i);
        let want = layout(&mut s, bounces);
        let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        let v2 = |a: f32, b: f32| Vec2::new(a, b);

        let mut s = SampleStream::new(key, i, 2 * i + 1, 3 + i);
        s.set_dimension(123);
        let u = SegmentSamples::draw(&mut s, bounces);
        assert_eq!(
            bits(&[u.u_ff, u.u_phase.x, u.u_phase.y, u.u_rr]),
            bits(&want[0])
        );
        // The later sets in reverse order, the stream moved in between.
        for n in [4, 3, 2, 1] {
            s.set_dimension(9 + n as u32);
            let d = u.distant(&mut s, n);
            let mut flat = vec![];
            for k in 0..4 {
                let (a, b) = (
                    want[3 + k / 2][2 * (k % 2)],
                    want[3 + k / 2][2 * (k % 2) + 1],
                );
                flat.push(if k < n.div_ceil(2) * 2 {
                    v2(a, b)
                } else {
                    Vec2::ZERO
                });
            }
            assert_eq!(d.to_vec(), flat, "{n} distant lights");
        }
        s.set_dimension(1);
        let l = u.local(&mut s);
        assert_eq!(
            bits(&[l.u_eq, l.u_eq_sel, l.u_light.x, l.u_light.y]),
            bits(&want[1])
        );
        let c = u.in_scatter(&mut s);
        let [sel, ex, ey, sky] = want[2];
        assert_eq!(
            bits(&[c.u_sel, c.u_eq_light.x, c.u_eq_light.y, c.u_sky]),
            bits(&[sel, ex, ey, sky])
        );
        assert_eq!(
            bits(&[c.u_local, c.u_shadow[0], c.u_shadow[1]]),
            bits(&want[6][..3])
        );
    }
}
