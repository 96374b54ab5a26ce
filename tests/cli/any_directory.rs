//! Every command works from any directory: the town descriptions and the
//! street scene are built into the binary. Run from a temporary working
//! directory (not the repository): `render --town`, `dataset`, `verify
//! --repair` and `bench` without a scene. `--scenes DIR` overrides the
//! built-in towns, a missing directory or town is refused (exit 2, named),
//! and a dataset refuses to resume with other town descriptions than the
//! ones `dataset.json` records.

use std::path::Path;
use std::process::Output;

use serde_json::Value;

use crate::common::cli::parallax_in;

fn text(o: &Output) -> String {
    format!(
        "exit {:?}\n{}{}",
        o.status.code(),
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

fn ok(cwd: &Path, args: &[&str]) -> Output {
    let o = parallax_in(cwd, args);
    assert!(o.status.success(), "{args:?}: {}", text(&o));
    o
}

fn refused(cwd: &Path, args: &[&str], needles: &[&str]) {
    let o = parallax_in(cwd, args);
    let t = text(&o);
    assert_eq!(o.status.code(), Some(2), "{args:?}: {t}");
    for n in needles {
        assert!(t.contains(n), "{args:?}: no '{n}' in {t}");
    }
}

fn json(path: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

const TINY: &str = "seed = 5\ntowns = [\"town02\"]\nconfigs = [\"normal\"]\n\
weathers = [\"clear\"]\nbaselines_cm = [54.0]\nframes_per_sequence = 1\n\
width = 32\nheight = 18\nspp = 1\nmax_depth = 2\n";

#[test]
fn render_town_dataset_and_verify_repair_run_outside_the_repository() {
    let cwd = tempfile::tempdir().unwrap();
    let cwd = cwd.path();
    assert!(!cwd.join("scenes").exists());
    #[rustfmt::skip]
    ok(cwd, &[
        "render", "--town", "town02", "--seed", "3", "--width", "32", "--height", "18",
        "--spp", "1", "--baselines", "54", "--threads", "2", "-o", "one",
    ]);
    let cam = json(&cwd.join("one/cameras/000000.json"));
    assert_eq!(cam["town"]["source"], "built-in", "{cam}");

    std::fs::write(cwd.join("tiny.toml"), TINY).unwrap();
    ok(cwd, &["dataset", "tiny.toml", "-o", "ds", "--threads", "2"]);
    let meta = json(&cwd.join("ds/dataset.json"));
    assert_eq!(meta["towns"][0]["source"], "built-in", "{meta}");
    let rgb = cwd.join("ds/town02/normal_clear/0000/left/rgb/000000.png");
    let before = std::fs::read(&rgb).unwrap();
    std::fs::remove_file(&rgb).unwrap();
    let o = ok(cwd, &["verify", "ds", "--repair", "--threads", "2"]);
    assert!(text(&o).contains("whole"), "{}", text(&o));
    assert_eq!(
        std::fs::read(&rgb).unwrap(),
        before,
        "repaired to the same bytes"
    );

    // The built-in towns are the repository's: the same frame from --scenes.
    let repo = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    #[rustfmt::skip]
    ok(cwd, &[
        "render", "--town", "town02", "--scenes", repo.to_str().unwrap(), "--seed", "3",
        "--width", "32", "--height", "18", "--spp", "1", "--baselines", "54",
        "--threads", "2", "-o", "two",
    ]);
    for rel in ["left/rgb/000000.png", "baseline_054/disp/000000.pfm"] {
        assert_eq!(
            std::fs::read(cwd.join("one").join(rel)).unwrap(),
            std::fs::read(cwd.join("two").join(rel)).unwrap(),
            "{rel}"
        );
    }
    let two = json(&cwd.join("two/cameras/000000.json"));
    assert_eq!(two["town"]["sha256"], cam["town"]["sha256"]);
    let town02 = repo.join("town02.toml");
    assert_eq!(two["town"]["source"], town02.display().to_string());
}

#[test]
fn bench_without_a_scene_runs_outside_the_repository() {
    let cwd = tempfile::tempdir().unwrap();
    #[rustfmt::skip]
    let o = ok(cwd.path(), &[
        "bench", "--width", "16", "--height", "9", "--spp", "1", "--threads", "1",
    ]);
    assert!(text(&o).contains("Mrays/s"), "{}", text(&o));
}

#[test]
fn scenes_dir_overrides_and_bad_ones_are_refused() {
    let cwd = tempfile::tempdir().unwrap();
    let cwd = cwd.path();
    // A town02 of our own: denser traffic than the built-in one.
    let repo = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/town02.toml");
    let own = std::fs::read_to_string(repo).unwrap();
    let own = own
        .lines()
        .map(|l| {
            if l.starts_with("traffic_density") {
                "traffic_density = 0.05".to_string()
            } else {
                l.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n");
    std::fs::create_dir(cwd.join("mine")).unwrap();
    std::fs::write(cwd.join("mine/town02.toml"), &own).unwrap();
    std::fs::write(cwd.join("tiny.toml"), TINY).unwrap();

    refused(
        cwd,
        &[
            "render", "--town", "town02", "--scenes", "nowhere", "-o", "o",
        ],
        &["--scenes nowhere", "no such directory"],
    );
    refused(
        cwd,
        &["render", "--town", "town03", "--scenes", "mine", "-o", "o"],
        &["mine/town03.toml"],
    );
    refused(
        cwd,
        &["dataset", "tiny.toml", "-o", "o", "--scenes", "nowhere"],
        &["--scenes nowhere"],
    );
    refused(cwd, &["town", "town11"], &["town11", "built in: town01"]);
    assert!(!cwd.join("o").exists(), "nothing written");

    // A dataset made from the built-in town02 does not resume with ours.
    ok(cwd, &["dataset", "tiny.toml", "-o", "ds", "--threads", "2"]);
    let meta_before = std::fs::read(cwd.join("ds/dataset.json")).unwrap();
    let sha = parallax::output::sha256_bytes(own.as_bytes());
    refused(
        cwd,
        &["dataset", "tiny.toml", "-o", "ds", "--scenes", "mine"],
        &["town02", &sha, "built-in"],
    );
    // Nor is it repaired with ours, and the refused repair touches nothing.
    let rgb = cwd.join("ds/town02/normal_clear/0000/left/rgb/000000.png");
    std::fs::remove_file(&rgb).unwrap();
    let manifest = std::fs::read(cwd.join("ds/manifest/shard-1-of-1.jsonl")).unwrap();
    refused(
        cwd,
        &["verify", "ds", "--repair", "--scenes", "mine"],
        &["town02", &sha],
    );
    assert_eq!(
        std::fs::read(cwd.join("ds/dataset.json")).unwrap(),
        meta_before
    );
    let after = std::fs::read(cwd.join("ds/manifest/shard-1-of-1.jsonl")).unwrap();
    assert_eq!(after, manifest);
    assert!(!rgb.exists());
}
