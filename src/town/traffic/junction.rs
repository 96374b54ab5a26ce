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
//! have left. Where a street meets a divided highway (right in, right
//! out: `Crossing::major`), the highway has no signals and the right of
//! way; the street's drivers also wait until no highway driver whose lane
//! they merge into (a bus or truck: any highway driver) is inside or can
//! arrive before they are clear plus the time it needs to brake from its
//! limit.

use super::{Schedule, A_LAT_MPS2, A_LON_MPS2};
use crate::town::routes::drive::{Crossing, DrivePath, Move};
use crate::town::routes::Segment;
use crate::town::signals::until_red_s;

/// Reserve in the clearing-time estimate before the lamp turns red, seconds.
pub const CLEAR_RESERVE_S: f64 = 1.0;
/// Margin by which an opposing driver must arrive after a left turn has
/// cleared, seconds.
const YIELD_MARGIN_S: f64 = 1.5;
/// The first seconds of an axis's green, in which a left turner standing
/// at its line goes before the opposing traffic (a leading left turn: in
/// a steady opposing stream it would otherwise never find a gap).
const LEFT_LEAD_S: f64 = 3.0;

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
    /// Whether its body is long (`LONG_M`): turning, it sweeps into the
    /// next lane.
    pub long: bool,
}

/// Bodies longer than this sweep their corners into the next lane when
/// they turn (a bus's ends on a 10 m arc bulge out ~2 m), metres.
pub const LONG_M: f64 = 7.0;

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
            long: 2.0 * half > LONG_M,
        })
    }

    /// Whether its front is past the stop line.
    pub fn inside(&self) -> bool {
        self.d_stop < -0.01
    }

    /// Whether it is a left turner standing at its stop line in the first
    /// `LEFT_LEAD_S` of its green at time `t`.
    fn leads(&self, sched: &Schedule, t: f64) -> bool {
        let waiting = self.d_stop.abs() < 1.0 && self.v < 0.5;
        let early = sched.axis_time_s(self.c.dir, t) < LEFT_LEAD_S;
        self.c.turn == Move::Left && !self.c.roundabout && waiting && early
    }
}

/// Whether drivers at the same junction may be inside it together.
pub fn compatible(a: &Crossing, b: &Crossing) -> bool {
    match (a.major, b.major) {
        (Some(true), Some(true)) => return true,
        // A highway driver and a street driver: apart unless the street's
        // right turn merges into the kerb lane the highway driver keeps.
        (Some(x), Some(y)) if x != y => {
            let (m, s) = if x { (a, b) } else { (b, a) };
            let merge = m.turn == Move::Straight && m.dir == (s.dir + 3) % 4;
            return !(merge && m.lane == s.lane);
        }
        _ => {}
    }
    if a.roundabout {
        return a.dir == b.dir && a.lane == b.lane;
    }
    a.dir == b.dir || (a.dir == (b.dir + 2) % 4 && a.turn != Move::Left && b.turn != Move::Left)
}

