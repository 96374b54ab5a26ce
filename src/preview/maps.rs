//! One preview picture per map: the map at an integer zoom (so a tiny render
//! stays visible) above a white legend band with a title and either a colour
//! bar with its range or colour swatches with names.

use super::canvas::{text_width, Canvas, GLYPH};
use super::colormap::{turbo, INVALID};

/// Width a narrow map is enlarged to at least (by an integer factor).
const MIN_WIDTH: usize = 320;
const PAD: usize = 6;
const BAR_W: usize = 256;
const BAR_H: usize = 12;
const INK: [u8; 3] = [0, 0, 0];
const PAPER: [u8; 3] = [255, 255, 255];

/// The integer zoom of a map `w` pixels wide: map pixel (x, y) covers canvas
/// pixels [x·zoom, (x+1)·zoom) × [y·zoom, (y+1)·zoom).
pub fn zoom_for(w: usize) -> usize {
    (MIN_WIDTH / w.max(1)).max(1)
}

/// How values map to the colour bar: t = 0 at the bar's left, 1 at its right.
#[derive(Clone, Copy, Debug)]
pub enum Scale {
    /// t = (v − lo) / (hi − lo).
    Linear {
        /// Value at t = 0.
        lo: f64,
        /// Value at t = 1.
        hi: f64,
    },
    /// t = 1 − ln(v / near) / ln(far / near): near values red, far blue.
    LogReversed {
        /// Value at t = 1.
        near: f64,
        /// Value at t = 0.
        far: f64,
    },
}

impl Scale {
    fn t(self, v: f64) -> f64 {
        match self {
            Scale::Linear { lo, hi } if hi > lo => (v - lo) / (hi - lo),
            Scale::LogReversed { near, far } if far > near => {
                1.0 - (v / near).ln() / (far / near).ln()
            }
            _ => 1.0,
        }
    }

    /// The values at t = 0, ½ and 1.
    fn ticks(self) -> [f64; 3] {
        match self {
            Scale::Linear { lo, hi } => [lo, 0.5 * (lo + hi), hi],
            Scale::LogReversed { near, far } => [far, (near * far).sqrt(), near],
        }
    }
}

fn canvas_width(w: usize, title: &str) -> usize {
    (w * zoom_for(w))
        .max(text_width(title) + 2 * PAD)
        .max(BAR_W + 2 * PAD + 4 * GLYPH)
}

/// The map (`rgb`, `w × h`) zoomed, a title under it and a legend band of
/// `legend_h` px drawn by `legend(canvas, top of band)`.
fn compose(
    w: usize,
    h: usize,
    rgb: &[u8],
    title: &str,
    legend_h: usize,
    legend: impl FnOnce(&mut Canvas, usize),
) -> Canvas {
    let z = zoom_for(w);
    let cw = canvas_width(w, title);
    let mut c = Canvas::new(cw, h * z + 3 * PAD + GLYPH + legend_h, PAPER);
    for y in 0..h {
        for x in 0..w {
            let i = (y * w + x) * 3;
            c.fill_rect(x * z, y * z, z, z, [rgb[i], rgb[i + 1], rgb[i + 2]]);
        }
    }
    c.text(PAD, h * z + PAD, title, INK);
    legend(&mut c, h * z + 2 * PAD + GLYPH);
    c
}

/// A scalar map colour-coded with turbo; non-finite or ≤ 0 values are black.
/// The legend is a colour bar with the values at its ends and middle.
pub fn scalar_map(title: &str, unit: &str, w: usize, h: usize, v: &[f32], scale: Scale) -> Canvas {
    let rgb: Vec<u8> = v
        .iter()
        .flat_map(|&d| {
            if d.is_finite() && d > 0.0 {
                turbo(scale.t(d as f64))
            } else {
                INVALID
            }
        })
        .collect();
    compose(w, h, &rgb, title, BAR_H + 4 + GLYPH, |c, y0| {
        for i in 0..BAR_W {
            c.fill_rect(
                PAD + 2 * GLYPH + i,
                y0,
                1,
                BAR_H,
                turbo(i as f64 / (BAR_W - 1) as f64),
            );
        }
        let y = y0 + BAR_H + 4;
        let labels = scale.ticks().map(|t| format!("{t:.1} {unit}"));
        c.text(PAD, y, &labels[0], INK);
        let mid = PAD + 2 * GLYPH + BAR_W / 2;
        c.text(
            mid.saturating_sub(text_width(&labels[1]) / 2),
            y,
            &labels[1],
            INK,
        );
        let right = PAD + 2 * GLYPH + BAR_W + 2 * GLYPH;
        c.text(
            right.saturating_sub(text_width(&labels[2])),
            y,
            &labels[2],
            INK,
        );
    })
}

/// A map already in colours, with a legend of colour swatches and names
/// (flowing left to right, as many per row as fit).
pub fn palette_map(
    title: &str,
    w: usize,
    h: usize,
    rgb: &[u8],
    entries: &[([u8; 3], String)],
) -> Canvas {
    let cw = canvas_width(w, title);
    let cell = entries
        .iter()
        .map(|(_, n)| GLYPH + 4 + text_width(n) + 2 * GLYPH)
        .max()
        .unwrap_or(1);
    let per_row = ((cw - 2 * PAD) / cell).max(1);
    let rows = entries.len().div_ceil(per_row);
    compose(w, h, rgb, title, rows * (GLYPH + 4), |c, y0| {
        for (k, (colour, name)) in entries.iter().enumerate() {
            let (x, y) = (PAD + (k % per_row) * cell, y0 + (k / per_row) * (GLYPH + 4));
            // A swatch with a grey frame, so black and white swatches show.
            c.fill_rect(x, y, GLYPH, GLYPH, [128; 3]);
            c.fill_rect(x + 1, y + 1, GLYPH - 2, GLYPH - 2, *colour);
            c.text(x + GLYPH + 4, y, name, INK);
        }
    })
}
