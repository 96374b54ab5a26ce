//! An overpass (`overpass = true`): a two-lane country road running north–
//! south through the middle of the block column nearest the town centre,
//! crossing over the south highway (x-road 0) and its slip road on a bridge
//! deck. Its road rises from grade to `TOP_M` over `APPROACH_M` by a C¹
//! smoothstep (steepest grade 1.5·TOP_M/APPROACH_M = 5.6 %), runs level
//! over the deck (underside `CLEARANCE_M` above the highway) and falls
//! again; at both ends a turning loop lets its one traffic route (`route`:
//! north on the east lane, round the loop, south on the west lane) come
//! back. The route meets no other road: no junction, no stop, and the
//! vehicles below it are on another level (`VehiclePose::same_level`).
//!
//! Coordinates: the road's centreline is x = `x_m`; `y` runs north. World
//! frame z up, metres; the built meshes are in `overpass/deck.rs`.

mod deck;

use std::f64::consts::PI;

use super::desc::TownDesc;
use super::layout::{Layout, Rect};
use super::ramps::GAP_M;
use super::routes::{Route, RouteKind, Segment};
use super::vehicles::BodyKind;

pub use deck::overpass_meshes;

/// Height of the overpass road surface over the deck, metres.
pub const TOP_M: f64 = 6.0;
/// Depth of the deck (road surface to underside), metres.
pub const DECK_M: f64 = 0.9;
/// Clear height under the deck above the highway, metres.
pub const CLEARANCE_M: f64 = TOP_M - DECK_M;
/// Length of each approach from grade to the deck, metres.
pub const APPROACH_M: f64 = 160.0;
/// Lane width of the overpass road, metres.
pub const LANE_M: f64 = 3.5;
/// Half width of its asphalt (two lanes and 1 m shoulders), metres.
pub const HALF_WIDTH_M: f64 = LANE_M + 1.0;
/// Parapet thickness (outside the asphalt) and height, metres.
pub const PARAPET_M: (f64, f64) = (0.3, 1.0);
/// Level run between an approach's foot and its turning loop, metres.
const LEVEL_RUN_M: f64 = 20.0;
/// Radii of a turning loop: the two reverse curves and the loop, metres.
const LOOP_R_M: (f64, f64) = (8.0, 10.0);
/// Radius of a turning loop's asphalt disc, metres.
pub const DISC_R_M: f64 = 15.5;
/// Clearance between the deck's ends and the roads below, metres.
const DECK_END_MARGIN_M: f64 = 7.0;

/// The overpass of a town: where it runs and its height profile.
#[derive(Clone, Debug, PartialEq)]
pub struct Overpass {
    /// Centreline x, world metres.
    pub x_m: f64,
    /// Centreline y of the highway below, world metres.
    pub y_road_m: f64,
    /// The deck's south and north ends, world y, metres.
    pub deck: (f64, f64),
    /// Y of the pier line between the highway and its slip road, metres.
    pub pier_y_m: f64,
    /// Where the straight lanes meet the south and north turning loops
    /// (world y), metres.
    pub ends: (f64, f64),
}

/// C¹ smoothstep on [0, 1] and its derivative.
fn smoothstep(x: f64) -> (f64, f64) {
    let x = x.clamp(0.0, 1.0);
    (x * x * (3.0 - 2.0 * x), 6.0 * x * (1.0 - x))
}

impl Overpass {
    /// The overpass of a validated town, `None` without one.
    pub fn new(desc: &TownDesc, l: &Layout) -> Option<Self> {
        if !desc.overpass {
            return None;
        }
        let x_m = (l.nx / 2) as f64 * l.pitch_m + l.pitch_m / 2.0;
        let hw = l.road_w_m / 2.0;
        // South of the highway: its slip road's run (edge GAP_M out, one
        // lane + 1 m wide, a shoulder beyond); north: its shoulder.
        let ramp_out = hw + GAP_M + l.lane_w_m + 1.0 + l.sidewalk_m;
        let deck = (
            -ramp_out - DECK_END_MARGIN_M,
            hw + l.sidewalk_m + DECK_END_MARGIN_M,
        );
        let pier_y_m = -(hw + l.sidewalk_m + hw + GAP_M - l.sidewalk_m) / 2.0;
        let ends = (
            deck.0 - APPROACH_M - LEVEL_RUN_M,
            deck.1 + APPROACH_M + LEVEL_RUN_M,
        );
        Some(Overpass {
            x_m,
            y_road_m: 0.0,
            deck,
            pier_y_m,
            ends,
        })
    }

