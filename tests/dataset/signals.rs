//! Interruptions through the real binary: SIGKILL after the first manifest
//! line, then a resume (which sweeps the temporary files left behind), ends
//! byte-identical to an uninterrupted run; SIGTERM
//! stops cleanly and promptly (at most the frame being written finishes),
//! with no partial frame and no temporary file.

use crate::common::dataset;

use std::path::Path;
use std::process::{Child, Stdio};
use std::time::{Duration, Instant};

use dataset::*;

fn spawn(cfg: &Path, out: &Path) -> Child {
    let s = scenes();
    parallax(&[
        "dataset",
        cfg.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--scenes",
        &s,
        "--threads",
        "2",
    ])
    .stdout(Stdio::null())
    .stderr(Stdio::null())
    .spawn()
    .unwrap()
}

/// Waits until the root holds at least one manifest line.
fn wait_for_first_line(out: &Path, child: &mut Child) {
    let t0 = Instant::now();
    while manifest_lines(out) < 1 {
        assert!(
            child.try_wait().unwrap().is_none(),
            "run ended before its first line"
        );
        assert!(
            t0.elapsed() < Duration::from_secs(60),
            "no manifest line after 60 s"
        );
        std::thread::sleep(Duration::from_millis(5));
    }
}

fn temp_files(root: &Path) -> Vec<String> {
    walk(root)
        .into_iter()
        .filter(|(_, p, is_dir)| !is_dir && p.to_string_lossy().contains(".tmp-"))
        .map(|(_, p, _)| p.display().to_string())
        .collect()
}

#[test]
fn sigkill_then_resume_is_byte_identical_to_an_uninterrupted_run() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write_config(
        dir.path(),
        "c.toml",
        &tiny_config(&["normal", "pitch00"], 3),
    );
    let reference = dir.path().join("ref");
    ok(&dataset(&cfg, &reference, &[]));
    let out = dir.path().join("out");
    let mut child = spawn(&cfg, &out);
    wait_for_first_line(&out, &mut child);
    child.kill().unwrap();
    child.wait().unwrap();
    let done_before = manifest_lines(&out);
    assert!(done_before < 6, "the kill came after the last frame");
    // Temporary files as a kill mid-write leaves them: of a frame and of
    // dataset.json (the atomic writer's `<name>.tmp-<pid>-<n>`).
    let planted = [
        out.join("town01/pitch00_clear/0000/left/rgb/000002.png.tmp-4242-0"),
        out.join("dataset.json.tmp-4242-1"),
    ];
    for p in &planted {
        std::fs::create_dir_all(p.parent().unwrap()).unwrap();
        std::fs::write(p, b"half written").unwrap();
    }
    let o = dataset(&cfg, &out, &[]);
    ok(&o);
    let t = text(&o);
    assert!(t.contains(&format!("{} skipped", done_before)), "{t}");
    assert!(t.contains("temporary files of an interrupted run"), "{t}");
    for p in &planted {
        assert!(!p.exists(), "{} was not swept", p.display());
    }
    assert!(temp_files(&out).is_empty());
    assert_eq!(data_files(&out), data_files(&reference));
    ok(&verify(&out, &[]));
}

#[test]
fn sigterm_stops_with_no_partial_frame() {
    let dir = tempfile::tempdir().unwrap();
    // Enough frames that the run cannot end before the signal lands, even on
    // a fast machine (it stops long before the last one).
    const FRAMES: usize = 2 * 20;
    let cfg = write_config(
        dir.path(),
        "c.toml",
        &tiny_config(&["normal", "roll30"], 20),
    );
    let out = dir.path().join("out");
    let mut child = spawn(&cfg, &out);
    wait_for_first_line(&out, &mut child);
    let lines_at_signal = manifest_lines(&out);
    let kill = std::process::Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(kill.success());
    let status = child.wait().unwrap();
    assert_eq!(status.code(), Some(130));
    assert!(temp_files(&out).is_empty(), "{:?}", temp_files(&out));
    // Whatever exists is whole: verify finds frames missing, nothing else.
    let v = verify(&out, &[]);
    let t = text(&v);
    let lines = manifest_lines(&out);
    assert!((1..FRAMES).contains(&lines), "{t}");
    // Prompt: a frame being written when the signal came may finish, no
    // frame that was still rendering may (no wall-clock bound: CI is loaded).
    assert!(
        lines <= lines_at_signal + 1,
        "{lines} lines after {lines_at_signal} at the signal"
    );
    assert!(t.contains(&format!("{lines} frames ok")), "{t}");
    assert!(
        t.contains(&format!(
            "{} missing, 0 corrupted, 0 duplicate, 0 extra files",
            FRAMES - lines
        )),
        "{t}"
    );
}
