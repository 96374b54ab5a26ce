//! The sky table's row bound (`Strategies::sky_row_bound`): stopping a
//! medium point's sky draw at a row the phase roulette drops whole gives the
//! same bits as the whole draw, at every bounce, in fog and in thin haze.

use super::{samples_in, DIRS, SCENE, SKY};
use crate::integrator::volpath::Strategies;

#[test]
fn sky_row_bound_gives_the_whole_draws_bits() {
    let whole = Strategies {
        sky_row_bound: false,
        ..Strategies::default()
    };
    let fog = format!("{SCENE}{SKY}");
    // g = 0.7 in a thinner slab, as a storm's haze.
    let haze = fog
        .replace("sigma_t = 0.05", "sigma_t = 0.002")
        .replace("g = 0.85", "g = 0.7");
    for scene in [fog, haze] {
        let (a, rays_a) = samples_in(&scene, Strategies::default(), &DIRS, 2048);
        let (b, rays_b) = samples_in(&scene, whole, &DIRS, 2048);
        assert_eq!(rays_a, rays_b);
        for (da, db) in a.iter().zip(&b) {
            for (x, y) in da.iter().zip(db) {
                assert_eq!(x.to_bits(), y.to_bits(), "{x} vs {y}");
            }
        }
        // Not a scene without light: the sky's NEE is in these numbers.
        assert!(a.iter().flatten().sum::<f64>() > 0.0);
    }
}
