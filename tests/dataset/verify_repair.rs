//! `verify --repair` through the real binary: it re-renders exactly the
//! damaged frame of several, removes only the dataset's own stray files and
//! keeps the user's, changes nothing when it cannot render, and a manifest
//! line naming one file twice is reported and repaired. What is the
//! dataset's is exact: a frame's number in a folder, extension or sequence
//! folder the layouts do not write is the user's, for `--repair` and for
//! `dataset --force`; the other layouts' files of a planned frame are the
//! dataset's.

use crate::common::dataset;

use std::collections::BTreeSet;
use std::path::Path;

use dataset::*;

#[test]
fn repair_re_renders_only_the_damaged_frame_and_keeps_the_users_files() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write_config(dir.path(), "c.toml", &tiny_config(&["normal"], 3));
    let out = dir.path().join("out");
    ok(&dataset(&cfg, &out, &[]));
    let files = data_files(&out);
    let lines = lines_by_frame(&out);
    let seq = out.join("town01/normal_clear/0000");
    // One frame of three damaged.
    flip_byte(&seq.join("baseline_054/disp/000001.pfm"));
    // A stale temporary of the atomic writer: the dataset's.
    let temp = seq.join("left/rgb/000002.png.tmp-4242-0");
    std::fs::write(&temp, b"half a frame").unwrap();
    // The user's files: beside the frames, named after a frame, at the root.
    let mine = [
        "town01/normal_clear/0000/left/rgb/stray.png",
        "town01/normal_clear/0000/left/rgb/000001.png.bak",
        "notes.txt",
    ];
    for m in mine {
        std::fs::write(out.join(m), m.as_bytes()).unwrap();
    }
    let before = mtimes(&out);

    let v = verify(&out, &[]);
    let t = text(&v);
    assert_eq!(v.status.code(), Some(1), "{t}");
    assert!(
        t.contains("corrupted  town01/normal_clear/0000/000001: town01/normal_clear/0000/baseline_054/disp/000001.pfm: SHA-256 differs"),
        "{t}"
    );
    assert!(
        t.contains("extra      town01/normal_clear/0000/left/rgb/000002.png.tmp-4242-0"),
        "{t}"
    );
    for m in mine {
        assert!(t.contains(&format!("extra, kept {m} ")), "{m}: {t}");
    }
    assert!(
        t.contains("2 frames ok, 51 files checked; 0 missing, 1 corrupted, 0 duplicate, 1 extra files, 0 bad manifest lines; 3 files not the dataset's kept"),
        "{t}"
    );

    let r = verify(&out, &["--repair"]);
    ok(&r);
    let t = text(&r);
    assert!(t.contains("re-rendering 1 frames"), "{t}");
    assert!(
        t.contains("1 frames replaced, 0 not rendered (left as they were), 1 manifest lines dropped, 1 files removed"),
        "{t}"
    );
    assert!(!temp.exists());
    for m in mine {
        assert_eq!(std::fs::read(out.join(m)).unwrap(), m.as_bytes(), "{m}");
    }
    // The dataset's bytes are the original ones; only frame 1 was written
    // again (every file of it, no file of the others).
    let mut now = data_files(&out);
    for m in mine {
        now.remove(m);
    }
    assert_eq!(now, files);
    let after = mtimes(&out);
    let redone = frame_files(files.keys(), "town01/normal_clear/0000/000001");
    assert_eq!(redone.len(), 17);
    for rel in files.keys() {
        assert_eq!(
            after[rel] != before[rel],
            redone.contains(rel),
            "{rel}: written again or not"
        );
    }
    // One line per frame; frames 0 and 2 keep theirs byte for byte.
    let new_lines = lines_by_frame(&out);
    assert_eq!(new_lines.len(), 3);
    for (id, l) in &new_lines {
        assert_eq!(l.len(), 1, "{id}");
        let same = *l == lines[id];
        assert_eq!(same, !id.ends_with("000001"), "{id}: line replaced or not");
    }
    let v = verify(&out, &[]);
    ok(&v);
    assert!(text(&v).contains("extra, kept notes.txt"), "{}", text(&v));
}

#[test]
fn repair_that_cannot_render_changes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write_config(dir.path(), "c.toml", &tiny_config(&["normal"], 2));
    let out = dir.path().join("out");
    ok(&dataset(&cfg, &out, &[]));
    let seq = out.join("town01/normal_clear/0000");
    // A corrupted frame, an unreadable line, a stale temporary file.
    flip_byte(&seq.join("left/rgb/000000.png"));
    let manifest = out.join("manifest/shard-1-of-1.jsonl");
    let mut m = std::fs::read_to_string(&manifest).unwrap();
    m += "{\"town\": \"town01\", torn\n";
    std::fs::write(&manifest, m).unwrap();
    std::fs::write(seq.join("left/rgb/000001.png.tmp-4242-0"), b"x").unwrap();
    let report = text(&verify(&out, &[]));
    let snapshot = tree(&out);

    let mut args = vec![
        "verify".to_string(),
        out.display().to_string(),
        "--repair".into(),
    ];
    args.extend(["--scenes", "/nonexistent", "--threads", "2"].map(String::from));
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let r = parallax(&args).output().unwrap();
    let t = text(&r);
    assert_eq!(r.status.code(), Some(2), "{t}");
    // The towns are looked up before anything is staged or rendered.
    assert!(
        t.contains("--scenes /nonexistent: no such directory"),
        "{t}"
    );
    assert!(tree(&out) == snapshot, "the failed repair changed the root");
    assert_eq!(text(&verify(&out, &[])), report);
}

