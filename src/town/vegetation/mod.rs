//! Vegetation: trees grown procedurally (`grow`: a branching skeleton with
//! pipe-model radii, individual leaves at the twig ends) in four species
//! (`species`: plane, oak, spruce, birch) of `VARIANTS` seeded variants
//! each, bushes, a clipped hedge (`hedge`), and the materials they use.
//!
//! Every variant is one prefab (`tree_<species>_<k>`, `bush_<k>`, `hedge`),
//! placed many times with a heading and a small scale jitter, so its
//! triangles are stored once when prefabs are instanced. Prefabs depend on
//! nothing but fixed seeds (the same in every town); which species and
//! variant stand where follows the town's seed (`Planting`, `place`).
//! Trees, bushes and hedges are `vegetation`; grass verges are `terrain`.

pub mod grow;
pub mod hedge;
pub mod mesh;
pub mod species;

use std::sync::OnceLock;

use crate::scene::desc::{
    MaterialDesc, ObjectDesc, PrefabDesc, ScaleDesc, ShapeDesc, TextureKindDesc, TransformDesc,
};

use super::desc::TownDesc;
use super::materials;
use super::parts::{class, instance};
use super::rng::{tag, Rng};
use grow::{grow, Grown};
pub use species::{Species, SPECIES};

/// Seeded variants per tree species.
pub const VARIANTS: usize = 3;
/// Bush variants.
pub const BUSH_VARIANTS: usize = 2;
/// Name of the hedge prefab (a `hedge::HEDGE_LEN_M` segment along local x).
pub const HEDGE: &str = "hedge";
/// Material of grass verges.
pub const VERGE: &str = "verge_grass";
/// Key of the fixed streams the prefabs grow from.
const PREFAB_KEY: u64 = 0x7ee5_0fa1;

/// What stands at a place: a tree of a species, or a bush.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Plant {
    /// A tree.
    Tree(Species),
    /// A bush.
    Bush,
}

/// Prefab name of tree `variant` of `s`.
pub fn tree_prefab(s: Species, variant: usize) -> String {
    format!("tree_{}_{variant}", s.name())
}

/// Prefab name of bush `variant`.
pub fn bush_prefab(variant: usize) -> String {
    format!("bush_{variant}")
}

fn leaves_material(s: Species, variant: usize) -> String {
    format!("leaves_{}_{variant}", s.name())
}

fn bark_material(s: Species) -> String {
    format!("bark_{}", s.name())
}

/// The grown tree of variant `variant` of `s` (a pure function of both).
pub fn grow_tree(s: Species, variant: usize) -> Grown {
    let mut r = Rng::new(&[PREFAB_KEY, s as u64, variant as u64]);
    let form = s.form(&mut r);
    grow(&form, r)
}

/// The grown bush of variant `variant`.
pub fn grow_bush(variant: usize) -> Grown {
    let mut r = Rng::new(&[PREFAB_KEY, 100, variant as u64]);
    let form = species::shrub_form(&mut r);
    grow(&form, r)
}

fn mesh_object(m: &mesh::PlantMesh, material: String) -> ObjectDesc {
    ObjectDesc {
        name: None,
        material: Some(material),
        semantic: Some("vegetation".to_string()),
        instance: None,
        transform: TransformDesc::default(),
        repeat: Vec::new(),
        shape: m.to_shape(),
    }
}

/// The prefab of a grown plant: its bark and its leaves.
pub fn plant_prefab(name: String, g: &Grown, bark: String, leaves: String) -> PrefabDesc {
    PrefabDesc {
        name,
        objects: vec![mesh_object(&g.bark, bark), mesh_object(&g.leaves, leaves)],
    }
}

fn build_prefabs() -> Vec<PrefabDesc> {
    let mut out = Vec::new();
    for s in SPECIES {
        for v in 0..VARIANTS {
            let g = grow_tree(s, v);
            out.push(plant_prefab(
                tree_prefab(s, v),
                &g,
                bark_material(s),
                leaves_material(s, v),
            ));
        }
    }
    for v in 0..BUSH_VARIANTS {
        let g = grow_bush(v);
        out.push(plant_prefab(
            bush_prefab(v),
            &g,
            "bark_bush".to_string(),
            format!("leaves_bush_{v}"),
        ));
    }
    let (leaves, _) = hedge::hedge_leaves(Rng::new(&[PREFAB_KEY, 200]));
    let size = hedge::core_size();
    out.push(PrefabDesc {
        name: HEDGE.to_string(),
        objects: vec![
            ObjectDesc {
                transform: TransformDesc {
                    translate: Some([0.0, 0.0, size[2] / 2.0]),
                    ..TransformDesc::default()
                },
                shape: ShapeDesc::Box { size },
                ..mesh_object(&mesh::PlantMesh::default(), "hedge_core".to_string())
            },
            mesh_object(&leaves, "leaves_hedge".to_string()),
        ],
    });
    out
}

/// Every vegetation prefab (grown once per process: they depend on fixed
/// seeds only).
pub fn vegetation_prefabs() -> Vec<PrefabDesc> {
    static PREFABS: OnceLock<Vec<PrefabDesc>> = OnceLock::new();
    PREFABS.get_or_init(build_prefabs).clone()
}

