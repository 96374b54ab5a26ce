//! Lettering for signs, plates and shop fronts: a 5 × 7 block font turned
//! into raised letters, one closed box per run of filled cells, so text is
//! real geometry (exact in the ground truth, visible in stereo) without
//! textures.
//!
//! The text plane is local x (right) and y (up), with the text's bottom-left
//! corner at the origin; letters rise from z = 0 to z = `depth` toward +z.
//! Letters are upper case; lower case is drawn as upper case and any other
//! character as a space.

use glam::DVec3;

use crate::scene::mesh::{cuboid, LocalMesh};

/// Rows of a glyph, top row first; bit 4 is the leftmost of five columns.
type Glyph = [u8; 7];

const ROWS: usize = 7;
const COLUMNS: usize = 5;
/// Horizontal advance per character, in cells (five columns and a gap).
const ADVANCE: usize = 6;

fn glyph(c: char) -> Option<Glyph> {
    Some(match c.to_ascii_uppercase() {
        'A' => [14, 17, 17, 31, 17, 17, 17],
        'B' => [30, 17, 17, 30, 17, 17, 30],
        'C' => [14, 17, 16, 16, 16, 17, 14],
        'D' => [30, 17, 17, 17, 17, 17, 30],
        'E' => [31, 16, 16, 30, 16, 16, 31],
        'F' => [31, 16, 16, 30, 16, 16, 16],
        'G' => [14, 17, 16, 23, 17, 17, 15],
        'H' => [17, 17, 17, 31, 17, 17, 17],
        'I' => [14, 4, 4, 4, 4, 4, 14],
        'J' => [7, 2, 2, 2, 2, 18, 12],
        'K' => [17, 18, 20, 24, 20, 18, 17],
        'L' => [16, 16, 16, 16, 16, 16, 31],
        'M' => [17, 27, 21, 21, 17, 17, 17],
        'N' => [17, 17, 25, 21, 19, 17, 17],
        'O' => [14, 17, 17, 17, 17, 17, 14],
        'P' => [30, 17, 17, 30, 16, 16, 16],
        'Q' => [14, 17, 17, 17, 21, 18, 13],
        'R' => [30, 17, 17, 30, 20, 18, 17],
        'S' => [15, 16, 16, 14, 1, 1, 30],
        'T' => [31, 4, 4, 4, 4, 4, 4],
        'U' => [17, 17, 17, 17, 17, 17, 14],
        'V' => [17, 17, 17, 17, 17, 10, 4],
        'W' => [17, 17, 17, 21, 21, 21, 10],
        'X' => [17, 17, 10, 4, 10, 17, 17],
        'Y' => [17, 17, 10, 4, 4, 4, 4],
        'Z' => [31, 1, 2, 4, 8, 16, 31],
        '0' => [14, 17, 19, 21, 25, 17, 14],
        '1' => [4, 12, 4, 4, 4, 4, 14],
        '2' => [14, 17, 1, 2, 4, 8, 31],
        '3' => [31, 2, 4, 2, 1, 17, 14],
        '4' => [2, 6, 10, 18, 31, 2, 2],
        '5' => [31, 16, 30, 1, 1, 17, 14],
        '6' => [6, 8, 16, 30, 17, 17, 14],
        '7' => [31, 1, 2, 4, 8, 8, 8],
        '8' => [14, 17, 17, 14, 17, 17, 14],
        '9' => [14, 17, 17, 15, 1, 2, 12],
        '-' => [0, 0, 0, 31, 0, 0, 0],
        '.' => [0, 0, 0, 0, 0, 12, 12],
        '/' => [1, 2, 2, 4, 8, 8, 16],
        _ => return None,
    })
}

/// A filled rectangle of the text plane, metres: `[x0, y0, x1, y1]`.
pub type Rect = [f64; 4];

/// Laid-out text: its filled rectangles and its extent.
#[derive(Clone, Debug, PartialEq)]
pub struct Text {
    /// Filled rectangles (runs of cells merged along rows, then down columns).
    pub rects: Vec<Rect>,
    /// Width of the text, metres (0 for empty text).
    pub width: f64,
    /// Height of the text (the cap height), metres.
    pub height: f64,
}

/// Lays out one line of `text` with capital letters `cap_height` metres tall.
pub fn layout(text: &str, cap_height: f64) -> Text {
    let cell = cap_height / ROWS as f64;
    let mut rects = Vec::new();
    let count = text.chars().count();
    for (i, c) in text.chars().enumerate() {
        let Some(g) = glyph(c) else { continue };
        let x0 = (i * ADVANCE) as f64 * cell;
        for [col0, row0, col1, row1] in glyph_blocks(&g) {
            rects.push([
                x0 + col0 as f64 * cell,
                (ROWS - row1) as f64 * cell,
                x0 + col1 as f64 * cell,
                (ROWS - row0) as f64 * cell,
            ]);
        }
    }
    let width = match count {
        0 => 0.0,
        n => (n * ADVANCE - (ADVANCE - COLUMNS)) as f64 * cell,
    };
    Text {
        rects,
        width,
        height: cap_height,
    }
}

