//! Dataset round trips through the real binary: a run verifies whole and
//! resumes as all-skipped; a resume with --check-hashes re-renders exactly
//! a corrupted and a truncated frame; shards unite to the one-shard bytes;
//! tampering is detected and repaired; a different configuration is refused
//! naming the keys; config errors name the file and key.

use crate::common::dataset;

use dataset::*;

#[test]
fn run_verifies_whole_and_second_run_skips_every_frame() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write_config(
        dir.path(),
        "c.toml",
        &tiny_config(&["normal", "pitch30"], 2),
    );
    let out = dir.path().join("out");
    let o = dataset(&cfg, &out, &[]);
    ok(&o);
    assert!(
        text(&o).contains("4 frames done, 0 skipped, 0 failed"),
        "{}",
        text(&o)
    );
    assert_eq!(manifest_lines(&out), 4);
    // 7 + 5 per baseline files per frame, plus dataset.json.
    assert_eq!(data_files(&out).len(), 4 * (7 + 5 * 2) + 1);
    assert!(out
        .join("town01/pitch30_clear/0000/baseline_054/disp/000001.pfm")
        .is_file());
    let v = verify(&out, &[]);
    ok(&v);
    assert!(text(&v).contains("4 frames ok"), "{}", text(&v));
    let again = dataset(&cfg, &out, &["--check-hashes"]);
    ok(&again);
    assert!(
        text(&again).contains("0 frames done, 4 skipped"),
        "{}",
        text(&again)
    );
    assert_eq!(manifest_lines(&out), 4);
}

#[test]
fn resume_with_check_hashes_re_renders_exactly_the_corrupted_and_truncated_frames() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write_config(
        dir.path(),
        "c.toml",
        &tiny_config(&["normal", "pitch30"], 2),
    );
    let out = dir.path().join("out");
    ok(&dataset(&cfg, &out, &[]));
    let files = data_files(&out);
    let lines = lines_by_frame(&out);
    // Same size, other bytes: only a hash finds it. And a truncated file.
    let corrupted = "town01/normal_clear/0000/000000";
    let truncated = "town01/pitch30_clear/0000/000001";
    flip_byte(&out.join("town01/normal_clear/0000/left/rgb/000000.png"));
    truncate_half(&out.join("town01/pitch30_clear/0000/baseline_010/disp/000001.pfm"));
    let before = mtimes(&out);

    let o = dataset(&cfg, &out, &["--check-hashes"]);
    ok(&o);
    assert!(
        text(&o).contains("2 frames done, 2 skipped, 0 failed"),
        "{}",
        text(&o)
    );
    assert_eq!(data_files(&out), files);
    // Every file of the two frames is written again, no other file.
    let mut redone = frame_files(files.keys(), corrupted);
    redone.extend(frame_files(files.keys(), truncated));
    assert_eq!(redone.len(), 2 * 17);
    let after = mtimes(&out);
    for rel in files.keys() {
        assert_eq!(
            after[rel] != before[rel],
            redone.contains(rel),
            "{rel}: written again or not"
        );
    }
    // One line per frame: the two new ones replace theirs, the rest stay.
    let now = lines_by_frame(&out);
    assert_eq!(now.len(), 4);
    for (id, l) in &now {
        assert_eq!(l.len(), 1, "{id}: {l:?}");
        let redone = id == corrupted || id == truncated;
        assert_eq!(*l != lines[id], redone, "{id}: line replaced or not");
    }
    ok(&verify(&out, &[]));
}

#[test]
fn three_shards_unite_to_the_one_shard_bytes() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write_config(dir.path(), "c.toml", &tiny_config(&["normal", "roll15"], 2));
    let one = dir.path().join("one");
    ok(&dataset(&cfg, &one, &[]));
    let many = dir.path().join("many");
    for i in 1..=3 {
        let s = format!("{i}/3");
        ok(&dataset(&cfg, &many, &["--shard", &s]));
        assert!(many
            .join(format!("manifest/shard-{i}-of-3.jsonl"))
            .is_file());
    }
    assert_eq!(manifest_lines(&many), 4);
    let (a, b) = (data_files(&one), data_files(&many));
    assert_eq!(a.len(), 4 * 17 + 1);
    assert_eq!(a, b);
    ok(&verify(&many, &[]));
}

