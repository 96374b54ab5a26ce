//! `verify --repair` through the real binary: it re-renders exactly the
//! damaged frame of several, removes only the dataset's own stray files and
//! keeps the user's, changes nothing when it cannot render, and a manifest
//! line naming one file twice is reported and repaired.

mod dataset_common;

use dataset_common::*;

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
    assert!(t.contains("--scenes /nonexistent"), "{t}");
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
