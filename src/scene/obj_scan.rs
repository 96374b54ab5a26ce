//! A light pass over OBJ text before tobj parses it, for what tobj does not
//! report: the line of every face (to name it in errors), index errors with
//! their line and value (index 0, or beyond the elements defined so far),
//! faces of fewer than three corners, and `l` / `p` elements, which tobj
//! would turn into triangles and which are blanked out of the geometry.

use std::borrow::Cow;

/// The faces' lines and the lines tobj should not see.
#[derive(Debug)]
pub struct ObjScan {
    /// 1-based line of each `f` element, in file order (tobj's face order).
    pub face_lines: Vec<usize>,
    /// 0-based indices of the `l` and `p` lines.
    pub skipped: Vec<usize>,
}

impl ObjScan {
    /// The scanned text with the `l` and `p` lines emptied (line numbers
    /// unchanged), copied only when there are any.
    pub fn geometry<'a>(&self, text: &'a str) -> Cow<'a, str> {
        if self.skipped.is_empty() {
            return Cow::Borrowed(text);
        }
        let mut skip = self.skipped.iter().peekable();
        let mut out = String::with_capacity(text.len());
        for (i, line) in text.lines().enumerate() {
            if skip.next_if_eq(&&i).is_none() {
                out.push_str(line);
            }
            out.push('\n');
        }
        Cow::Owned(out)
    }
}

/// Scans OBJ text; an error names the line and the offending value.
pub fn scan(text: &str) -> Result<ObjScan, String> {
    let mut counts = [0usize; 3]; // positions, texcoords, normals so far
    let mut face_lines = Vec::new();
    let mut skipped = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => counts[0] += 1,
            Some("vt") => counts[1] += 1,
            Some("vn") => counts[2] += 1,
            Some("f") => {
                let corners: Vec<&str> = words.collect();
                if corners.len() < 3 {
                    return Err(format!(
                        "line {}: a face needs at least 3 corners, got {} (\"{}\")",
                        i + 1,
                        corners.len(),
                        line.trim()
                    ));
                }
                for c in corners {
                    check_corner(c, &counts).map_err(|m| format!("line {}: {m}", i + 1))?;
                }
                face_lines.push(i + 1);
            }
            // Lines and points are not surfaces.
            Some("l") | Some("p") => skipped.push(i),
            _ => {}
        }
    }
    Ok(ObjScan {
        face_lines,
        skipped,
    })
}

/// Checks one face corner `v`, `v/vt`, `v//vn` or `v/vt/vn` against the
/// elements defined so far (negative indices count back from the last).
fn check_corner(corner: &str, counts: &[usize; 3]) -> Result<(), String> {
    const WHAT: [(&str, &str); 3] = [
        ("vertex", "vertices"),
        ("texcoord", "texcoords"),
        ("normal", "normals"),
    ];
    let parts: Vec<&str> = corner.split('/').collect();
    if parts.len() > 3 || parts[0].is_empty() {
        return Err(format!(
            "face corner \"{corner}\" is not v, v/vt, v//vn or v/vt/vn"
        ));
    }
    for (k, part) in parts.iter().enumerate() {
        if part.is_empty() {
            continue;
        }
        let (what, plural) = WHAT[k];
        let n = counts[k];
        let index: i64 = part.parse().map_err(|_| {
            format!("{what} index \"{part}\" in face corner \"{corner}\" is not an integer")
        })?;
        if index == 0 {
            return Err(format!(
                "{what} index 0 in face corner \"{corner}\": OBJ indices start at 1 (or count back from -1)"
            ));
        }
        let resolved = if index > 0 {
            index
        } else {
            n as i64 + 1 + index
        };
        if resolved < 1 || resolved > n as i64 {
            return Err(format!(
                "{what} index {index} in face corner \"{corner}\" is out of range: {n} {plural} defined so far (allowed 1..={n} or -{n}..=-1)"
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    const TRI: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n";

    #[test]
    fn faces_are_numbered_by_line_and_polylines_blanked() {
        let text = format!("{TRI}l 1 2 3\nf 1 2 3\np 1\nf -3 -2 -1\n");
        let s = scan(&text).unwrap();
        assert_eq!(s.face_lines, vec![7, 9]);
        let g = s.geometry(&text);
        assert_eq!(g.lines().nth(5), Some(""));
        assert_eq!(g.lines().nth(6), Some("f 1 2 3"));
        assert_eq!(g.lines().nth(7), Some(""));
        assert_eq!(g.lines().count(), 9);
        let plain = scan(TRI).unwrap();
        assert!(matches!(plain.geometry(TRI), Cow::Borrowed(_)));
    }

    #[test]
    fn index_errors_name_the_line_and_the_value() {
        let e = scan(&format!("{TRI}f 1/0 2/1 3/1\n")).unwrap_err();
        assert!(e.starts_with("line 6: texcoord index 0"), "{e}");
        let e = scan(&format!("{TRI}f 1//1 2//0 3//1\n")).unwrap_err();
        assert!(e.starts_with("line 6: normal index 0"), "{e}");
        let e = scan(&format!("{TRI}f 1 2 4\n")).unwrap_err();
        assert!(
            e.contains("line 6: vertex index 4") && e.contains("3 vertices"),
            "{e}"
        );
        let e = scan(&format!("{TRI}f 1 2 -4\n")).unwrap_err();
        assert!(e.contains("vertex index -4"), "{e}");
        let e = scan(&format!("{TRI}f 1/1/2 2 3\n")).unwrap_err();
        assert!(e.contains("normal index 2"), "{e}");
        let e = scan(&format!("{TRI}f 1 2\n")).unwrap_err();
        assert!(
            e.contains("line 6: a face needs at least 3 corners, got 2"),
            "{e}"
        );
        let e = scan(&format!("{TRI}f 1 2 x\n")).unwrap_err();
        assert!(e.contains("\"x\""), "{e}");
    }
}