#[test]
fn a_line_naming_one_file_twice_is_reported_and_repaired() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write_config(dir.path(), "c.toml", &tiny_config(&["normal"], 1));
    let out = dir.path().join("out");
    ok(&dataset(&cfg, &out, &[]));
    let files = data_files(&out);
    let manifest = out.join("manifest/shard-1-of-1.jsonl");
    let text_before = std::fs::read_to_string(&manifest).unwrap();
    let mut line: serde_json::Value = serde_json::from_str(text_before.trim()).unwrap();
    let list = line["files"].as_array_mut().unwrap();
    let first = list[0].clone();
    let path = first["path"].as_str().unwrap().to_string();
    list.push(first);
    std::fs::write(&manifest, format!("{line}\n")).unwrap();

    let v = verify(&out, &[]);
    let t = text(&v);
    assert_eq!(v.status.code(), Some(1), "{t}");
    assert!(
        t.contains(&format!("shard-1-of-1.jsonl:1: names {path} twice")),
        "{t}"
    );
    assert!(t.contains("0 frames ok") && t.contains("1 missing"), "{t}");

    let r = verify(&out, &["--repair"]);
    ok(&r);
    assert!(text(&r).contains("re-rendering 1 frames"), "{}", text(&r));
    assert_eq!(data_files(&out), files);
    let lines = lines_by_frame(&out);
    let only: serde_json::Value = serde_json::from_str(&lines.values().next().unwrap()[0]).unwrap();
    assert_eq!(only["files"].as_array().unwrap().len(), 17);
}

#[test]
fn a_bad_line_beside_a_good_line_of_its_frame_is_dropped_by_repair() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write_config(dir.path(), "c.toml", &tiny_config(&["normal"], 1));
    let out = dir.path().join("out");
    ok(&dataset(&cfg, &out, &[]));
    let manifest = out.join("manifest/shard-1-of-1.jsonl");
    let good = std::fs::read_to_string(&manifest).unwrap();
    // A second line of the same frame that names one file twice: the frame
    // stays whole by its good line, the bad line must go.
    let mut line: serde_json::Value = serde_json::from_str(good.trim()).unwrap();
    let list = line["files"].as_array_mut().unwrap();
    list.push(list[0].clone());
    std::fs::write(&manifest, format!("{good}{line}\n")).unwrap();
    let v = verify(&out, &[]);
    assert_eq!(v.status.code(), Some(1), "{}", text(&v));
    assert!(text(&v).contains("twice"), "{}", text(&v));

    ok(&verify(&out, &["--repair"]));
    assert_eq!(std::fs::read_to_string(&manifest).unwrap(), good);
    ok(&verify(&out, &[]));
}

/// The paths `verify` reports as `extra` and as `extra, kept`.
fn extra_and_kept(report: &str) -> (BTreeSet<String>, BTreeSet<String>) {
    let mut extra = BTreeSet::new();
    let mut kept = BTreeSet::new();
    for l in report.lines() {
        if let Some(p) = l.strip_prefix("extra      ") {
            extra.insert(p.to_string());
        } else if let Some(p) = l.strip_prefix("extra, kept ") {
            kept.insert(p.trim_end_matches(" (not the dataset's)").to_string());
        }
    }
    (extra, kept)
}

/// Writes `bytes` at `root/rel`, creating its folders.
fn plant(root: &Path, rel: &str, bytes: &[u8]) {
    let p = root.join(rel);
    std::fs::create_dir_all(p.parent().unwrap()).unwrap();
    std::fs::write(p, bytes).unwrap();
}

