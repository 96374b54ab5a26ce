//! The species: growth forms of four trees (a plane with a round crown, a
//! spreading oak, a Norway spruce with whorled layered sprays, a weeping
//! birch) and a shrub, with the seeded variation of each variant (size,
//! lean of the limbs, leaf size), and their bark and leaf colours.

use super::grow::{Crown, Form, Level};
use super::mesh::Blade;
use crate::sampler::rng::Rng;

/// A tree species.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Species {
    /// London plane: round crown, broad leaves; the street tree.
    Plane,
    /// Oak: short bole, wide crooked spreading crown.
    Oak,
    /// Norway spruce: a cone of whorled, drooping branches with needle sprays.
    Spruce,
    /// Birch: slender, upright limbs, hanging twigs, small leaves.
    Birch,
}

/// Every species.
pub const SPECIES: [Species; 4] = [
    Species::Plane,
    Species::Oak,
    Species::Spruce,
    Species::Birch,
];

fn level(count: u32, angle_deg: f64, ratio: f64, segments: u32, lift: f64, sides: u32) -> Level {
    Level {
        count,
        angle_deg,
        ratio,
        segments,
        lift,
        sides,
    }
}

impl Species {
    /// Lower-case name (prefab and material names).
    pub fn name(self) -> &'static str {
        match self {
            Species::Plane => "plane",
            Species::Oak => "oak",
            Species::Spruce => "spruce",
            Species::Birch => "birch",
        }
    }

    /// Whether it keeps needles (a conifer).
    pub fn conifer(self) -> bool {
        self == Species::Spruce
    }

    /// Bark albedo (linear RGB).
    pub fn bark_albedo(self) -> [f64; 3] {
        match self {
            Species::Plane => [0.3, 0.27, 0.2],
            Species::Oak => [0.16, 0.12, 0.08],
            Species::Spruce => [0.17, 0.1, 0.06],
            Species::Birch => [0.62, 0.6, 0.55],
        }
    }

    /// Leaf albedo of `variant` (linear RGB): the species' green shifted
    /// per variant, from fresh spring green to a late-summer yellowing.
    pub fn leaf_albedo(self, variant: usize) -> [f64; 3] {
        let base = match self {
            Species::Plane => [0.1, 0.22, 0.05],
            Species::Oak => [0.07, 0.16, 0.04],
            Species::Spruce => [0.035, 0.09, 0.045],
            Species::Birch => [0.15, 0.27, 0.06],
        };
        let season = [[1.0, 1.0, 1.0], [1.25, 1.08, 0.8], [0.85, 0.9, 1.0]][variant % 3];
        [
            base[0] * season[0],
            base[1] * season[1],
            base[2] * season[2],
        ]
    }

    /// The growth form of one variant, its sizes drawn from `r`.
    pub fn form(self, r: &mut Rng) -> Form {
        let size = r.range(0.85, 1.15);
        let spread = r.range(-6.0, 6.0);
        let leaf = r.range(0.9, 1.1);
        let mut f = match self {
            Species::Plane => Form {
                trunk_m: 10.0,
                clear_bole: 0.3,
                trunk_r: 0.24,
                trunk_segments: 8,
                trunk_sides: 10,
                whorl: 1,
                crown: Crown::Round,
                levels: vec![
                    level(8, 50.0 + spread, 0.42, 6, 0.08, 6),
                    level(5, 45.0, 0.5, 4, 0.05, 4),
                    level(5, 45.0, 0.45, 3, 0.0, 3),
                    level(4, 40.0, 0.55, 2, -0.05, 3),
                ],
                wobble: 0.12,
                leaves_per_twig: 18,
                blade: Blade {
                    len: 0.2 * leaf,
                    width: 0.18 * leaf,
                    widest: 0.45,
                },
                leaf_droop: 0.3,
            },
            Species::Oak => Form {
                trunk_m: 7.0,
                clear_bole: 0.25,
                trunk_r: 0.34,
                trunk_segments: 8,
                trunk_sides: 10,
                whorl: 1,
                crown: Crown::Spreading,
                levels: vec![
                    level(7, 66.0 + spread, 0.75, 7, 0.03, 6),
                    level(6, 48.0, 0.45, 4, 0.02, 4),
                    level(4, 45.0, 0.45, 3, 0.0, 3),
                    level(4, 40.0, 0.5, 2, -0.05, 3),
                ],
                wobble: 0.22,
                leaves_per_twig: 22,
                blade: Blade {
                    len: 0.15 * leaf,
                    width: 0.1 * leaf,
                    widest: 0.65,
                },
                leaf_droop: 0.2,
            },
            Species::Spruce => Form {
                trunk_m: 13.0,
                clear_bole: 0.12,
                trunk_r: 0.22,
                trunk_segments: 16,
                trunk_sides: 8,
                whorl: 5,
                crown: Crown::Conical,
                levels: vec![
                    level(70, 82.0 + spread, 0.24, 5, -0.12, 4),
                    level(12, 58.0, 0.36, 2, 0.05, 3),
                ],
                wobble: 0.05,
                leaves_per_twig: 13,
                blade: Blade {
                    len: 0.3 * leaf,
                    width: 0.1 * leaf,
                    widest: 0.5,
                },
                leaf_droop: 0.05,
            },
            Species::Birch => Form {
                trunk_m: 11.0,
                clear_bole: 0.3,
                trunk_r: 0.15,
                trunk_segments: 9,
                trunk_sides: 8,
                whorl: 1,
                crown: Crown::Columnar,
                levels: vec![
                    level(7, 35.0 + spread, 0.45, 6, 0.06, 5),
                    level(6, 40.0, 0.5, 4, -0.1, 3),
                    level(5, 45.0, 0.45, 3, -0.5, 3),
                    level(5, 30.0, 0.6, 2, -0.9, 3),
                ],
                wobble: 0.1,
                leaves_per_twig: 12,
                blade: Blade {
                    len: 0.09 * leaf,
                    width: 0.065 * leaf,
                    widest: 0.35,
                },
                leaf_droop: 0.5,
            },
        };
        f.trunk_m *= size;
        f.trunk_r *= size;
        f
    }
}

/// A shrub's form (bushes): many stems from the ground, dense small leaves.
pub fn shrub_form(r: &mut Rng) -> Form {
    let size = r.range(0.8, 1.2);
    Form {
        trunk_m: 0.3 * size,
        clear_bole: 0.0,
        trunk_r: 0.06 * size,
        trunk_segments: 2,
        trunk_sides: 5,
        whorl: 1,
        crown: Crown::Columnar,
        levels: vec![
            level(7, 45.0, 3.2, 4, 0.2, 3),
            level(5, 45.0, 0.5, 3, 0.0, 3),
            level(4, 40.0, 0.5, 2, -0.2, 3),
        ],
        wobble: 0.2,
        leaves_per_twig: 10,
        blade: Blade {
            len: 0.06,
            width: 0.035,
            widest: 0.4,
        },
        leaf_droop: 0.2,
    }
}
