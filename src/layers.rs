//! The crate's layer table and the test that holds it: a module may name
//! (`crate::…`) only modules of lower rows, or peers of its own row. The
//! table is written once, here; a new top-level module must be placed in it.
//!
//! `scene::desc` (the descriptions) is its own layer below `scene` (the
//! built scene), so that camera, weather, accel and material can sit
//! between the two; `render::recipe` (the frame recipe) is its own layer
//! above `render` (the passes), `output` and `town`.

use std::path::Path;

/// Layers from the bottom up; modules of one row may use each other.
const LAYERS: &[&[&str]] = &[
    &["sampler"],
    &["geometry"],
    &["camera"],
    &["scene::desc"],
    &["weather"],
    &["accel"],
    &["material"],
    &["scene"],
    &["film"],
    &["light"],
    &["integrator"],
    &["denoise"],
    // The frame passes (`render`) sit below the writers and the towns; the
    // frame recipe (`render::recipe`) above both, as it reads a town and
    // makes the camera record.
    &["render"],
    &["output"],
    &["town"],
    &["render::recipe"],
    &["preview"],
    &["eval"],
    &["stats"],
    &["dataset"],
    &["bench"],
    &["cli"],
];

/// The row of layer `name`, if the table has it.
fn rank(name: &str) -> Option<usize> {
    LAYERS.iter().position(|row| row.contains(&name))
}

/// The layer a `crate::` path names (`scene::desc::X` → `scene::desc`).
fn layer_of_path(path: &str) -> String {
    let mut parts = path.split("::").map(str::trim);
    let first = parts.next().unwrap_or_default();
    match (first, parts.next()) {
        ("scene", Some("desc")) => "scene::desc".to_string(),
        ("render", Some("recipe")) => "render::recipe".to_string(),
        _ => first.to_string(),
    }
}

/// The layer a source file (relative to `src/`) belongs to; None for the
/// crate roots.
fn layer_of_file(rel: &Path) -> Option<String> {
    let parts: Vec<&str> = rel.iter().filter_map(|c| c.to_str()).collect();
    match parts.as_slice() {
        // The crate roots, and this table (its test texts name every layer).
        ["lib.rs" | "main.rs" | "layers.rs"] | [] => None,
        ["scene", "desc", ..] => Some("scene::desc".to_string()),
        ["render", "recipe", ..] => Some("render::recipe".to_string()),
        [first, ..] => Some(first.trim_end_matches(".rs").to_string()),
    }
}

/// Every layer `source` names through `crate::`, with its line number;
/// comment lines are skipped. A group `crate::{a::X, b}` names each member.
fn imports(source: &str) -> Vec<(usize, String)> {
    let code: String = source
        .lines()
        .map(|l| {
            if l.trim_start().starts_with("//") {
                ""
            } else {
                l
            }
        })
        .collect::<Vec<_>>()
        .join("\n");
    let line_of = |at: usize| code[..at].matches('\n').count() + 1;
    let mut found = Vec::new();
    for (at, _) in code.match_indices("crate::") {
        // `parallax_crate::` or `$crate::` are not this crate's paths.
        let before = code[..at].chars().next_back();
        if before.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == '$') {
            continue;
        }
        let rest = &code[at + "crate::".len()..];
        if let Some(group) = rest.strip_prefix('{') {
            for member in top_level_members(group) {
                found.push((line_of(at), layer_of_path(&member)));
            }
        } else {
            let end = rest
                .find(|c: char| !(c.is_alphanumeric() || c == '_' || c == ':'))
                .unwrap_or(rest.len());
            found.push((line_of(at), layer_of_path(&rest[..end])));
        }
    }
    found
}

/// The comma-separated members of a `{…}` group (text after its `{`), up
/// to its closing brace; nested groups stay inside their member.
fn top_level_members(group: &str) -> Vec<String> {
    let mut members = vec![String::new()];
    let mut depth = 0;
    for c in group.chars() {
        match c {
            '{' => depth += 1,
            '}' if depth == 0 => break,
            '}' => depth -= 1,
            ',' if depth == 0 => {
                members.push(String::new());
                continue;
            }
            _ => {}
        }
        if let Some(m) = members.last_mut() {
            m.push(c);
        }
    }
    members
        .into_iter()
        .map(|m| m.trim().to_string())
        .filter(|m| !m.is_empty())
        .collect()
}

/// Every import of every file below `src` that breaks the table, as
/// "file:line: layer uses higher layer".
fn violations(src: &Path) -> Vec<String> {
    let mut bad = Vec::new();
    let mut files = Vec::new();
    collect_rs(src, &mut files);
    files.sort();
    for file in files {
        let rel = file.strip_prefix(src).expect("below src");
        let Some(layer) = layer_of_file(rel) else {
            continue;
        };
        let Some(own) = rank(&layer) else {
            bad.push(format!(
                "{}: module `{layer}` is not in the layer table",
                rel.display()
            ));
            continue;
        };
        let text = std::fs::read_to_string(&file).expect("source file reads");
        for (line, target) in imports(&text) {
            match rank(&target) {
                _ if target == layer => {}
                Some(r) if r <= own => {}
                Some(_) => bad.push(format!(
                    "{}:{line}: `{layer}` uses the higher layer `{target}`",
                    rel.display()
                )),
                None => bad.push(format!(
                    "{}:{line}: `crate::{target}` is not in the layer table",
                    rel.display()
                )),
            }
        }
    }
    bad
}

fn collect_rs(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("source directory reads") {
        let path = entry.expect("directory entry").path();
        if path.is_dir() {
            collect_rs(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

#[test]
fn imports_name_the_layers_of_paths_groups_and_descriptions() {
    let text = "use crate::scene::desc::RigDesc;\n\
                use crate::{light::{Light, LightSet}, scene::Scene};\n\
                // crate::cli is only mentioned here\n\
                let x = crate::film::Film::new(); $crate::town::x(); my_crate::dataset::y();\n";
    let got = imports(text);
    assert_eq!(
        got,
        vec![
            (1, "scene::desc".to_string()),
            (2, "light".to_string()),
            (2, "scene".to_string()),
            (4, "film".to_string()),
        ]
    );
    assert_eq!(
        layer_of_file(Path::new("scene/desc/rig.rs")).as_deref(),
        Some("scene::desc")
    );
    assert_eq!(
        layer_of_file(Path::new("weather.rs")).as_deref(),
        Some("weather")
    );
    assert_eq!(layer_of_file(Path::new("lib.rs")), None);
    // The table's order is the rule: scene::desc under camera is an upward use.
    assert!(rank("camera") < rank("scene::desc") && rank("scene::desc") < rank("scene"));
}

#[test]
fn every_module_uses_only_lower_layers() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let bad = violations(&src);
    assert!(bad.is_empty(), "upward imports:\n{}", bad.join("\n"));
}
