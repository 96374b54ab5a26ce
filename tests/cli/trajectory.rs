//! `parallax town NAME --seed S --sequence N --trajectory COUNT`: JSON lines
//! of the ego pose whose speed matches the motion, that agree with the
//! library's drive, differ between sequences, and a bad COUNT exits 2.

use crate::common::cli::{parallax_ok, parallax_status, repo};

/// (frame, time, position, rotation, speed) of every printed line.
type Line = (u64, f64, [f64; 3], [f64; 3], f64);

fn trajectory(town: &str, seed: &str, sequence: &str, count: &str) -> Vec<Line> {
    let o = parallax_ok(
        repo(),
        &[
            "town",
            town,
            "--seed",
            seed,
            "--sequence",
            sequence,
            "--trajectory",
            count,
        ],
    );
    String::from_utf8(o.stdout)
        .unwrap()
        .lines()
        .map(|l| {
            let v: serde_json::Value = serde_json::from_str(l).unwrap();
            let three = |k: &str| -> [f64; 3] {
                let a = v[k].as_array().unwrap();
                assert_eq!(a.len(), 3, "{k}: {l}");
                [0, 1, 2].map(|i| a[i].as_f64().unwrap())
            };
            (
                v["frame"].as_u64().unwrap(),
                v["time"].as_f64().unwrap(),
                three("position"),
                three("rotation"),
                v["speed"].as_f64().unwrap(),
            )
        })
        .collect()
}

#[test]
fn trajectory_lines_move_at_their_speed_and_differ_per_sequence() {
    let fps = 10.0;
    // A grid town: an organic town's warp (town03) stretches the level
    // motion by up to 3 % against the reported speed.
    let lines = trajectory("town05", "5", "2", "300");
    assert_eq!(lines.len(), 300);
    let (mut moving, mut stood) = (0, 0);
    for (k, w) in lines.windows(2).enumerate() {
        let ((_, _, p, _, _), (f, t, q, rot, v)) = (w[0], w[1]);
        assert_eq!(f, k as u64 + 1);
        assert!((t - f as f64 / fps).abs() < 1e-9, "time {t} at frame {f}");
        // Speed over the last frame: the chord is the arc on straights
        // and at most 0.1 % shorter on the tightest turn in one frame.
        let chord = (q[0] - p[0]).hypot(q[1] - p[1]) * fps;
        assert!(
            chord <= v + 1e-9 && chord >= v * 0.999 - 1e-9,
            "frame {f}: moved {chord} m/s, speed {v}"
        );
        // Level town: no roll or pitch; yaw in [0, 360).
        assert_eq!((rot[0], rot[1], q[2]), (0.0, 0.0, 0.0));
        assert!((0.0..360.0).contains(&rot[2]));
        assert!(v <= 40.0 / 3.6 + 1e-9);
        if v > 1.0 {
            moving += 1;
        }
        if v == 0.0 {
            stood += 1;
        }
    }
    assert!(moving > 100 && stood > 0, "moving {moving}, stood {stood}");
    // Another sequence (drive) starts elsewhere; the same one repeats.
    let other = trajectory("town05", "5", "3", "2");
    assert_ne!(other[0].2, lines[0].2);
    assert_eq!(trajectory("town05", "5", "2", "2")[..], lines[..2]);
}

/// The world distance of each frame's step against the printed speed
/// (m/s over the last frame): at least 0.999 of it (the chord of a turn)
/// and no more; returns how many frames moved faster than 1 m/s.
fn steps_match_speed(town: &str, lines: &[Line]) -> usize {
    let fps = 10.0;
    let mut moving = 0;
    for w in lines.windows(2) {
        let ((_, _, p, _, _), (f, _, q, _, v)) = (w[0], w[1]);
        let chord =
            ((q[0] - p[0]).powi(2) + (q[1] - p[1]).powi(2) + (q[2] - p[2]).powi(2)).sqrt() * fps;
        assert!(
            chord <= v * (1.0 + 2e-5) + 1e-9 && chord >= v * 0.999 - 1e-9,
            "{town} frame {f}: moved {chord} m/s, speed {v}"
        );
        moving += usize::from(v > 1.0);
    }
    moving
}

#[test]
fn bent_and_graded_towns_report_the_speed_the_positions_move_at() {
    // town03's warp stretches level motion by up to ~3 %, town04's grade
    // lengthens it along slopes: the printed speed is the world's.
    // (Town03's sequence 2 stands at red lights for most of its first
    // 200 frames since its parking lanes widened the crossings.)
    for (town, sequence) in [("town03", "4"), ("town04", "2")] {
        let lines = trajectory(town, "5", sequence, "200");
        let moving = steps_match_speed(town, &lines);
        assert!(moving > 50, "{town}: {moving} moving frames");
    }
}

#[test]
fn a_bad_trajectory_count_exits_2_naming_it() {
    for bad in ["0", "100000"] {
        let (code, err) = parallax_status(&["town", "town01", "--seed", "1", "--trajectory", bad]);
        assert_eq!(code, 2, "{bad}: {err}");
        assert!(
            err.contains(&format!("--trajectory {bad}")) && err.contains("1 to"),
            "{bad}: {err}"
        );
    }
    let (code, err) = parallax_status(&["town", "town01", "--trajectory", "many"]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("--trajectory") && err.contains("many"),
        "{err}"
    );
}

/// Town03's underpass (docs/towns.md): seed 0's drive 22 passes under the
/// deck in its first 600 frames; its z follows the cut's profile (never
/// below 5.5 m down, level at the bottom) and its pitch is nose down
/// (falling) or up (rising) at most atan 9.8 % on the way.
#[test]
fn town03_drive_goes_through_the_underpass() {
    let lines = trajectory("town03", "0", "22", "600");
    assert_eq!(lines.len(), 600);
    let deepest = lines.iter().map(|l| l.2[2]).fold(f64::INFINITY, f64::min);
    assert!((deepest + 5.5).abs() < 1e-9, "deepest {deepest}");
    let steepest = (5.5f64 / 56.0).atan().to_degrees();
    let (mut down, mut up) = (0, 0);
    for w in lines.windows(2) {
        let ((_, _, p, _, _), (_, _, q, rot, _)) = (w[0], w[1]);
        assert!(
            q[2] <= 0.0 && rot[1].abs() <= steepest + 1e-9,
            "{q:?} {rot:?}"
        );
        // Falling frames pitch nose down, rising ones nose up (level
        // where a frame ends on the bottom).
        if q[2] < p[2] - 1e-6 {
            assert!(rot[1] <= 0.0, "{q:?} {rot:?}");
            down += 1;
        } else if q[2] > p[2] + 1e-6 {
            assert!(rot[1] >= 0.0, "{q:?} {rot:?}");
            up += 1;
        }
    }
    assert!(down > 10 && up > 10, "{down} falling, {up} rising frames");
}
