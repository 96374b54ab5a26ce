//! An RGB8 drawing surface for plots and legends: rectangles, lines and text
//! in the public-domain 8×8 bitmap font of `font8x8` (ASCII), so pictures
//! carry their own labels with no system font at run time.

use std::io;
use std::path::Path;

use crate::output::write_png_rgb8;

/// Width and height of one character cell, px.
pub const GLYPH: usize = 8;

/// An RGB8 image, row-major, top row first.
#[derive(Clone, Debug, PartialEq)]
pub struct Canvas {
    /// Width, px.
    pub w: usize,
    /// Height, px.
    pub h: usize,
    /// `w · h · 3` bytes.
    pub rgb: Vec<u8>,
}

impl Canvas {
    /// A canvas filled with `bg`.
    pub fn new(w: usize, h: usize, bg: [u8; 3]) -> Canvas {
        Canvas {
            w,
            h,
            rgb: bg.repeat(w * h),
        }
    }

    /// Sets one pixel; outside the canvas nothing happens.
    pub fn put(&mut self, x: usize, y: usize, c: [u8; 3]) {
        if x < self.w && y < self.h {
            let i = (y * self.w + x) * 3;
            self.rgb[i..i + 3].copy_from_slice(&c);
        }
    }

    /// The colour of one pixel (precondition: inside).
    pub fn get(&self, x: usize, y: usize) -> [u8; 3] {
        let i = (y * self.w + x) * 3;
        [self.rgb[i], self.rgb[i + 1], self.rgb[i + 2]]
    }

    /// Fills `w × h` pixels from `(x, y)`, clipped.
    pub fn fill_rect(&mut self, x: usize, y: usize, w: usize, h: usize, c: [u8; 3]) {
        for yy in y..y + h {
            for xx in x..x + w {
                self.put(xx, yy, c);
            }
        }
    }

    /// Writes `s` with its top-left corner at `(x, y)`, 8 px per character
    /// (non-ASCII shows as `?`).
    pub fn text(&mut self, x: usize, y: usize, s: &str, c: [u8; 3]) {
        for (k, ch) in s.chars().enumerate() {
            for (row, bits) in glyph(ch).iter().enumerate() {
                for col in 0..GLYPH {
                    if bits >> col & 1 == 1 {
                        self.put(x + k * GLYPH + col, y + row, c);
                    }
                }
            }
        }
    }

    /// Writes `s` turned a quarter counter-clockwise (reading upwards), its
    /// first character's bottom-left corner at `(x, y_bottom)`.
    pub fn text_up(&mut self, x: usize, y_bottom: usize, s: &str, c: [u8; 3]) {
        for (k, ch) in s.chars().enumerate() {
            for (row, bits) in glyph(ch).iter().enumerate() {
                for col in 0..GLYPH {
                    if bits >> col & 1 == 1 {
                        let yy = (y_bottom + 1).checked_sub(1 + k * GLYPH + col);
                        if let Some(yy) = yy {
                            self.put(x + row, yy, c);
                        }
                    }
                }
            }
        }
    }

    /// Writes the canvas as an 8-bit RGB PNG (atomically).
    pub fn write_png(&self, path: &Path) -> io::Result<()> {
        write_png_rgb8(path, self.w, self.h, &self.rgb)
    }
}

/// Width of `s` in pixels.
pub fn text_width(s: &str) -> usize {
    s.chars().count() * GLYPH
}

fn glyph(ch: char) -> [u8; 8] {
    let i = if ch.is_ascii() {
        ch as usize
    } else {
        '?' as usize
    };
    font8x8::legacy::BASIC_LEGACY[i]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_sets_the_glyph_bits_and_nothing_else() {
        let mut c = Canvas::new(20, 10, [255; 3]);
        c.text(1, 1, "1", [0; 3]);
        let dark = (0..10)
            .flat_map(|y| (0..20).map(move |x| (x, y)))
            .filter(|&(x, y)| c.get(x, y) == [0; 3])
            .count();
        let bits: u32 = glyph('1').iter().map(|b| b.count_ones()).sum();
        assert_eq!(dark as u32, bits);
        assert!(bits > 0);
        // Turned upwards: the same number of pixels.
        let mut u = Canvas::new(10, 20, [255; 3]);
        u.text_up(1, 18, "1", [0; 3]);
        assert_eq!(u.rgb.iter().filter(|&&v| v == 0).count() as u32, 3 * bits);
    }
}
