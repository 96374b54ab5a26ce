//! Unit tests of the vegetation generator: leaf counts, species that
//! differ, determinism, attachment, clean triangles, budgets, planting.

use std::collections::BTreeSet;

use glam::DVec3;

use super::grow::Grown;
use super::*;
use crate::scene::mesh::is_degenerate;

fn bbox(ps: &[DVec3]) -> (DVec3, DVec3) {
    ps.iter().fold(
        (DVec3::splat(f64::MAX), DVec3::splat(f64::MIN)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    )
}

fn triangles(g: &Grown) -> usize {
    g.bark.triangles.len() + g.leaves.triangles.len()
}

fn mean_leaf_area(g: &Grown) -> f64 {
    let m = &g.leaves;
    let total: f64 = m
        .triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| m.positions[i as usize]);
            (b - a).cross(c - a).length() / 2.0
        })
        .sum();
    total / g.leaf_count as f64
}

#[test]
fn broadleaves_grow_at_least_ten_thousand_leaves_of_two_triangles() {
    for s in [Species::Plane, Species::Oak, Species::Birch] {
        for v in 0..VARIANTS {
            let g = grow_tree(s, v);
            assert!(g.leaf_count >= 10_000, "{s:?} {v}: {} leaves", g.leaf_count);
            assert_eq!(g.leaves.triangles.len(), 2 * g.leaf_count);
            assert_eq!(g.leaf_bases.len(), g.leaf_count);
        }
    }
    // The conifer carries thousands of needle sprays.
    assert!(grow_tree(Species::Spruce, 0).leaf_count >= 8_000);
}

#[test]
fn species_differ_in_shape_and_leaves() {
    let grown: Vec<Grown> = SPECIES.iter().map(|&s| grow_tree(s, 0)).collect();
    let shape: Vec<(f64, f64)> = grown
        .iter()
        .map(|g| {
            let (lo, hi) = bbox(&g.leaves.positions);
            let width = (hi.x - lo.x).max(hi.y - lo.y);
            (hi.z, width)
        })
        .collect();
    let [plane, oak, spruce, birch] = [0, 1, 2, 3];
    // The oak spreads wider than it is tall; the spruce and the birch are
    // slender (taller than wide); the plane's crown is round.
    assert!(shape[oak].1 > shape[oak].0, "oak {:?}", shape[oak]);
    assert!(
        shape[spruce].0 > 1.5 * shape[spruce].1,
        "spruce {:?}",
        shape[spruce]
    );
    assert!(
        shape[birch].0 > 1.2 * shape[birch].1,
        "birch {:?}",
        shape[birch]
    );
    assert!(shape[oak].1 > shape[birch].1 && shape[plane].1 > shape[birch].1);
    // The spruce's crown is widest near the ground: leaves in its lowest
    // third spread further from the trunk than those in its top third.
    let g = &grown[spruce];
    let top = shape[spruce].0;
    let reach = |lo: f64, hi: f64| {
        g.leaf_bases
            .iter()
            .filter(|p| p.z >= lo * top && p.z < hi * top)
            .map(|p| p.truncate().length())
            .fold(0.0, f64::max)
    };
    assert!(reach(0.1, 0.4) > 2.0 * reach(0.7, 1.0));
    // Leaves: the plane's are the broadest, the birch's the smallest.
    let area: Vec<f64> = grown.iter().map(mean_leaf_area).collect();
    assert!(area[plane] > 2.0 * area[oak], "{area:?}");
    assert!(area[oak] > area[birch], "{area:?}");
    assert!(area[spruce] > area[birch], "{area:?}");
}

#[test]
fn the_generator_is_a_pure_function_of_species_and_variant() {
    let bits = |g: &Grown| -> Vec<u64> {
        g.bark
            .positions
            .iter()
            .chain(&g.leaves.positions)
            .flat_map(|p| p.to_array().map(f64::to_bits))
            .collect()
    };
    for s in SPECIES {
        let (a, b) = (grow_tree(s, 1), grow_tree(s, 1));
        assert_eq!(bits(&a), bits(&b), "{s:?} twice");
        assert_eq!(a.bark.triangles, b.bark.triangles);
        let c = grow_tree(s, 2);
        assert_ne!(
            bits(&a),
            bits(&c),
            "{s:?}: variants 1 and 2 are the same tree"
        );
        let (ha, hc) = (bbox(&a.leaves.positions).1.z, bbox(&c.leaves.positions).1.z);
        assert!((ha - hc).abs() > 0.05, "{s:?}: variant heights {ha} {hc}");
    }
    assert_eq!(bits(&grow_bush(0)), bits(&grow_bush(0)));
}

#[test]
fn every_leaf_hangs_within_a_twig_length_of_a_twig_end() {
    let mut plants: Vec<Grown> = SPECIES.iter().map(|&s| grow_tree(s, 0)).collect();
    plants.push(grow_bush(1));
    for g in &plants {
        let longest = g.twig_tips.iter().map(|t| t.1).fold(0.0, f64::max);
        assert!(longest > 0.0 && longest < 2.0, "twig length {longest}");
        for (k, p) in g.leaf_bases.iter().enumerate() {
            let attached = g
                .twig_tips
                .iter()
                .any(|(tip, len)| (*p - *tip).length() <= *len);
            assert!(attached, "leaf {k} at {p} hangs from no twig");
        }
        // The blade starts at its base point (vertex 0 of its four).
        for (k, p) in g.leaf_bases.iter().enumerate() {
            assert_eq!(g.leaves.positions[4 * k], *p);
        }
    }
}

