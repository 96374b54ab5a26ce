//! Histogram plots without fonts: a PNG bar chart per histogram (256 bars over
//! [0, max disparity], bar height ∝ log10(1 + count), since driving disparities
//! are heavy-tailed) and the same bars as CSV (`lo_px,hi_px,count`), which
//! carries the numbers the picture cannot label.

use std::collections::BTreeMap;
use std::io;
use std::path::{Path, PathBuf};

use super::DisparityHistogram;
use crate::output::{write_atomic, write_png_rgb8};

const BARS: usize = 256;
const BAR_W: usize = 2;
const PLOT_H: usize = 200;
const MARGIN: usize = 10;

fn draw(bars: &[(f64, f64, u64)]) -> (usize, usize, Vec<u8>) {
    let (w, h) = (BARS * BAR_W + 2 * MARGIN, PLOT_H + 2 * MARGIN);
    let mut rgb = vec![255u8; w * h * 3];
    let mut put = |x: usize, y: usize, c: [u8; 3]| {
        let i = (y * w + x) * 3;
        rgb[i..i + 3].copy_from_slice(&c);
    };
    let top = bars.iter().map(|b| b.2).max().unwrap_or(0);
    let scale = ((1 + top) as f64).log10().max(1e-12);
    for (b, &(_, _, count)) in bars.iter().enumerate() {
        let bar_h = (((1 + count) as f64).log10() / scale * PLOT_H as f64).round() as usize;
        for dy in 0..bar_h.min(PLOT_H) {
            for dx in 0..BAR_W {
                put(
                    MARGIN + b * BAR_W + dx,
                    MARGIN + PLOT_H - 1 - dy,
                    [40, 70, 140],
                );
            }
        }
    }
    // Axis line under the bars.
    for x in MARGIN - 2..w - MARGIN + 2 {
        put(x, MARGIN + PLOT_H, [0, 0, 0]);
    }
    (w, h, rgb)
}

fn write_one(dir: &Path, name: &str, hist: &DisparityHistogram) -> io::Result<Vec<PathBuf>> {
    let max = hist.summary().max;
    let hi = if max.is_finite() {
        max.ceil().max(1.0)
    } else {
        1.0
    };
    let bars = hist.coarse(BARS, hi);
    let mut csv = String::from("lo_px,hi_px,count\n");
    for (lo, hi, c) in &bars {
        csv.push_str(&format!("{lo},{hi},{c}\n"));
    }
    let csv_path = dir.join(format!("hist_{name}.csv"));
    write_atomic(&csv_path, csv.as_bytes())?;
    let (w, h, rgb) = draw(&bars);
    let png_path = dir.join(format!("hist_{name}.png"));
    write_png_rgb8(&png_path, w, h, &rgb)?;
    Ok(vec![png_path, csv_path])
}

/// Writes `hist_overall.{png,csv}` and `hist_baseline_XXX.{png,csv}` into
/// `dir`; returns the files written.
pub fn write_histogram_plots(
    dir: &Path,
    overall: &DisparityHistogram,
    per_baseline: &BTreeMap<String, DisparityHistogram>,
) -> io::Result<Vec<PathBuf>> {
    let mut written = write_one(dir, "overall", overall)?;
    for (name, h) in per_baseline {
        written.extend(write_one(dir, name, h)?);
    }
    Ok(written)
}
