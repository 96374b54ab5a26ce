//! Towns whose acceleration structure once aborted Embree: Debian's Embree
//! 3.13.5 asserts inside its spatial-split builder (high build quality) on
//! some frames, killing the process; the medium-quality build must take them.

use crate::common::cli::{parallax_ok, repo};

#[test]
fn frames_that_aborted_the_spatial_split_builder_now_build() {
    // town02 seed 69 frame 4 aborted with `sequential_spatial_split:
    // Assertion '!lset.geomBounds.empty()'` (found by a random-seed CLI test).
    let o = parallax_ok(
        repo(),
        &[
            "town",
            "town02",
            "--seed",
            "69",
            "--frame",
            "4",
            "--threads",
            "1",
        ],
    );
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(out.contains("accel"), "no build summary: {out}");
}
