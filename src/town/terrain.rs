//! Hills around a town: a seeded smooth height field that is exactly 0 on and
//! near the road network, the blocks and the river, and rises into hills of
//! `hills_m` in the terrain margin, tessellated as a regular grid mesh.
//!
//! h(x, y) = A · w(d) · g(x, y) / peak, where d is the distance from the flat
//! zone (town bounds, river band and ramp sites), w a C¹ smoothstep from 0 at `FLAT_M` to
//! 1 at `FLAT_M + BLEND_M`, and g a blend of a sum of random sinusoids (the
//! hills) and a ramp in d (so the town sits in a valley). `peak` is the
//! largest w·g over the mesh vertices, so the highest vertex is exactly A.
//! World frame z up, metres; the mesh lies 2 cm below h, as the flat ground.

use glam::DVec3;

use crate::scene::desc::{ObjectDesc, TransformDesc};
use crate::scene::mesh::LocalMesh;

use super::desc::TownDesc;
use super::layout::{Layout, Rect, GROUND_MARGIN_M};
use super::ramps::RampSite;
use super::rng::Rng;
use super::vegetation;

/// Name of the terrain mesh object (`kind = "mesh"`) in a town frame.
pub const TERRAIN_NAME: &str = "terrain";
/// Distance from the flat zone within which the height is exactly 0, metres.
pub const FLAT_M: f64 = 8.0;
/// Width of the blend from flat ground to full hills, metres.
pub const BLEND_M: f64 = 90.0;
/// Offset of the terrain below its height function (as the flat ground), metres.
pub const GROUND_Z: f64 = -0.02;
/// Most terrain triangles; the grid spacing grows past this.
const MAX_TRIANGLES: f64 = 4.5e5;
/// Finest grid spacing, metres.
const MIN_SPACING_M: f64 = 2.0;
/// Rng stream tag of the terrain (distinct from `rng::tag`).
const TERRAIN_TAG: u64 = 0x7e77_a1a0;
/// Number of sinusoids in the hill sum.
const WAVES: usize = 7;

/// One plane wave of the hill sum: amplitude, wave vector (rad/m), phase.
#[derive(Clone, Copy, Debug)]
struct Wave {
    amp: f64,
    k: [f64; 2],
    phase: f64,
}

/// The height field of one (town, seed): evaluate with `height_m`.
#[derive(Clone, Debug)]
pub struct Terrain {
    amplitude_m: f64,
    flat: Rect,
    river: Option<Rect>,
    /// Clear zones of the highway ramp sites (flat like the town).
    ramps: Vec<Rect>,
    waves: Vec<Wave>,
    /// Extent of the terrain mesh (the ground's extent).
    extent: Rect,
    spacing_m: f64,
    /// Normaliser: largest raw height over the mesh vertices.
    peak: f64,
}

/// Distance from `p` to rectangle `r` (0 inside), metres.
fn rect_distance(r: &Rect, p: [f64; 2]) -> f64 {
    let dx = (r.min[0] - p[0]).max(p[0] - r.max[0]).max(0.0);
    let dy = (r.min[1] - p[1]).max(p[1] - r.max[1]).max(0.0);
    dx.hypot(dy)
}