#[test]
fn files_named_like_frames_outside_the_layout_are_kept_by_repair_and_force() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write_config(dir.path(), "c.toml", &tiny_config(&["normal"], 1));
    let out = dir.path().join("out");
    ok(&dataset(&cfg, &out, &[]));
    let seq = out.join("town01/normal_clear/0000");
    let png = std::fs::read(seq.join("left/rgb/000000.png")).unwrap();
    // The user's: a planned frame's number in a folder, with an extension or
    // below a sequence folder the native layout does not write, a baseline
    // not configured, a frame not planned, a temporary of one of these.
    let mine = [
        "town01/normal_clear/0000/mystuff/000000.txt",
        "town01/normal_clear/0000/mystuff/000000.txt.tmp-42-0",
        "town01/normal_clear/0000/left/rgb/000000.txt",
        "town01/normal_clear/0/left/rgb/000000.png",
        "town01/normal_clear/0000/baseline_300/rgb/000000.png",
        "town01/normal_clear/0000/left/rgb/000003.png",
    ];
    for m in mine {
        plant(&out, m, &png);
    }
    // The dataset's: a native file of the planned frame that its line does
    // not list (no HDR is configured), left by some other run.
    let hdr_rel = "town01/normal_clear/0000/left/rgb_hdr/000000.exr";
    let depth = std::fs::read(seq.join("left/depth/000000.exr")).unwrap();
    plant(&out, hdr_rel, &depth);

    let v = verify(&out, &[]);
    let t = text(&v);
    assert_eq!(v.status.code(), Some(1), "{t}");
    let (extra, kept) = extra_and_kept(&t);
    assert_eq!(extra, BTreeSet::from([hdr_rel.to_string()]), "{t}");
    assert_eq!(kept, mine.iter().map(|m| m.to_string()).collect(), "{t}");

    let r = verify(&out, &["--repair"]);
    ok(&r);
    assert!(
        text(&r).contains("0 frames replaced, 0 not rendered (left as they were), 0 manifest lines dropped, 1 files removed"),
        "{}",
        text(&r)
    );
    assert!(!out.join(hdr_rel).exists());
    for m in mine {
        assert_eq!(std::fs::read(out.join(m)).unwrap(), png, "{m}");
    }

    // `dataset --force` with another configuration removes the old
    // dataset's files (also one no line lists) and nothing of the user's.
    plant(&out, hdr_rel, &depth);
    let other = write_config(dir.path(), "o.toml", &tiny_config(&["roll05"], 1));
    ok(&dataset(&other, &out, &["--force"]));
    assert!(!seq.join("left/rgb/000000.png").exists());
    assert!(!out.join(hdr_rel).exists());
    for m in mine {
        assert_eq!(std::fs::read(out.join(m)).unwrap(), png, "{m}");
    }
    let v = verify(&out, &[]);
    ok(&v);
    let (extra, kept) = extra_and_kept(&text(&v));
    assert!(extra.is_empty(), "{}", text(&v));
    assert_eq!(kept, mine.iter().map(|m| m.to_string()).collect());
}

#[test]
fn other_layouts_files_of_a_planned_frame_are_the_datasets_and_only_those() {
    let dir = tempfile::tempdir().unwrap();
    let text_cfg = tiny_config(&["normal"], 2)
        + "layouts = [\"native\", \"kitti\", \"stereocarla\", \"sceneflow\"]\n";
    let cfg = write_config(dir.path(), "c.toml", &text_cfg);
    let out = dir.path().join("out");
    ok(&dataset(&cfg, &out, &[]));
    // Frame 1 loses its line (as when a run is killed between its files and
    // its line): every file it has in every layout is the dataset's.
    let lines = lines_by_frame(&out);
    let line1: serde_json::Value =
        serde_json::from_str(&lines["town01/normal_clear/0000/000001"][0]).unwrap();
    let files1: BTreeSet<String> = line1["files"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f["path"].as_str().unwrap().to_string())
        .collect();
    assert!(files1.iter().any(|f| f.starts_with("stereocarla/")));
    assert!(files1.iter().any(|f| f.starts_with("sceneflow/")));
    assert!(files1.iter().any(|f| f.starts_with("kitti/")));
    let manifest = out.join("manifest/shard-1-of-1.jsonl");
    let line0 = &lines["town01/normal_clear/0000/000000"][0];
    std::fs::write(&manifest, format!("{line0}\n")).unwrap();
    // The user's, in the layouts' folders: other names, an unplanned frame,
    // a temporary of such a file.
    let mine = [
        "kitti/baseline_054/image_2/mine.png",
        "kitti/baseline_054/image_2/mine.png.tmp-42-0",
        "kitti/baseline_054/image_2/town01_normal_clear_0000_000002.png",
        "sceneflow/disparity/baseline_054/town01_normal_clear_clear/0000/left/000001.png",
        "stereocarla/normal/town01/baseline_054/pose/0000_000001.txt",
    ];
    for m in mine {
        plant(&out, m, m.as_bytes());
    }

    let v = verify(&out, &[]);
    let t = text(&v);
    assert_eq!(v.status.code(), Some(1), "{t}");
    assert!(
        t.contains("missing    town01/normal_clear/0000/000001"),
        "{t}"
    );
    let (extra, kept) = extra_and_kept(&t);
    assert_eq!(extra, files1, "{t}");
    assert_eq!(kept, mine.iter().map(|m| m.to_string()).collect(), "{t}");

    let r = verify(&out, &["--repair"]);
    ok(&r);
    assert!(text(&r).contains("re-rendering 1 frames"), "{}", text(&r));
    for m in mine {
        assert_eq!(std::fs::read(out.join(m)).unwrap(), m.as_bytes(), "{m}");
    }
}
