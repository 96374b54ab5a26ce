//! Stations along a profiled road (ramps, the overpass, the underpass):
//! the points its meshes are cut at.

/// Stations from `from` to `to`, at most `step_m` apart, through every
/// breakpoint of `knots` strictly between them (where the profile's
/// curvature changes, so no piece straddles one).
pub(crate) fn stations(from: f64, to: f64, knots: &[f64], step_m: f64) -> Vec<f64> {
    let mut cuts = vec![from];
    cuts.extend(knots.iter().copied().filter(|&k| k > from && k < to));
    cuts.push(to);
    let mut out = vec![from];
    for w in cuts.windows(2) {
        let n = ((w[1] - w[0]) / step_m).ceil().max(1.0) as usize;
        out.extend((1..=n).map(|k| w[0] + (w[1] - w[0]) * k as f64 / n as f64));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::stations;

    #[test]
    fn stations_keep_the_ends_and_knots_and_the_step() {
        let s = stations(0.0, 10.0, &[-1.0, 3.0, 10.0, 12.0], 2.0);
        assert_eq!(s, vec![0.0, 1.5, 3.0, 4.75, 6.5, 8.25, 10.0]);
        assert_eq!(stations(1.0, 1.5, &[], 2.0), vec![1.0, 1.5]);
    }
}