    /// Height of the road surface at world y, metres, and its slope dz/dy.
    pub fn profile(&self, y: f64) -> (f64, f64) {
        let (d0, d1) = self.deck;
        if y >= d0 && y <= d1 {
            (TOP_M, 0.0)
        } else if y > d1 {
            let (s, ds) = smoothstep((y - d1) / APPROACH_M);
            (TOP_M * (1.0 - s), -TOP_M * ds / APPROACH_M)
        } else {
            let (s, ds) = smoothstep((y - (d0 - APPROACH_M)) / APPROACH_M);
            (TOP_M * s, TOP_M * ds / APPROACH_M)
        }
    }

    /// Centres of the south and north turning loops' discs, world (x, y).
    pub fn loop_centres(&self) -> [[f64; 2]; 2] {
        let reach = self.loop_reach();
        [
            [self.x_m, self.ends.0 - reach],
            [self.x_m, self.ends.1 + reach],
        ]
    }

    /// How far beyond a straight's end the loop's centre lies, metres.
    fn loop_reach(&self) -> f64 {
        let (r1, r2) = LOOP_R_M;
        let alpha = self.loop_alpha();
        (r1 + r2) * alpha.sin()
    }

    /// Sweep of each reverse curve: cos α = (d + R₁) / (R₁ + R₂), with d
    /// the lane centre's offset, so the loop's centre lies on the centreline.
    fn loop_alpha(&self) -> f64 {
        let (r1, r2) = LOOP_R_M;
        ((LANE_M / 2.0 + r1) / (r1 + r2)).acos()
    }

    /// Whether world (x, y) lies on the overpass road's asphalt (strip
    /// between the loops' centres, or a loop's disc).
    pub fn on_surface(&self, p: [f64; 2]) -> bool {
        let [s, n] = self.loop_centres();
        let strip = (p[0] - self.x_m).abs() <= HALF_WIDTH_M && p[1] >= s[1] && p[1] <= n[1];
        let disc = |c: [f64; 2]| (p[0] - c[0]).hypot(p[1] - c[1]) <= DISC_R_M;
        strip || disc(s) || disc(n)
    }

    /// The ground kept clear of buildings, trees and furniture: the road,
    /// its parapets and loops and 6 m around them.
    pub fn clear_zone(&self) -> Rect {
        let [s, n] = self.loop_centres();
        let m = DISC_R_M + 6.0;
        Rect {
            min: [self.x_m - m, s[1] - m],
            max: [self.x_m + m, n[1] + m],
        }
    }

    /// The one closed route over the overpass: north on the east lane over
    /// the deck, round the north loop, south on the west lane, round the
    /// south loop (turning +2π in all, as the ring).
    pub fn route(&self) -> Route {
        let (r1, r2) = LOOP_R_M;
        let d = LANE_M / 2.0;
        let a = self.loop_alpha();
        let reach = self.loop_reach();
        let (x, (ys, yn)) = (self.x_m, self.ends);
        let len = yn - ys;
        let segments = vec![
            Segment::Line {
                from: [x + d, ys],
                heading: PI / 2.0,
                len_m: len,
            },
            // North loop: right, round the disc left, right again.
            arc([x + d + r1, yn], r1, PI, -a),
            arc([x, yn + reach], r2, -a, PI + 2.0 * a),
            arc([x - d - r1, yn], r1, a, -a),
            Segment::Line {
                from: [x - d, yn],
                heading: -PI / 2.0,
                len_m: len,
            },
            arc([x - d - r1, ys], r1, 0.0, -a),
            arc([x, ys - reach], r2, PI - a, PI + 2.0 * a),
            arc([x + d + r1, ys], r1, PI + a, -a),
        ];
        let bodies = vec![
            BodyKind::Sedan,
            BodyKind::Hatchback,
            BodyKind::Suv,
            BodyKind::Van,
        ];
        Route::new(RouteKind::Overpass, 0, segments, Vec::new(), bodies)
    }