/// The farthest any placed plant reaches from its foot in plan view,
/// metres (the widest prefab at the largest placement scale): what keeps
/// crowns out of a clear zone.
pub fn max_reach_m() -> f64 {
    static REACH: OnceLock<f64> = OnceLock::new();
    *REACH.get_or_init(|| {
        let mut reach: f64 = 0.0;
        for p in vegetation_prefabs() {
            for o in &p.objects {
                if let ShapeDesc::Mesh { positions, .. } = &o.shape {
                    for q in positions {
                        reach = reach.max(q[0].hypot(q[1]));
                    }
                }
            }
        }
        reach * 1.1
    })
}

/// The species a town plants along its streets: a main one and a second,
/// drawn per town and seed.
#[derive(Clone, Debug)]
pub struct Planting {
    /// The town's `vegetation_density`.
    pub density: f64,
    /// Most street trees (70 %).
    pub main: Species,
    /// The rest.
    pub second: Species,
    /// Whether the sidewalks carry a grass verge along the tree line.
    pub verges: bool,
    seed: u64,
}

impl Planting {
    /// The planting of `desc` with `seed`.
    pub fn new(desc: &TownDesc, seed: u64) -> Self {
        let name = desc
            .name
            .bytes()
            .fold(0u64, |h, b| h.wrapping_mul(31) ^ b as u64);
        let mut r = Rng::new(&[seed, tag::TREES, name]);
        let street = [Species::Plane, Species::Plane, Species::Birch, Species::Oak];
        let main = street[r.index(street.len())];
        let rest: Vec<_> = street.iter().copied().filter(|&s| s != main).collect();
        Planting {
            density: desc.vegetation_density,
            main,
            second: rest[r.index(rest.len())],
            verges: desc.sidewalks
                && desc.sidewalk_width_m >= 2.5
                && desc.vegetation_density >= 0.5,
            seed,
        }
    }

    /// A street tree at `at`: the main species when `main`.
    pub fn street_tree(&self, main: bool, at: [f64; 3], heading_deg: f64) -> ObjectDesc {
        let s = if main { self.main } else { self.second };
        place(Plant::Tree(s), at, heading_deg, self.seed)
    }
}

/// `plant` at `at` with `heading_deg`: its variant and a ±10 % scale drawn
/// from a stream keyed by `seed` and the place.
pub fn place(plant: Plant, at: [f64; 3], heading_deg: f64, seed: u64) -> ObjectDesc {
    let mut r = Rng::new(&[seed, tag::TREES, at[0].to_bits(), at[1].to_bits()]);
    let name = match plant {
        Plant::Tree(s) => tree_prefab(s, r.index(VARIANTS)),
        Plant::Bush => bush_prefab(r.index(BUSH_VARIANTS)),
    };
    let s = r.range(0.9, 1.1);
    let mut o = instance(&name, at, heading_deg, &[], class("vegetation"));
    o.transform.scale = Some(ScaleDesc::Uniform(s));
    o
}

/// What parks plant (drawn uniformly).
pub const PARK: [Plant; 5] = [
    Plant::Tree(Species::Plane),
    Plant::Tree(Species::Oak),
    Plant::Tree(Species::Birch),
    Plant::Tree(Species::Spruce),
    Plant::Bush,
];
/// What grows wild on hills (drawn uniformly): mostly conifers.
pub const HILL: [Plant; 5] = [
    Plant::Tree(Species::Spruce),
    Plant::Tree(Species::Spruce),
    Plant::Tree(Species::Oak),
    Plant::Tree(Species::Birch),
    Plant::Bush,
];

fn diffuse(
    name: String,
    albedo: [f64; 3],
    texture: Option<(TextureKindDesc, u32)>,
) -> MaterialDesc {
    let plain = materials::diffuse(&name, albedo);
    match texture {
        Some((kind, seed)) => materials::with_texture(plain, kind, seed),
        None => plain,
    }
}

/// Bark and leaf materials of every species and variant (leaves are
/// diffuse, so lit from either face), the bushes', the hedge's and the
/// grass verge's.
pub fn materials() -> Vec<MaterialDesc> {
    let mut out = Vec::new();
    let (foliage, bark) = (TextureKindDesc::Leaves, TextureKindDesc::Bark);
    for (k, s) in SPECIES.into_iter().enumerate() {
        out.push(diffuse(
            bark_material(s),
            s.bark_albedo(),
            Some((bark, 40 + k as u32)),
        ));
        for v in 0..VARIANTS {
            let seed = 50 + (k * VARIANTS + v) as u32;
            out.push(diffuse(
                leaves_material(s, v),
                s.leaf_albedo(v),
                Some((foliage, seed)),
            ));
        }
    }
    out.push(diffuse(
        "bark_bush".into(),
        [0.2, 0.15, 0.1],
        Some((bark, 70)),
    ));
    out.push(diffuse(
        "leaves_bush_0".into(),
        [0.08, 0.19, 0.05],
        Some((foliage, 71)),
    ));
    out.push(diffuse(
        "leaves_bush_1".into(),
        [0.12, 0.2, 0.06],
        Some((foliage, 72)),
    ));
    out.push(diffuse("hedge_core".into(), [0.025, 0.06, 0.02], None));
    out.push(diffuse(
        "leaves_hedge".into(),
        [0.06, 0.15, 0.04],
        Some((foliage, 73)),
    ));
    out.push(diffuse(
        VERGE.into(),
        [0.1, 0.19, 0.06],
        Some((TextureKindDesc::Grass, 74)),
    ));
    out
}

#[cfg(test)]
mod tests;