fn check_clean(name: &str, positions: &[DVec3], tris: &[[u32; 3]]) {
    assert!(!tris.is_empty(), "{name}: no triangles");
    for p in positions {
        assert!(p.is_finite(), "{name}: vertex {p}");
    }
    for t in tris {
        let [a, b, c] = t.map(|i| positions[i as usize]);
        assert!(!is_degenerate(a, b, c), "{name}: degenerate {t:?}");
        let shortest = (b - a).length().min((c - b).length()).min((a - c).length());
        assert!(shortest > 1e-5, "{name}: edge of {shortest} m in {t:?}");
    }
}

#[test]
fn no_nan_and_no_degenerate_triangles_in_any_prefab() {
    let prefabs = vegetation_prefabs();
    for p in &prefabs {
        for o in &p.objects {
            if let ShapeDesc::Mesh {
                positions,
                triangles,
                ..
            } = &o.shape
            {
                let ps: Vec<DVec3> = positions.iter().map(|&p| DVec3::from_array(p)).collect();
                check_clean(&p.name, &ps, triangles);
            }
        }
    }
}

#[test]
fn prefabs_are_unique_and_use_defined_materials_within_budget() {
    let prefabs = vegetation_prefabs();
    let names: BTreeSet<_> = prefabs.iter().map(|p| p.name.clone()).collect();
    assert_eq!(names.len(), prefabs.len());
    assert_eq!(prefabs.len(), SPECIES.len() * VARIANTS + BUSH_VARIANTS + 1);
    let mats: BTreeSet<_> = materials().into_iter().map(|m| m.name).collect();
    let mut total = 0;
    for p in &prefabs {
        let mut tris = 0;
        for o in &p.objects {
            let m = o.material.as_deref().expect("material");
            assert!(mats.contains(m), "{}: material {m} undefined", p.name);
            assert_eq!(o.semantic.as_deref(), Some("vegetation"));
            if let ShapeDesc::Mesh { triangles, .. } = &o.shape {
                tris += triangles.len();
            }
        }
        eprintln!("{}: {tris} triangles", p.name);
        assert!(tris <= 60_000, "{}: {tris} triangles", p.name);
        total += tris;
    }
    eprintln!("all vegetation prefabs: {total} triangles");
    // The hedge's skin stays inside its segment, so segments laid end to
    // end never interpenetrate.
    let (leaves, n) = hedge::hedge_leaves(Rng::new(&[PREFAB_KEY, 200]));
    assert!(n > 1000);
    let (lo, hi) = bbox(&leaves.positions);
    assert!(lo.x > -hedge::HEDGE_LEN_M / 2.0 && hi.x < hedge::HEDGE_LEN_M / 2.0);
    assert!(lo.z > -0.05 && hi.z < hedge::HEDGE_HEIGHT_M + 0.05);
}

#[test]
fn triangle_counts_per_variant_fit_the_sum() {
    let t: usize = SPECIES
        .iter()
        .flat_map(|&s| (0..VARIANTS).map(move |v| triangles(&grow_tree(s, v))))
        .sum();
    assert!(t > 4 * VARIANTS * 20_000, "{t}");
}

#[test]
fn planting_follows_the_town_and_seed() {
    let desc = crate::town::load_named_town("town01", None)
        .expect("town01")
        .desc;
    let plantings: Vec<_> = (0..16).map(|s| Planting::new(&desc, s)).collect();
    for p in &plantings {
        assert_ne!(p.main, p.second);
        assert!(!p.main.conifer() && !p.second.conifer());
    }
    let mains: BTreeSet<_> = plantings.iter().map(|p| p.main).collect();
    assert!(mains.len() >= 2, "16 seeds, one street species: {mains:?}");
    let again = Planting::new(&desc, 5);
    assert_eq!(
        (again.main, again.second),
        (plantings[5].main, plantings[5].second)
    );
    // Placement: variant and scale follow the place; the label is vegetation.
    let a = place(Plant::Tree(Species::Oak), [3.0, 4.0, 0.0], 10.0, 7);
    let b = place(Plant::Tree(Species::Oak), [3.0, 4.0, 0.0], 10.0, 7);
    assert_eq!(a, b);
    assert_eq!(a.semantic.as_deref(), Some("vegetation"));
    let names: BTreeSet<_> = (0..40)
        .map(
            |k| match place(Plant::Tree(Species::Oak), [k as f64, 0.0, 0.0], 0.0, 7).shape {
                ShapeDesc::Instance { prefab, .. } => prefab,
                _ => unreachable!("an instance"),
            },
        )
        .collect();
    assert_eq!(names.len(), VARIANTS, "{names:?}");
}
