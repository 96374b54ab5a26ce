//! `parallax dataset` taking its shard from a batch engine's environment,
//! through the real binary: a Slurm array (`SLURM_ARRAY_TASK_ID`, `_COUNT`,
//! `_MIN`) and a Kubernetes Indexed Job (`JOB_COMPLETION_INDEX`,
//! `PARALLAX_SHARD_COUNT`), as `deploy/` runs it (no `--shard`). Each task
//! writes its own manifest; the shards are disjoint, their union is the whole
//! plan and verifies; `--shard` wins over the environment; bad values exit 2.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;
use std::process::Output;

use crate::common::cli::parallax;

/// Every variable a batch engine may set; removed, then set as each test says.
const SHARD_VARS: [&str; 5] = [
    "SLURM_ARRAY_TASK_ID",
    "SLURM_ARRAY_TASK_COUNT",
    "SLURM_ARRAY_TASK_MIN",
    "JOB_COMPLETION_INDEX",
    "PARALLAX_SHARD_COUNT",
];

/// town01, 2 configurations × 2 frames = 4 frames of 32×18 at 1 spp.
const CONFIG: &str = "seed = 5\ntowns = [\"town01\"]\nconfigs = [\"normal\", \"roll15\"]\n\
weathers = [\"clear\"]\nbaselines_cm = [10.0, 54.0]\nframes_per_sequence = 2\nstride = 5\n\
width = 32\nheight = 18\nspp = 1\nmax_depth = 2\n";

/// `parallax dataset CONFIG -o OUT [extra]` with exactly the batch variables `env`.
fn dataset(root: &Path, out: &str, env: &[(&str, &str)], extra: &[&str]) -> Output {
    let config = root.join("c.toml");
    std::fs::write(&config, CONFIG).unwrap();
    let mut c = parallax(&[]);
    c.arg("dataset").arg(&config).arg("-o").arg(root.join(out));
    c.args(["--scenes", concat!(env!("CARGO_MANIFEST_DIR"), "/scenes")]);
    c.args(["--threads", "2"]).args(extra);
    for v in SHARD_VARS {
        c.env_remove(v);
    }
    c.envs(env.iter().copied());
    c.output().unwrap()
}

