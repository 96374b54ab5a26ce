//! How pixels without a prediction are scored: counted as errors (default) or
//! filled first by the KITTI stereo devkit's background interpolation
//! (`DisparityImage::interpolateBackground` in its `io_disp.h`).

use std::fmt;
use std::str::FromStr;

use serde::Serialize;

use super::metrics::predicted;

/// The rule for missing predictions.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Fill {
    /// No fill: a missing pixel counts in D1 and every bad-x, not in EPE.
    #[default]
    None,
    /// The KITTI devkit's fill, then every pixel is scored.
    Kitti,
}

impl Fill {
    /// The lowercase name (`none`, `kitti`).
    pub fn name(self) -> &'static str {
        match self {
            Fill::None => "none",
            Fill::Kitti => "kitti",
        }
    }

    /// The rule in one sentence, printed with every report.
    pub fn rule(self) -> &'static str {
        match self {
            Fill::None => {
                "missing prediction (16-bit PNG 0, NaN, inf or < 0) = error: counted in D1 and \
bad-x, left out of EPE (EPE over predicted pixels); density = predicted / valid pixels"
            }
            Fill::Kitti => {
                "missing prediction (16-bit PNG 0, NaN, inf or < 0) filled first by the KITTI \
devkit's background interpolation (each gap in a row takes the smaller neighbour, rows then \
columns extrapolated from the nearest value; what stays empty counts as error), then scored; density = predicted / valid pixels \
before the fill"
            }
        }
    }

    /// `raw` (row-major, `w` wide) prepared for scoring: unchanged for
    /// `None`, background-interpolated for `Kitti`.
    pub fn apply(self, w: usize, raw: &[f32]) -> std::borrow::Cow<'_, [f32]> {
        match self {
            Fill::None => std::borrow::Cow::Borrowed(raw),
            Fill::Kitti => std::borrow::Cow::Owned(interpolate_background(w, raw)),
        }
    }
}

impl fmt::Display for Fill {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Fill {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "none" => Ok(Fill::None),
            "kitti" => Ok(Fill::Kitti),
            _ => Err(format!("unknown fill '{s}' (expected none or kitti)")),
        }
    }
}

/// The KITTI devkit's fill: in each row a gap between two predictions takes
/// the smaller (background) of the two; a gap touching the row's ends takes
/// the nearest prediction in the row; then rows above the first and below the
/// last row with a prediction take that row's values column by column. Rows
/// between two predicted rows that have no prediction stay missing, as in the
/// devkit, and so does an image without any prediction.
pub fn interpolate_background(w: usize, raw: &[f32]) -> Vec<f32> {
    let mut d = raw.to_vec();
    if w == 0 {
        return d;
    }
    let h = d.len() / w;
    for row in d.chunks_mut(w) {
        let mut count = 0;
        for u in 0..w {
            if !predicted(row[u]) {
                count += 1;
                continue;
            }
            if count > 0 {
                let (u1, u2) = (u - count, u - 1);
                // Gaps at either end are left to the extrapolation below.
                if u1 > 0 && u2 < w - 1 {
                    let v = row[u1 - 1].min(row[u2 + 1]);
                    row[u1..=u2].fill(v);
                }
            }
            count = 0;
        }
        if let Some(first) = row.iter().position(|&v| predicted(v)) {
            let v = row[first];
            row[..first].fill(v);
            let last = row.iter().rposition(|&v| predicted(v)).unwrap_or(first);
            let v = row[last];
            row[last + 1..].fill(v);
        }
    }
    for u in 0..w {
        let Some(top) = (0..h).find(|&v| predicted(d[v * w + u])) else {
            continue;
        };
        let bottom = (0..h)
            .rev()
            .find(|&v| predicted(d[v * w + u]))
            .unwrap_or(top);
        let (a, b) = (d[top * w + u], d[bottom * w + u]);
        (0..top).for_each(|v| d[v * w + u] = a);
        (bottom + 1..h).for_each(|v| d[v * w + u] = b);
    }
    d
}

#[cfg(test)]
mod tests {
    use super::*;

    const N: f32 = f32::NAN;

    #[test]
    fn interior_gaps_take_the_background_and_ends_the_nearest_value() {
        // Row 0: nothing predicted → the column's nearest below (row 1, filled).
        // Row 1: gap between 5 and 3 → 3; left end ← 5; right end ← 3.
        // Row 2: -1 is missing; gap between 2 and 8 → 2.
        let raw = [
            N, N, N, N, N, N, //
            N, 5.0, N, N, 3.0, N, //
            1.0, 2.0, -1.0, 8.0, 8.0, 8.0,
        ];
        let got = interpolate_background(6, &raw);
        let want = [
            5.0, 5.0, 3.0, 3.0, 3.0, 3.0, //
            5.0, 5.0, 3.0, 3.0, 3.0, 3.0, //
            1.0, 2.0, 2.0, 8.0, 8.0, 8.0,
        ];
        assert_eq!(got, want);
        // As in the devkit, an empty row between two others stays missing.
        let col = interpolate_background(1, &[5.0, N, 7.0]);
        assert!(col[0] == 5.0 && col[1].is_nan() && col[2] == 7.0);
        assert!(interpolate_background(2, &[N, N])
            .iter()
            .all(|v| v.is_nan()));
    }
}