#[test]
fn tampering_is_detected_and_repaired_to_the_original_bytes() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write_config(dir.path(), "c.toml", &tiny_config(&["normal"], 3));
    let out = dir.path().join("out");
    ok(&dataset(&cfg, &out, &[]));
    let before = data_files(&out);
    let seq = out.join("town01/normal_clear/0000");
    // A flipped byte, a truncated file, a deleted right image, an extra file.
    let rgb = seq.join("left/rgb/000000.png");
    let mut bytes = std::fs::read(&rgb).unwrap();
    let mid = bytes.len() / 2;
    bytes[mid] ^= 0x40;
    std::fs::write(&rgb, &bytes).unwrap();
    let disp = seq.join("baseline_010/disp/000001.pfm");
    let len = std::fs::metadata(&disp).unwrap().len();
    std::fs::OpenOptions::new()
        .write(true)
        .open(&disp)
        .unwrap()
        .set_len(len / 2)
        .unwrap();
    std::fs::remove_file(seq.join("baseline_054/rgb/000002.png")).unwrap();
    std::fs::write(seq.join("left/rgb/stray.png"), b"not a frame").unwrap();

    let v = verify(&out, &[]);
    assert_eq!(v.status.code(), Some(1), "{}", text(&v));
    let t = text(&v);
    assert!(t.contains("left/rgb/000000.png: SHA-256 differs"), "{t}");
    assert!(
        t.contains(&format!(
            "baseline_010/disp/000001.pfm: {} bytes, expected {len}",
            len / 2
        )),
        "{t}"
    );
    assert!(
        t.contains("baseline_054/rgb/000002.png: file is missing"),
        "{t}"
    );
    assert!(
        t.contains("extra, kept town01/normal_clear/0000/left/rgb/stray.png"),
        "{t}"
    );
    assert!(t.contains("0 frames ok"), "{t}");

    let r = verify(&out, &["--repair"]);
    ok(&r);
    assert!(text(&r).contains("re-rendering 3 frames"), "{}", text(&r));
    // The user's file stays; the dataset is back to its bytes.
    let mut after = data_files(&out);
    assert!(after
        .remove("town01/normal_clear/0000/left/rgb/stray.png")
        .is_some());
    assert_eq!(after, before);
    assert_eq!(manifest_lines(&out), 3);
    ok(&verify(&out, &[]));
}

#[test]
fn different_configuration_in_a_used_directory_is_refused_unless_forced() {
    let dir = tempfile::tempdir().unwrap();
    let a = write_config(dir.path(), "a.toml", &tiny_config(&["normal"], 1));
    let b = write_config(dir.path(), "b.toml", &tiny_config(&["roll05"], 1));
    let out = dir.path().join("out");
    ok(&dataset(&a, &out, &[]));
    let refused = dataset(&b, &out, &[]);
    assert_eq!(refused.status.code(), Some(2));
    // The refusal names the key that differs, with both values.
    assert!(
        text(&refused).contains(
            "different configuration (configs = [\"normal\"] in dataset.json, \
             [\"roll05\"] in the new configuration)"
        ),
        "{}",
        text(&refused)
    );
    assert!(!out.join("town01/roll05_clear").exists());
    // A file of the user's beside the old frames survives the restart.
    std::fs::write(out.join("town01/normal_clear/notes.txt"), b"mine").unwrap();
    let forced = dataset(&b, &out, &["--force"]);
    ok(&forced);
    assert!(out
        .join("town01/roll05_clear/0000/left/rgb/000000.png")
        .is_file());
    assert!(
        !out.join("town01/normal_clear/0000").exists(),
        "the replaced dataset's frames are gone"
    );
    assert_eq!(
        std::fs::read(out.join("town01/normal_clear/notes.txt")).unwrap(),
        b"mine"
    );

    let foreign = dir.path().join("foreign");
    std::fs::create_dir_all(foreign.join("sub")).unwrap();
    std::fs::write(foreign.join("notes.txt"), b"mine").unwrap();
    std::fs::write(foreign.join("sub/data.bin"), [0u8, 1, 2, 3]).unwrap();
    let before = tree(&foreign);
    let refused = dataset(&a, &foreign, &[]);
    assert_eq!(refused.status.code(), Some(2));
    assert!(
        text(&refused).contains("no dataset.json") && text(&refused).contains("foreign"),
        "{}",
        text(&refused)
    );
    assert_eq!(tree(&foreign), before, "the refused directory was touched");
}

