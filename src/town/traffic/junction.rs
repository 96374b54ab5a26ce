//! Who may enter a junction. A driver's next junction is a `JState`; it
//! passes the stop line only when (a) its approach's lamp stays non-red
//! until it has cleared the junction (`can_clear`; the roundabout has no
//! lamps), and (b) no driver that could cross its path is inside the
//! junction (`compatible`: the same approach, or opposite approaches
//! neither of which turns left; at the roundabout only the same approach
//! and lane), and (c) turning left, no opposing driver can reach its stop
//! line before the turn is clear (drivers heading east or north do not
//! yield to opposing left turns that have not entered, so two opposing
//! left turns never wait for each other). Drivers already inside are
//! never stopped by these rules; (b) keeps everyone else out until they
//! have left.

use super::{Schedule, A_LAT_MPS2, A_LON_MPS2};
use crate::town::routes::drive::{Crossing, DrivePath, Move};
use crate::town::routes::Segment;
use crate::town::signals::until_red_s;

/// Reserve in the clearing-time estimate before the lamp turns red, seconds.
pub const CLEAR_RESERVE_S: f64 = 1.0;
/// Margin by which an opposing driver must arrive after a left turn has
/// cleared, seconds.
const YIELD_MARGIN_S: f64 = 1.5;

/// One driver's next junction (the first whose zone its rear has not left).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JState {
    /// The crossing on the driver's path.
    pub c: Crossing,
    /// Metres from the driver's front to the stop line (< 0: past it).
    pub d_stop: f64,
    /// Its speed, m/s.
    pub v: f64,
    /// Its speed limit, m/s.
    pub v_max: f64,
}

impl JState {
    /// The state of the driver at arc length `s` (centre) with half length
    /// `half`, or None when no junction lies within `within` metres.
    pub fn of(
        path: &DrivePath,
        s: f64,
        half: f64,
        v: f64,
        v_max: f64,
        within: f64,
    ) -> Option<Self> {
        let c = *path.crossings.iter().find(|c| c.clear_m + half > s)?;
        (c.stop_m < s + within).then_some(JState {
            c,
            d_stop: c.stop_m - (s + half),
            v,
            v_max,
        })
    }

    /// Whether its front is past the stop line.
    pub fn inside(&self) -> bool {
        self.d_stop < -0.01
    }
}

/// Whether drivers at the same junction may be inside it together.
pub fn compatible(a: &Crossing, b: &Crossing) -> bool {
    if a.roundabout {
        return a.dir == b.dir && a.lane == b.lane;
    }
    a.dir == b.dir || (a.dir == (b.dir + 2) % 4 && a.turn != Move::Left && b.turn != Move::Left)
}

/// Earliest time (s) a driver `d` metres before a point at speed `v`
/// (limit `v_max`) reaches it, accelerating at `A_LON_MPS2`.
pub fn earliest_arrival_s(d: f64, v: f64, v_max: f64) -> f64 {
    let (a, d) = (A_LON_MPS2, d.max(0.0));
    let v = v.min(v_max);
    let d_acc = (v_max * v_max - v * v) / (2.0 * a);
    if d_acc >= d {
        ((v * v + 2.0 * a * d).sqrt() - v) / a
    } else {
        (v_max - v) / a + (d - d_acc) / v_max
    }
}

/// Time (s) for a driver at speed `v` to cover `d` metres of `path` from
/// `from`, accelerating at `A_LON_MPS2` to the slowest curve speed on
/// the way (capped at `v_max`).
pub fn clear_time_s(path: &DrivePath, from: f64, d: f64, v: f64, v_max: f64) -> f64 {
    let vc = path
        .pieces(from, from + d)
        .filter_map(|(_, seg)| match *seg {
            Segment::Arc { radius_m, .. } => Some((A_LAT_MPS2 * radius_m).sqrt()),
            Segment::Line { .. } => None,
        })
        .fold(v_max, f64::min)
        .max(1.0);
    if v >= vc {
        d / vc
    } else {
        earliest_arrival_s(d, v, vc)
    }
}

/// Whether the driver in state `me` (its rear `d` metres from clearing
/// the zone) clears it before its lamp turns red: always at the roundabout.
pub fn can_clear(sched: &Schedule, me: &JState, clear_s: f64, t: f64) -> bool {
    me.c.roundabout || clear_s + CLEAR_RESERVE_S <= until_red_s(sched, me.c.dir, t)
}

/// Whether another driver `o` at the same junction keeps `me` (not yet
/// inside, needing `clear_s` to clear) out: `o_inside` when `o` is past
/// its stop line or passes it this step.
pub fn blocks(
    sched: &Schedule,
    me: &JState,
    o: &JState,
    o_inside: bool,
    clear_s: f64,
    t: f64,
) -> bool {
    if o_inside {
        return !compatible(&me.c, &o.c);
    }
    let opposing = o.c.dir == (me.c.dir + 2) % 4;
    if me.c.turn != Move::Left || me.c.roundabout || !opposing {
        return false;
    }
    let yields = me.c.dir >= 2 || o.c.turn != Move::Left;
    let t_arr = earliest_arrival_s(o.d_stop, o.v, o.v_max);
    yields && t_arr < clear_s + YIELD_MARGIN_S && t_arr < until_red_s(sched, o.c.dir, t)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn crossing(dir: usize, turn: Move, lane: u32, roundabout: bool) -> Crossing {
        Crossing {
            junction: (1, 1),
            turn,
            stop_m: 0.0,
            clear_m: 20.0,
            dir,
            roundabout,
            lane,
        }
    }

    #[test]
    fn only_the_same_approach_or_opposing_non_left_moves_share_a_junction() {
        use Move::*;
        let c = |d, m| crossing(d, m, 0, false);
        assert!(compatible(&c(0, Left), &c(0, Straight)));
        assert!(compatible(&c(0, Straight), &c(2, Straight)));
        assert!(compatible(&c(0, Right), &c(2, Straight)));
        assert!(!compatible(&c(0, Left), &c(2, Straight)));
        assert!(!compatible(&c(0, Straight), &c(2, Left)));
        assert!(!compatible(&c(0, Straight), &c(1, Straight)));
        assert!(!compatible(&c(0, Right), &c(3, Right)));
        let r = |d, lane| crossing(d, Straight, lane, true);
        assert!(compatible(&r(1, 0), &r(1, 0)));
        assert!(!compatible(&r(1, 0), &r(1, 1)));
        assert!(!compatible(&r(1, 0), &r(3, 0)));
    }

    #[test]
    fn earliest_arrival_is_the_kinematic_bound() {
        // From rest over 6 m at 3 m/s²: t = √(2·6/3) = 2 s.
        assert!((earliest_arrival_s(6.0, 0.0, 20.0) - 2.0).abs() < 1e-12);
        // Reaching the 6 m/s limit after 6 m (2 s), then 12 m more at 6 m/s.
        assert!((earliest_arrival_s(18.0, 0.0, 6.0) - 4.0).abs() < 1e-12);
        assert_eq!(earliest_arrival_s(-1.0, 5.0, 10.0), 0.0);
    }
}