    /// Height, nose-up pitch (degrees) of a body at (x, y) heading
    /// `heading_deg` on the overpass road.
    pub fn pose(&self, p: [f64; 2], heading_deg: f64) -> (f64, f64) {
        let (z, dz_dy) = self.profile(p[1]);
        let along = dz_dy * heading_deg.to_radians().sin();
        (z, along.atan().to_degrees())
    }
}

fn arc(centre: [f64; 2], radius_m: f64, phi0: f64, sweep: f64) -> Segment {
    Segment::Arc {
        centre,
        radius_m,
        phi0,
        sweep,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn town06() -> (TownDesc, Layout) {
        let text =
            std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/town06.toml"));
        let desc = crate::town::parse_town_str(&text.unwrap(), "town06.toml".as_ref()).unwrap();
        let l = Layout::new(&desc);
        (desc, l)
    }

    #[test]
    fn route_is_continuous_and_stays_on_the_overpass_asphalt() {
        let (desc, l) = town06();
        let o = Overpass::new(&desc, &l).expect("town06 has an overpass");
        let r = o.route();
        let n = (r.length_m() / 0.25) as usize;
        let mut prev = r.pose(0.0);
        for k in 1..=n {
            let s = k as f64 * 0.25;
            let (p, h) = r.pose(s);
            let step = (p[0] - prev.0[0]).hypot(p[1] - prev.0[1]);
            assert!(step < 0.2501, "jump {step} at {s}");
            let dh = (h - prev.1 + PI).rem_euclid(2.0 * PI) - PI;
            assert!(dh.abs() < 0.25 / 7.9, "heading jump {dh} at {s}");
            // A 1 m half-width body stays on the asphalt.
            let side = [-h.sin(), h.cos()];
            for u in [-1.0, 1.0] {
                let q = [p[0] + u * side[0], p[1] + u * side[1]];
                assert!(o.on_surface(q), "{q:?} off the overpass");
            }
            prev = (p, h);
        }
        // Never on another road at grade: where it is over the highway or
        // its slip road it is on the deck.
        for k in 0..n {
            let (p, _) = r.pose(k as f64 * 0.25);
            let on_highway = l
                .road_rects()
                .iter()
                .any(|q| q.contains(&Rect::centered(p, [0.0, 0.0]), 0.0));
            if on_highway || p[1] < -l.road_w_m / 2.0 && p[1] > o.deck.0 {
                assert_eq!(o.profile(p[1]).0, TOP_M, "{p:?}");
            }
        }
        assert!(r.keep_clear_m.is_empty());
    }

    #[test]
    fn profile_is_smooth_and_never_steeper_than_six_percent() {
        let (desc, l) = town06();
        let o = Overpass::new(&desc, &l).unwrap();
        let mut y = o.ends.0 - 30.0;
        let mut steepest: f64 = 0.0;
        while y < o.ends.1 + 30.0 {
            let (z, s) = o.profile(y);
            let e = 1e-4;
            let fd = (o.profile(y + e).0 - o.profile(y - e).0) / (2.0 * e);
            assert!((fd - s).abs() < 1e-6, "slope at {y}: {s} vs {fd}");
            assert!((0.0..=TOP_M).contains(&z));
            steepest = steepest.max(s.abs());
            y += 0.5;
        }
        assert!(steepest <= 0.06 && steepest > 0.05, "{steepest}");
        assert_eq!(o.profile(o.ends.0).0, 0.0);
        assert_eq!(o.profile(o.ends.1).0, 0.0);
    }
}