/// Whether two drivers of one approach in different lanes may not be
/// inside together because one is a long body that turns.
pub fn sweeps(a: &JState, b: &JState) -> bool {
    let turning = |x: &JState| x.long && x.c.turn != Move::Straight;
    a.c.dir == b.c.dir && a.c.lane != b.c.lane && (turning(a) || turning(b))
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
/// the zone) clears it before its lamp turns red: always at the roundabout
/// and on a divided highway's right of way.
pub fn can_clear(sched: &Schedule, me: &JState, clear_s: f64, t: f64) -> bool {
    me.c.roundabout
        || me.c.major == Some(true)
        || clear_s + CLEAR_RESERVE_S <= until_red_s(sched, me.c.dir, t)
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
    match (me.c.major, o.c.major) {
        (Some(true), _) => return false,
        // A long body turning off the street sweeps its front across the
        // far carriageway's inner lane too.
        (Some(false), Some(true))
            if !compatible(&me.c, &o.c) || (me.long && me.c.turn != Move::Straight) =>
        {
            // Merged in, it is slow in the highway driver's lane: that
            // one must still be able to brake from its limit behind it.
            let t_arr = earliest_arrival_s(o.d_stop, o.v, o.v_max);
            let brake_s = o.v_max / (2.0 * A_LON_MPS2);
            return o_inside || t_arr < clear_s + YIELD_MARGIN_S + brake_s;
        }
        _ => {}
    }
    if o_inside {
        return !compatible(&me.c, &o.c) || sweeps(me, o);
    }
    let opposing = o.c.dir == (me.c.dir + 2) % 4;
    if opposing && me.c.turn != Move::Left && o.leads(sched, t) {
        return true;
    }
    if me.c.turn != Move::Left || me.c.roundabout || !opposing {
        return false;
    }
    if o.c.turn != Move::Left && me.leads(sched, t) {
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
            major: None,
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
    fn the_divided_highway_has_the_right_of_way_where_a_street_merges_in() {
        use Move::*;
        let desc = crate::town::source::load_named_town("town06", None)
            .expect("town06")
            .desc;
        let sched = crate::town::traffic::Plan::new(&desc).schedule.clone();
        let at = |dir, turn, major, d_stop: f64, v| JState {
            c: Crossing {
                major: Some(major),
                ..crossing(dir, turn, 0, false)
            },
            d_stop,
            v,
            v_max: 25.0,
            long: false,
        };
        // Westbound highway straight on, a southbound street turning right
        // into it; the eastbound carriageway and the exit meet neither.
        let (west, east, exit) = (
            at(2, Straight, true, 50.0, 25.0),
            at(0, Straight, true, 0.0, 25.0),
            at(2, Right, true, 0.0, 10.0),
        );
        let street = at(3, Right, false, 0.0, 0.0);
        assert!(!compatible(&west.c, &street.c) && !compatible(&street.c, &west.c));
        assert!(compatible(&east.c, &street.c) && compatible(&exit.c, &street.c));
        assert!(compatible(&west.c, &east.c));
        let inner = Crossing { lane: 1, ..west.c };
        assert!(compatible(&inner, &street.c));
        // The highway never waits for the street, nor for red.
        assert!(!blocks(&sched, &west, &street, true, 5.0, 0.0));
        let red = (0..2000)
            .map(|k| k as f64 * 0.1)
            .find(|&t| until_red_s(&sched, 2, t) == 0.0)
            .expect("a red phase");
        assert!(can_clear(&sched, &west, 5.0, red));
        // The street waits for a highway driver 2 s away (50 m at 25 m/s),
        // and 10 s away (clear in 5 s + 1.5 s + 25/(2·3) s to brake from
        // the limit = 10.67 s), not for one 12 s away, nor for the other
        // carriageway.
        assert!(blocks(&sched, &street, &west, false, 5.0, 0.0));
        let at = |d_stop| JState { d_stop, ..west };
        assert!(blocks(&sched, &street, &at(250.0), false, 5.0, 0.0));
        let far = at(300.0);
        assert!(!blocks(&sched, &street, &far, false, 5.0, 0.0));
        // A bus turning off the street waits for the far carriageway too.
        let bus = JState {
            long: true,
            ..street
        };
        assert!(!blocks(&sched, &street, &at(300.0), false, 5.0, 0.0));
        assert!(blocks(
            &sched,
            &bus,
            &JState {
                d_stop: 50.0,
                ..east
            },
            false,
            5.0,
            0.0
        ));
        assert!(!blocks(&sched, &street, &east, true, 5.0, 0.0));
        assert!(blocks(&sched, &street, &far, true, 5.0, 0.0));
    }

    #[test]
    fn a_left_turner_waiting_at_its_line_leads_the_green() {
        use Move::*;
        let desc = crate::town::source::load_named_town("town03", None)
            .expect("town03")
            .desc;
        let sched = crate::town::traffic::Plan::new(&desc).schedule.clone();
        let green = (0..2000)
            .map(|k| k as f64 * 0.1)
            .find(|&t| sched.axis_time_s(0, t) < 0.05)
            .expect("an east-west green");
        let at = |dir, turn, d_stop, v| JState {
            c: crossing(dir, turn, 0, false),
            d_stop,
            v,
            v_max: 11.0,
            long: false,
        };
        let left = at(0, Left, 0.0, 0.0);
        let straight = at(2, Straight, 0.0, 0.0);
        // Early in the green: the opposing straight waits for the left turn,
        // which does not yield to it.
        assert!(blocks(&sched, &straight, &left, false, 4.0, green + 1.0));
        assert!(!blocks(&sched, &left, &straight, false, 4.0, green + 1.0));
        // Later, or with the left turner still rolling up, the usual rule:
        // the left turn yields.
        for (l, t) in [(left, green + 5.0), (at(0, Left, 10.0, 5.0), green + 1.0)] {
            assert!(!blocks(&sched, &straight, &l, false, 4.0, t));
            assert!(blocks(&sched, &l, &straight, false, 4.0, t));
        }
    }

    #[test]
    fn a_long_body_turning_keeps_the_next_lane_of_its_approach_out() {
        use Move::*;
        let sched = crate::town::traffic::Plan::new(
            &crate::town::source::load_named_town("town03", None)
                .unwrap()
                .desc,
        )
        .schedule
        .clone();
        let at = |turn, lane, long| JState {
            c: crossing(0, turn, lane, false),
            d_stop: 0.0,
            v: 0.0,
            v_max: 11.0,
            long,
        };
        // A bus turning left from the inner lane, a car turning left from
        // the kerb lane (a town corner): one at a time.
        let (bus, car) = (at(Left, 0, true), at(Left, 1, false));
        assert!(blocks(&sched, &car, &bus, true, 4.0, 0.0));
        assert!(blocks(&sched, &bus, &car, true, 4.0, 0.0));
        // Cars share the approach, and a bus going straight keeps its lane.
        assert!(!blocks(&sched, &car, &at(Left, 0, false), true, 4.0, 0.0));
        assert!(!blocks(
            &sched,
            &at(Straight, 1, false),
            &at(Straight, 0, true),
            true,
            4.0,
            0.0
        ));
        // Behind one another in the same lane: as before.
        assert!(!blocks(&sched, &at(Left, 0, false), &bus, true, 4.0, 0.0));
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
