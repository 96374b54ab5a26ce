//! Histogram plots a person can read: a PNG bar chart per histogram (256 bars
//! over [0, max disparity], bar height ∝ log10(1 + count), since driving
//! disparities are heavy-tailed) with a title, both axes, ticks with numbers
//! and axis labels with units, and the same bars as CSV (`lo_px,hi_px,count`).

use std::collections::BTreeMap;
use std::io;
use std::path::{Path, PathBuf};

use super::DisparityHistogram;
use crate::output::write_atomic;
use crate::preview::canvas::{text_width, Canvas, GLYPH};

const BARS: usize = 256;
const BAR_W: usize = 2;
/// Plot area, px.
const PLOT_W: usize = BARS * BAR_W;
const PLOT_H: usize = 200;
/// Margins: left holds the y label and tick numbers, top the title, bottom
/// the x tick numbers and label.
const LEFT: usize = 80;
const TOP: usize = 28;
const RIGHT: usize = 24;
const BOTTOM: usize = 44;
const INK: [u8; 3] = [0, 0, 0];
const BAR: [u8; 3] = [40, 70, 140];
const PAPER: [u8; 3] = [255, 255, 255];

/// Size of every histogram PNG, px.
pub const PLOT_SIZE: (usize, usize) = (LEFT + PLOT_W + RIGHT, TOP + PLOT_H + BOTTOM);
/// Pixel column of the y axis and row of the x axis in the PNG.
pub const AXES_AT: (usize, usize) = (LEFT - 1, TOP + PLOT_H);

/// A round tick step (1, 2 or 5 × 10^k) giving at most about `n` ticks over `span`.
fn nice_step(span: f64, n: f64) -> f64 {
    let raw = span / n;
    let p = 10f64.powf(raw.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * p)
        .find(|&s| s >= raw)
        .unwrap_or(10.0 * p)
}

/// A tick number with as many decimals as the step needs.
fn tick_label(v: f64, step: f64) -> String {
    let decimals = (-step.log10().floor()).max(0.0) as usize;
    format!("{v:.decimals$}")
}

/// A count in few characters: 1, 10, 100, 1k, …, 1G.
fn count_label(c: u64) -> String {
    match c {
        c if c >= 1_000_000_000 => format!("{}G", c / 1_000_000_000),
        c if c >= 1_000_000 => format!("{}M", c / 1_000_000),
        c if c >= 1_000 => format!("{}k", c / 1_000),
        c => c.to_string(),
    }
}

fn draw(title: &str, bars: &[(f64, f64, u64)], hi: f64) -> Canvas {
    let (w, h) = PLOT_SIZE;
    let mut c = Canvas::new(w, h, PAPER);
    let bottom = TOP + PLOT_H;
    let top = bars.iter().map(|b| b.2).max().unwrap_or(0);
    let scale = ((1 + top) as f64).log10().max(1e-12);
    let y_of = |count: u64| {
        bottom - (((1 + count) as f64).log10() / scale * PLOT_H as f64).round() as usize
    };
    for (b, &(_, _, count)) in bars.iter().enumerate() {
        let y = y_of(count).max(TOP);
        c.fill_rect(LEFT + b * BAR_W, y, BAR_W, bottom - y, BAR);
    }
    // Axes.
    c.fill_rect(LEFT - 1, TOP, 1, PLOT_H + 1, INK);
    c.fill_rect(LEFT - 1, bottom, PLOT_W + 1, 1, INK);
    // x ticks: round disparities.
    let step = nice_step(hi, 8.0);
    let mut k = 0.0;
    while k * step <= hi * (1.0 + 1e-9) {
        let v = k * step;
        let x = LEFT + ((v / hi) * PLOT_W as f64).round() as usize;
        c.fill_rect(x.min(LEFT + PLOT_W - 1), bottom + 1, 1, 4, INK);
        let s = tick_label(v, step);
        c.text(x.saturating_sub(text_width(&s) / 2), bottom + 7, &s, INK);
        k += 1.0;
    }
    // y ticks: 0 and powers of ten up to the tallest bar, never overlapping.
    let mut last_y = usize::MAX;
    let mut count = 0u64;
    loop {
        let y = y_of(count);
        if last_y == usize::MAX || last_y >= y + GLYPH + 2 {
            c.fill_rect(LEFT - 5, y, 4, 1, INK);
            let s = count_label(count);
            c.text(
                LEFT - 7 - text_width(&s),
                y.saturating_sub(GLYPH / 2),
                &s,
                INK,
            );
            last_y = y;
        }
        count = if count == 0 { 1 } else { count * 10 };
        if count > top {
            break;
        }
    }
    // Title and axis labels.
    c.text(LEFT, (TOP - GLYPH) / 2, title, INK);
    let xl = "disparity [px]";
    c.text(LEFT + (PLOT_W - text_width(xl)) / 2, h - GLYPH - 6, xl, INK);
    let yl = "pixels (log scale)";
    c.text_up(6, TOP + (PLOT_H + text_width(yl)) / 2, yl, INK);
    c
}

fn write_one(dir: &Path, name: &str, hist: &DisparityHistogram) -> io::Result<Vec<PathBuf>> {
    let s = hist.summary();
    let hi = if s.max.is_finite() {
        s.max.ceil().max(1.0)
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
    let label = if name == "overall" {
        "all baselines"
    } else {
        name
    };
    let title = format!(
        "disparity histogram, {label}: {} px, median {:.2} px",
        s.pixels, s.median
    );
    let png_path = dir.join(format!("hist_{name}.png"));
    draw(&title, &bars, hi).write_png(&png_path)?;
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_are_round_numbers() {
        assert_eq!(nice_step(100.0, 8.0), 20.0);
        assert_eq!(nice_step(7.0, 8.0), 1.0);
        assert_eq!(nice_step(1.0, 8.0), 0.2);
        assert_eq!(tick_label(0.4, 0.2), "0.4");
        assert_eq!(tick_label(40.0, 20.0), "40");
        assert_eq!(count_label(10_000), "10k");
    }
}