fn text(o: &Output) -> String {
    format!(
        "exit {:?}\n{}{}",
        o.status.code(),
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

/// Manifest file names below `out/manifest`.
fn manifests(out: &Path) -> BTreeSet<String> {
    let Ok(rd) = std::fs::read_dir(out.join("manifest")) else {
        return BTreeSet::new();
    };
    rd.map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect()
}

/// The frames of one manifest as "town/config_weather/sequence/frame", and
/// the files they list.
fn manifest_frames(path: &Path) -> (BTreeSet<String>, BTreeSet<String>) {
    let (mut frames, mut files) = (BTreeSet::new(), BTreeSet::new());
    for line in std::fs::read_to_string(path).unwrap().lines() {
        let v: serde_json::Value = serde_json::from_str(line).unwrap();
        let s = |k: &str| v[k].to_string();
        frames.insert(format!(
            "{}/{}_{}/{}/{}",
            s("town"),
            s("config"),
            s("weather"),
            s("sequence"),
            s("frame")
        ));
        for f in v["files"].as_array().unwrap() {
            assert!(files.insert(f["path"].as_str().unwrap().to_string()));
        }
    }
    (frames, files)
}

/// Runs both shards of a 2-way split, task by task, each with its own
/// variables; checks that each wrote exactly its own manifest, that their
/// frames and files are disjoint and that the union is the whole plan.
fn two_tasks(root: &Path, out: &str, tasks: [&[(&str, &str)]; 2]) {
    let dir = root.join(out);
    let mut all_frames = BTreeSet::new();
    let mut all_files = BTreeSet::new();
    for (k, env) in tasks.iter().enumerate() {
        let o = dataset(root, out, env, &[]);
        assert!(o.status.success(), "task {k}: {}", text(&o));
        let name = format!("shard-{}-of-2.jsonl", k + 1);
        assert!(
            text(&o).contains(&format!("shard {}/2: 2 frames done", k + 1)),
            "task {k}: {}",
            text(&o)
        );
        let want: BTreeSet<String> = (1..=k + 1)
            .map(|i| format!("shard-{i}-of-2.jsonl"))
            .collect();
        assert_eq!(manifests(&dir), want, "after task {k}");
        let (frames, files) = manifest_frames(&dir.join("manifest").join(&name));
        assert_eq!(frames.len(), 2, "{name}: {frames:?}");
        assert!(all_frames.is_disjoint(&frames), "{name} repeats a frame");
        assert!(all_files.is_disjoint(&files), "{name} repeats a file");
        all_frames.extend(frames);
        all_files.extend(files);
    }
    assert_eq!(all_frames.len(), 4, "{all_frames:?}");
    let v = parallax(&[]).arg("verify").arg(&dir).output().unwrap();
    assert!(v.status.success(), "{}", text(&v));
    assert!(text(&v).contains("4 frames ok"), "{}", text(&v));
}

/// SHA-256 of every file below `root` but the manifests, by relative path.
fn data_files(root: &Path, dir: &Path, out: &mut BTreeMap<String, String>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        let rel = p.strip_prefix(root).unwrap().to_string_lossy().into_owned();
        if p.is_dir() {
            data_files(root, &p, out);
        } else if !rel.starts_with("manifest") {
            out.insert(rel, parallax::output::sha256_file(&p).unwrap());
        }
    }
}

#[test]
fn slurm_and_indexed_job_tasks_write_disjoint_shards_that_verify_whole() {
    let dir = tempfile::tempdir().unwrap();
    let root = dir.path();
    // A 0-based Slurm array (--array=0-1): SLURM_ARRAY_TASK_MIN says so.
    let slurm = |id| {
        [
            ("SLURM_ARRAY_TASK_ID", id),
            ("SLURM_ARRAY_TASK_COUNT", "2"),
            ("SLURM_ARRAY_TASK_MIN", "0"),
        ]
    };
    two_tasks(root, "slurm", [&slurm("0"), &slurm("1")]);
    let k8s = |i| [("JOB_COMPLETION_INDEX", i), ("PARALLAX_SHARD_COUNT", "2")];
    two_tasks(root, "k8s", [&k8s("0"), &k8s("1")]);
    // The same shards, whichever engine numbered them: the same bytes.
    let (mut a, mut b) = (BTreeMap::new(), BTreeMap::new());
    data_files(&root.join("slurm"), &root.join("slurm"), &mut a);
    data_files(&root.join("k8s"), &root.join("k8s"), &mut b);
    assert_eq!(a.len(), 4 * (7 + 5 * 2) + 1);
    assert_eq!(a, b);
    // A task of the default 1-based array (no MIN) re-run after the fact:
    // task 2 of 2 is complete and skips; --shard overrides the variables.
    let task2 = [
        ("SLURM_ARRAY_TASK_ID", "2"),
        ("SLURM_ARRAY_TASK_COUNT", "2"),
    ];
    let o = dataset(root, "slurm", &task2, &[]);
    assert!(
        text(&o).contains("shard 2/2: 0 frames done, 2 skipped"),
        "{}",
        text(&o)
    );
    let o = dataset(root, "slurm", &task2, &["--shard", "1/2"]);
    assert!(
        text(&o).contains("shard 1/2: 0 frames done, 2 skipped"),
        "{}",
        text(&o)
    );
    assert_eq!(manifests(&root.join("slurm")).len(), 2);
}

#[test]
fn bad_shard_variables_exit_2_naming_them_and_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    for (env, needle) in [
        (&[("JOB_COMPLETION_INDEX", "0")][..], "PARALLAX_SHARD_COUNT"),
        (
            &[
                ("SLURM_ARRAY_TASK_ID", "x1"),
                ("SLURM_ARRAY_TASK_COUNT", "2"),
            ][..],
            "SLURM_ARRAY_TASK_ID='x1'",
        ),
        (
            &[("SLURM_ARRAY_TASK_ID", "3")][..],
            "SLURM_ARRAY_TASK_COUNT",
        ),
        (
            &[
                ("SLURM_ARRAY_TASK_ID", "3"),
                ("SLURM_ARRAY_TASK_COUNT", "2"),
            ][..],
            "SLURM_ARRAY_TASK_ID=3",
        ),
        (
            &[
                ("SLURM_ARRAY_TASK_ID", "0"),
                ("SLURM_ARRAY_TASK_COUNT", "2"),
            ][..],
            "SLURM_ARRAY_TASK_MIN",
        ),
    ] {
        let o = dataset(dir.path(), "out", env, &[]);
        assert_eq!(o.status.code(), Some(2), "{env:?}: {}", text(&o));
        assert!(text(&o).contains(needle), "{env:?}: {}", text(&o));
        assert!(!dir.path().join("out").exists(), "{env:?} wrote output");
    }
}