/// A glyph's filled cells as blocks `[col0, row0, col1, row1)` (rows from the
/// top): each row's runs, each extended down while the rows below repeat it.
fn glyph_blocks(g: &Glyph) -> Vec<[usize; 4]> {
    let filled = |row: usize, col: usize| g[row] >> (COLUMNS - 1 - col) & 1 == 1;
    let mut used = [[false; COLUMNS]; ROWS];
    let mut blocks = Vec::new();
    for row in 0..ROWS {
        let mut col = 0;
        while col < COLUMNS {
            if !filled(row, col) || used[row][col] {
                col += 1;
                continue;
            }
            let start = col;
            while col < COLUMNS && filled(row, col) && !used[row][col] {
                col += 1;
            }
            let run = |r: usize| (start..col).all(|c| filled(r, c) && !used[r][c]);
            let mut end_row = row + 1;
            while end_row < ROWS && run(end_row) {
                end_row += 1;
            }
            for r in used.iter_mut().take(end_row).skip(row) {
                r[start..col].iter_mut().for_each(|u| *u = true);
            }
            blocks.push([start, row, col, end_row]);
        }
    }
    blocks
}

/// `text` as raised letters: one closed box per rectangle, from z = 0 to
/// z = `depth`, bottom-left of the text at the origin. Empty for text with
/// no drawable character.
pub fn text_mesh(text: &str, cap_height: f64, depth: f64) -> LocalMesh {
    let mut mesh = LocalMesh::default();
    for [x0, y0, x1, y1] in layout(text, cap_height).rects {
        let block = cuboid([x1 - x0, y1 - y0, depth]);
        let centre = DVec3::new((x0 + x1) / 2.0, (y0 + y1) / 2.0, depth / 2.0);
        let base = mesh.positions.len() as u32;
        mesh.positions
            .extend(block.positions.iter().map(|p| *p + centre));
        mesh.triangles
            .extend(block.triangles.iter().map(|t| t.map(|i| i + base)));
    }
    mesh
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Cells covered by the rectangles, counted on the cell grid.
    fn covered_cells(text: &Text, cell: f64) -> usize {
        text.rects
            .iter()
            .map(|[x0, y0, x1, y1]| {
                (((x1 - x0) / cell).round() * ((y1 - y0) / cell).round()) as usize
            })
            .sum()
    }

    #[test]
    fn blocks_cover_each_filled_cell_once() {
        for c in ('A'..='Z').chain('0'..='9').chain(['-', '.', '/']) {
            let g = glyph(c).unwrap();
            let mut hits = [[0u8; COLUMNS]; ROWS];
            for [c0, r0, c1, r1] in glyph_blocks(&g) {
                for row in hits.iter_mut().take(r1).skip(r0) {
                    row[c0..c1].iter_mut().for_each(|h| *h += 1);
                }
            }
            for (row, bits) in g.iter().enumerate() {
                for (col, h) in hits[row].iter().enumerate() {
                    let on = bits >> (COLUMNS - 1 - col) & 1;
                    assert_eq!(*h, on, "{c:?} row {row} col {col}");
                }
            }
        }
    }

    #[test]
    fn glyph_rows_fit_five_columns_and_differ() {
        let all: Vec<Glyph> = ('A'..='Z')
            .chain('0'..='9')
            .map(|c| glyph(c).unwrap())
            .collect();
        assert!(all.iter().flatten().all(|row| *row < 32));
        for (i, a) in all.iter().enumerate() {
            assert!(all[i + 1..].iter().all(|b| b != a), "duplicate glyph {i}");
        }
    }

    #[test]
    fn layout_scales_and_advances() {
        // "T": a 5-cell top bar and a 6-cell stem, cap height 0.7 m → cell 0.1 m.
        let t = layout("T", 0.7);
        assert_eq!(t.rects.len(), 2);
        assert!((t.width - 0.5).abs() < 1e-12 && t.height == 0.7);
        let bar = t.rects[0];
        assert!(
            (bar[1] - 0.6).abs() < 1e-12 && (bar[3] - 0.7).abs() < 1e-12,
            "{bar:?}"
        );
        assert_eq!(covered_cells(&t, 0.1), 11);
        // The second letter starts one advance (6 cells) to the right.
        let tt = layout("TT", 0.7);
        assert!((tt.width - 1.1).abs() < 1e-12);
        assert!((tt.rects[2][0] - 0.6).abs() < 1e-12, "{:?}", tt.rects);
        // Lower case draws as upper case; unknown characters as spaces.
        assert_eq!(layout("t", 0.7), t);
        assert_eq!(layout("T?", 0.7).rects, t.rects);
        assert!(layout("", 1.0).rects.is_empty() && layout("", 1.0).width == 0.0);
    }

    #[test]
    fn text_mesh_is_boxes_inside_the_text_extent() {
        let t = layout("STOP 30", 0.35);
        let m = text_mesh("STOP 30", 0.35, 0.01);
        assert_eq!(m.triangles.len(), 12 * t.rects.len());
        for p in &m.positions {
            assert!(p.x >= -1e-12 && p.x <= t.width + 1e-12, "{p}");
            assert!(p.y >= -1e-12 && p.y <= 0.35 + 1e-12, "{p}");
            assert!(p.z == 0.0 || (p.z - 0.01).abs() < 1e-15, "{p}");
        }
    }
}