#[test]
fn config_errors_name_the_file_and_key() {
    let dir = tempfile::tempdir().unwrap();
    let text_cfg = tiny_config(&["normal"], 1).replace("[\"clear\"]", "[\"clear\", \"snow\"]");
    let cfg = write_config(dir.path(), "bad.toml", &text_cfg);
    let o = dataset(&cfg, &dir.path().join("out"), &[]);
    assert_eq!(o.status.code(), Some(2));
    let t = text(&o);
    assert!(
        t.contains("bad.toml") && t.contains("weathers[1]") && t.contains("snow"),
        "{t}"
    );
    assert!(!dir.path().join("out").exists());
    let cfg = write_config(
        dir.path(),
        "typo.toml",
        &format!("{}sppp = 2\n", tiny_config(&["normal"], 1)),
    );
    let o = dataset(&cfg, &dir.path().join("out"), &[]);
    let t = text(&o);
    assert_eq!(o.status.code(), Some(2), "{t}");
    assert!(t.contains("typo.toml") && t.contains("'sppp'"), "{t}");
    assert!(!dir.path().join("out").exists(), "typo.toml wrote output");
    // A valid configuration: the shard argument is what is refused.
    let good = write_config(dir.path(), "good.toml", &tiny_config(&["normal"], 1));
    for shard in ["0/3", "4/3"] {
        let o = dataset(&good, &dir.path().join("out"), &["--shard", shard]);
        let t = text(&o);
        assert_eq!(o.status.code(), Some(2), "--shard {shard}: {t}");
        assert!(
            t.contains("--shard") && t.contains(shard) && t.contains("1-based"),
            "{t}"
        );
        assert!(
            !dir.path().join("out").exists(),
            "--shard {shard} wrote output"
        );
    }
}

#[test]
fn every_layout_is_written_from_one_render_sharded_or_not_and_verifies() {
    let dir = tempfile::tempdir().unwrap();
    let text = tiny_config(&["normal", "pitch30"], 1)
        + "layouts = [\"native\", \"stereocarla\", \"kitti\", \"sceneflow\"]\n";
    let cfg = write_config(dir.path(), "c.toml", &text);
    let one = dir.path().join("one");
    ok(&dataset(&cfg, &one, &[]));
    let many = dir.path().join("many");
    for s in ["1/2", "2/2"] {
        ok(&dataset(&cfg, &many, &["--shard", s]));
    }
    assert_eq!(data_files(&one), data_files(&many));
    ok(&verify(&one, &[]));
    // Every entry of the stereocarla split list exists: left, right, depth.
    let list = std::fs::read_to_string(one.join("stereocarla/splits/stereocarla_all.txt")).unwrap();
    let entries: Vec<&str> = list.split_whitespace().collect();
    assert_eq!(
        entries.len(),
        2 * 2 * 3,
        "2 frames × 2 baselines × (left right depth)"
    );
    for e in entries {
        assert!(one.join("stereocarla").join(e).is_file(), "{e} missing");
    }
    assert!(one.join("kitti/baseline_054").is_dir());
    assert!(one.join("sceneflow/disparity").is_dir());
}