/// C¹ smoothstep from 0 at `a` to 1 at `b`.
fn smoothstep(a: f64, b: f64, x: f64) -> f64 {
    let t = ((x - a) / (b - a)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

impl Terrain {
    /// The height field of a (validated) town and seed; `None` when the town
    /// is flat (`hills_m = 0`).
    pub fn new(desc: &TownDesc, l: &Layout, seed: u64) -> Option<Self> {
        Self::with_sites(desc, l, &super::ramps::ramp_sites(desc, l), seed)
    }

    /// As `new`, with the town's ramp sites (`ramps::ramp_sites`) already at
    /// hand: hills stay flat over their clear zones.
    pub fn with_sites(desc: &TownDesc, l: &Layout, sites: &[RampSite], seed: u64) -> Option<Self> {
        if desc.hills_m <= 0.0 {
            return None;
        }
        let mut r = Rng::new(&[seed, TERRAIN_TAG]);
        let waves = (0..WAVES)
            .map(|i| {
                // Wavelengths spread around the configured one; amplitude ∝
                // wavelength so long waves dominate (a 1/f spectrum).
                let lambda = desc.hill_wavelength_m * r.range(0.45, 1.5) / (1.0 + i as f64 * 0.15);
                let dir = r.range(0.0, std::f64::consts::TAU);
                let k = std::f64::consts::TAU / lambda;
                Wave {
                    amp: lambda,
                    k: [k * dir.cos(), k * dir.sin()],
                    phase: r.range(0.0, std::f64::consts::TAU),
                }
            })
            .collect();
        let b = l.bounds();
        let m = GROUND_MARGIN_M;
        let extent = Rect {
            min: [b.min[0] - m, b.min[1] - m],
            max: [b.max[0] + m, b.max[1] + m],
        };
        let [w, h] = extent.size();
        let spacing_m = MIN_SPACING_M.max((2.0 * w * h / MAX_TRIANGLES).sqrt());
        let mut t = Terrain {
            amplitude_m: desc.hills_m,
            flat: b,
            river: l.river_band(),
            ramps: sites.iter().map(|r| r.clear_zone()).collect(),
            waves,
            extent,
            spacing_m,
            peak: 1.0,
        };
        let (nx, ny) = t.cells();
        let mut peak: f64 = 0.0;
        for j in 0..=ny {
            for i in 0..=nx {
                peak = peak.max(t.raw(t.vertex_xy(i, j)));
            }
        }
        t.peak = if peak > 0.0 { peak } else { 1.0 };
        Some(t)
    }

    /// Configured hill amplitude (the highest vertex), metres.
    pub fn amplitude_m(&self) -> f64 {
        self.amplitude_m
    }

    /// Grid spacing of the mesh, metres.
    pub fn spacing_m(&self) -> f64 {
        self.spacing_m
    }

    /// Distance from the flat zone (town bounds, river band, ramp sites), metres.
    fn flat_distance(&self, p: [f64; 2]) -> f64 {
        let d = self
            .ramps
            .iter()
            .fold(rect_distance(&self.flat, p), |d, r| {
                d.min(rect_distance(r, p))
            });
        match &self.river {
            Some(band) => d.min(rect_distance(band, p)),
            None => d,
        }
    }

    /// Unnormalised height in [0, ~1].
    fn raw(&self, p: [f64; 2]) -> f64 {
        let d = self.flat_distance(p);
        let w = smoothstep(FLAT_M, FLAT_M + BLEND_M, d);
        if w == 0.0 {
            return 0.0;
        }
        let (mut s, mut norm) = (0.0, 0.0);
        for v in &self.waves {
            s += v.amp * (v.k[0] * p[0] + v.k[1] * p[1] + v.phase).sin();
            norm += v.amp;
        }
        let hills = 0.5 + 0.5 * s / norm;
        let valley = smoothstep(0.0, GROUND_MARGIN_M, d);
        w * (0.6 * hills + 0.4 * valley)
    }

    /// Terrain height above the road plane at world (x, y), metres, ≥ 0;
    /// exactly 0 within `FLAT_M` of the town bounds and the river.
    pub fn height_m(&self, x: f64, y: f64) -> f64 {
        self.amplitude_m * self.raw([x, y]) / self.peak
    }

    /// Unit surface normal at (x, y) by central differences.
    pub fn normal(&self, x: f64, y: f64) -> DVec3 {
        let e = 0.05;
        let dx = (self.height_m(x + e, y) - self.height_m(x - e, y)) / (2.0 * e);
        let dy = (self.height_m(x, y + e) - self.height_m(x, y - e)) / (2.0 * e);
        DVec3::new(-dx, -dy, 1.0).normalize()
    }

    /// Grid cells along x and y.
    fn cells(&self) -> (usize, usize) {
        let [w, h] = self.extent.size();
        (
            (w / self.spacing_m).ceil() as usize,
            (h / self.spacing_m).ceil() as usize,
        )
    }

    fn vertex_xy(&self, i: usize, j: usize) -> [f64; 2] {
        let (nx, ny) = self.cells();
        let [w, h] = self.extent.size();
        [
            self.extent.min[0] + w * i as f64 / nx as f64,
            self.extent.min[1] + h * j as f64 / ny as f64,
        ]
    }

    /// The terrain grid mesh in world coordinates with smooth normals. Cells
    /// whose four corners are flat are left out (the flat ground quad lies
    /// there), as are cells over the river.
    pub fn mesh(&self) -> LocalMesh {
        let (nx, ny) = self.cells();
        let heights: Vec<f64> = (0..=ny)
            .flat_map(|j| (0..=nx).map(move |i| (i, j)))
            .map(|(i, j)| {
                let p = self.vertex_xy(i, j);
                self.height_m(p[0], p[1])
            })
            .collect();
        let at = |i: usize, j: usize| j * (nx + 1) + i;
        let mut index = vec![u32::MAX; heights.len()];
        let mut g = LocalMesh::default();
        for j in 0..ny {
            for i in 0..nx {
                let corners = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
                if corners.iter().all(|&c| heights[c] == 0.0) {
                    continue;
                }
                let (p0, p1) = (self.vertex_xy(i, j), self.vertex_xy(i + 1, j + 1));
                let cell = Rect { min: p0, max: p1 };
                if self.river.is_some_and(|b| b.overlaps(&cell)) {
                    continue;
                }
                let mut id = [0u32; 4];
                for (k, &c) in corners.iter().enumerate() {
                    if index[c] == u32::MAX {
                        let (ci, cj) = (c % (nx + 1), c / (nx + 1));
                        let p = self.vertex_xy(ci, cj);
                        index[c] = g.positions.len() as u32;
                        g.positions
                            .push(DVec3::new(p[0], p[1], heights[c] + GROUND_Z));
                        g.normals.push(self.normal(p[0], p[1]));
                    }
                    id[k] = index[c];
                }
                // Counter-clockwise seen from above: normals face +z.
                g.triangles.push([id[0], id[1], id[2]]);
                g.triangles.push([id[0], id[2], id[3]]);
            }
        }
        g
    }

    /// The terrain as a scene object: an inline mesh (`kind = "mesh"`) of
    /// ground material, validated like every scene mesh.
    pub fn object(&self) -> ObjectDesc {
        ObjectDesc {
            name: Some(TERRAIN_NAME.to_string()),
            material: Some("ground".to_string()),
            semantic: Some("terrain".to_string()),
            instance: None,
            transform: TransformDesc::default(),
            repeat: Vec::new(),
            shape: self.mesh().into_shape(),
        }
    }

    /// Trees and bushes scattered on the hills (not in the flat zone), each
    /// standing at the terrain height; `vegetation_density` sets how many.
    pub fn vegetation(&self, density: f64, seed: u64) -> Vec<ObjectDesc> {
        let mut r = Rng::new(&[seed, TERRAIN_TAG, 1]);
        let [w, h] = self.extent.size();
        let n = (w * h * density / 4000.0).round() as usize;
        let mut out = Vec::new();
        for _ in 0..n {
            let (x, y) = (
                r.range(self.extent.min[0], self.extent.max[0]),
                r.range(self.extent.min[1], self.extent.max[1]),
            );
            let plant = vegetation::HILL[r.index(vegetation::HILL.len())];
            let heading = r.range(0.0, 360.0);
            // Crowns stay out of the flat zone (roads, lots, ramp sites).
            if self.flat_distance([x, y]) < FLAT_M + vegetation::max_reach_m() {
                continue;
            }
            // Sunk 15 cm so the trunk base never floats over a slope.
            let z = self.height_m(x, y) + GROUND_Z - 0.15;
            out.push(vegetation::place(plant, [x, y, z], heading, seed));
        }
        out
    }
}
