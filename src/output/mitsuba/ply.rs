//! Binary little-endian PLY triangle meshes, as Mitsuba 3's `ply` shape reads
//! them: float positions, optional float normals, `uchar int` index lists.
//! Meshes are gathered per material from every flattened mesh of a scene,
//! keeping only the vertices their triangles use.

use glam::Vec3;

/// A triangle mesh being gathered for one PLY file.
#[derive(Clone, Debug, Default)]
pub struct PlyMesh {
    /// Positions (render space).
    pub positions: Vec<Vec3>,
    /// Per-vertex normals (empty: Mitsuba uses face normals).
    pub normals: Vec<Vec3>,
    /// Vertex indices.
    pub triangles: Vec<[u32; 3]>,
}

impl PlyMesh {
    /// Appends triangles `tris` of a mesh with `positions` and optional
    /// `normals` (empty or one per position), remapping to the vertices used;
    /// `flip` reverses the winding (and the normals): the back face of a
    /// two-sided emitter.
    pub fn append(&mut self, positions: &[Vec3], normals: &[Vec3], tris: &[[u32; 3]], flip: bool) {
        let mut remap = vec![u32::MAX; positions.len()];
        let sign = if flip { -1.0 } else { 1.0 };
        for t in tris {
            let mut out = [0u32; 3];
            for (o, &i) in out.iter_mut().zip(t) {
                let i = i as usize;
                if remap[i] == u32::MAX {
                    remap[i] = self.positions.len() as u32;
                    self.positions.push(positions[i]);
                    if !normals.is_empty() {
                        self.normals.push(normals[i] * sign);
                    }
                }
                *o = remap[i];
            }
            if flip {
                out.swap(1, 2);
            }
            self.triangles.push(out);
        }
    }

    /// The PLY file's bytes.
    pub fn encode(&self) -> Vec<u8> {
        let with_normals = !self.normals.is_empty();
        let mut header = format!(
            "ply\nformat binary_little_endian 1.0\ncomment parallax export\nelement vertex {}\n\
             property float x\nproperty float y\nproperty float z\n",
            self.positions.len()
        );
        if with_normals {
            header += "property float nx\nproperty float ny\nproperty float nz\n";
        }
        header += &format!(
            "element face {}\nproperty list uchar int vertex_indices\nend_header\n",
            self.triangles.len()
        );
        let per_vertex = if with_normals { 24 } else { 12 };
        let mut out = Vec::with_capacity(
            header.len() + self.positions.len() * per_vertex + self.triangles.len() * 13,
        );
        out.extend_from_slice(header.as_bytes());
        for (i, p) in self.positions.iter().enumerate() {
            for c in p.to_array() {
                out.extend_from_slice(&c.to_le_bytes());
            }
            if with_normals {
                for c in self.normals[i].to_array() {
                    out.extend_from_slice(&c.to_le_bytes());
                }
            }
        }
        for t in &self.triangles {
            out.push(3);
            for &i in t {
                out.extend_from_slice(&(i as i32).to_le_bytes());
            }
        }
        out
    }
}

/// Vertex and face counts and positions of a PLY file written by
/// [`PlyMesh::encode`] (for tests and checks): (vertices, triangles).
pub fn decode(bytes: &[u8]) -> Result<PlyMesh, String> {
    let end = b"end_header\n";
    let at = bytes
        .windows(end.len())
        .position(|w| w == end)
        .ok_or("no end_header")?;
    let header = std::str::from_utf8(&bytes[..at]).map_err(|e| e.to_string())?;
    let count = |name: &str| -> Result<usize, String> {
        header
            .lines()
            .find_map(|l| l.strip_prefix(&format!("element {name} ")))
            .ok_or(format!("no element {name}"))?
            .trim()
            .parse()
            .map_err(|e| format!("element {name}: {e}"))
    };
    let (nv, nf) = (count("vertex")?, count("face")?);
    let with_normals = header.contains("property float nx");
    let mut body = &bytes[at + end.len()..];
    let mut f32s = |n: usize| -> Result<Vec<f32>, String> {
        if body.len() < 4 * n {
            return Err("truncated".into());
        }
        let v = body[..4 * n]
            .chunks_exact(4)
            .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
            .collect();
        body = &body[4 * n..];
        Ok(v)
    };
    let mut mesh = PlyMesh::default();
    for _ in 0..nv {
        let p = f32s(3)?;
        mesh.positions.push(Vec3::new(p[0], p[1], p[2]));
        if with_normals {
            let n = f32s(3)?;
            mesh.normals.push(Vec3::new(n[0], n[1], n[2]));
        }
    }
    for _ in 0..nf {
        if body.len() < 13 || body[0] != 3 {
            return Err("bad face".into());
        }
        let idx = |k: usize| {
            let o = 1 + 4 * k;
            i32::from_le_bytes([body[o], body[o + 1], body[o + 2], body[o + 3]]) as u32
        };
        let t = [idx(0), idx(1), idx(2)];
        if t.iter().any(|&i| i as usize >= nv) {
            return Err(format!("face index out of range: {t:?}"));
        }
        mesh.triangles.push(t);
        body = &body[13..];
    }
    if !body.is_empty() {
        return Err(format!("{} trailing bytes", body.len()));
    }
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn append_keeps_used_vertices_and_round_trips() {
        let p = [Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z, Vec3::ONE];
        let n = [Vec3::Z; 5];
        let mut m = PlyMesh::default();
        m.append(&p, &n, &[[0, 1, 2], [2, 1, 4]], false);
        m.append(&p, &n, &[[0, 1, 2]], true);
        assert_eq!(
            m.positions.len(),
            4 + 3,
            "vertex 3 unused, second append its own"
        );
        assert_eq!(m.triangles, vec![[0, 1, 2], [2, 1, 3], [4, 6, 5]]);
        assert_eq!(m.normals[5], -Vec3::Z, "flipped normals");
        let back = decode(&m.encode()).unwrap();
        assert_eq!(back.positions, m.positions);
        assert_eq!(back.normals, m.normals);
        assert_eq!(back.triangles, m.triangles);
    }
}
