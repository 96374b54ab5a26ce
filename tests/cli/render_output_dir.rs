//! `render -o DIR` over what is already there: a directory that is not a
//! render's output is refused untouched (exit 2); an earlier render's output
//! is replaced whole, and stays whole if the new render is interrupted; an
//! unusable DIR is refused before any render work; `--help` names frame K.

use crate::common::dataset;

use std::collections::BTreeMap;
use std::os::unix::process::CommandExt;
use std::path::Path;
use std::process::{Output, Stdio};
use std::time::{Duration, Instant};

use dataset::{parallax, text, walk};

/// Every entry below `root` with its bytes (empty for folders).
fn tree(root: &Path) -> BTreeMap<String, Vec<u8>> {
    walk(root)
        .into_iter()
        .map(|(rel, p, is_dir)| {
            (
                rel,
                if is_dir {
                    vec![]
                } else {
                    std::fs::read(p).unwrap()
                },
            )
        })
        .collect()
}

/// `render scenes/street.toml` at `w`×`h`, `spp` spp, seed 2, with `extra`.
fn street_args(out: &Path, w: u32, h: u32, spp: u32, extra: &[&str]) -> Vec<String> {
    let scene = format!("{}/scenes/street.toml", env!("CARGO_MANIFEST_DIR"));
    let mut args: Vec<String> = ["render", &scene, "--seed", "2", "--threads", "2", "-o"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    args.push(out.to_str().unwrap().into());
    for (k, v) in [("--width", w), ("--height", h), ("--spp", spp)] {
        args.extend([k.to_string(), v.to_string()]);
    }
    args.extend(extra.iter().map(|s| s.to_string()));
    args
}

fn render(out: &Path, extra: &[&str]) -> Output {
    let args = street_args(out, 32, 18, 1, extra);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    parallax(&args).output().unwrap()
}

fn top_level(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

#[test]
fn directory_of_other_files_is_refused_untouched() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("photos");
    std::fs::create_dir_all(out.join("left/rgb")).unwrap();
    std::fs::write(out.join("left/rgb/000000.png"), b"not ours?").unwrap();
    std::fs::write(out.join("notes.txt"), b"keep me").unwrap();
    let before = tree(dir.path());
    let o = render(&out, &["--baselines", "54"]);
    let msg = text(&o);
    assert_eq!(o.status.code(), Some(2), "{msg}");
    for needle in [
        "--output",
        "photos",
        "notes.txt",
        "not part of a parallax render",
    ] {
        assert!(msg.contains(needle), "message lacks {needle:?}: {msg}");
    }
    assert!(!msg.contains("rendered"), "{msg}");
    assert_eq!(tree(dir.path()), before, "something was touched");
}

#[test]
fn rerender_replaces_the_earlier_render_whole() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let o = render(&out, &["--baselines", "54,100"]);
    assert!(o.status.success(), "{}", text(&o));
    assert_eq!(
        top_level(&out),
        ["baseline_054", "baseline_100", "cameras", "left"]
    );
    let o = render(&out, &["--baselines", "10"]);
    assert!(o.status.success(), "{}", text(&o));
    assert_eq!(top_level(&out), ["baseline_010", "cameras", "left"]);
    let cam: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("cameras/000000.json")).unwrap()).unwrap();
    assert_eq!(cam["right"].as_array().map(Vec::len), Some(1), "{cam}");
    // No staging or set-aside directory is left beside it.
    assert_eq!(top_level(dir.path()), ["out"]);
}

#[test]
fn rerender_over_its_preview_replaces_both_but_a_users_file_there_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let o = render(&out, &["--baselines", "54"]);
    assert!(o.status.success(), "{}", text(&o));
    let o = parallax(&["preview", out.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", text(&o));
    assert!(out.join("preview/000000_depth.png").is_file());
    // The pictures of the old render go with it.
    let o = render(&out, &["--baselines", "54"]);
    assert!(o.status.success(), "{}", text(&o));
    assert_eq!(top_level(&out), ["baseline_054", "cameras", "left"]);
    // A file of the user's own in the preview folder is not the render's.
    std::fs::create_dir(out.join("preview")).unwrap();
    std::fs::write(out.join("preview/notes.txt"), b"mine").unwrap();
    let o = render(&out, &["--baselines", "54"]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("notes.txt"), "{}", text(&o));
    assert_eq!(
        std::fs::read(out.join("preview/notes.txt")).unwrap(),
        b"mine"
    );
}

#[test]
fn unusable_output_is_refused_before_rendering() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("plain");
    std::fs::write(&file, b"a file").unwrap();
    let out = file.join("out");
    let o = render(&out, &["--baselines", "54"]);
    let msg = text(&o);
    assert_eq!(o.status.code(), Some(2), "{msg}");
    assert!(
        msg.contains("--output") && msg.contains("plain/out"),
        "{msg}"
    );
    assert!(!msg.contains("rendered"), "{msg}");
    assert_eq!(top_level(dir.path()), ["plain"]);
}

#[test]
fn interrupted_rerender_leaves_the_earlier_render_whole() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let o = render(&out, &["--baselines", "54"]);
    assert!(o.status.success(), "{}", text(&o));
    let before = tree(&out);
    // A render long enough to be stopped while it runs (minutes at 2 cores).
    let args = street_args(&out, 640, 360, 4096, &["--baselines", "10,54,100"]);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let mut cmd = parallax(&args);
    cmd.stdout(Stdio::null()).stderr(Stdio::null());
    // A background job of a non-interactive shell (`nohup cargo test &`)
    // inherits SIGINT ignored; the render must see it as a terminal's
    // Ctrl-C would.
    // SAFETY: between fork and exec, only the async-signal-safe signal(2).
    unsafe {
        cmd.pre_exec(|| {
            libc::signal(libc::SIGINT, libc::SIG_DFL);
            Ok(())
        });
    }
    let mut child = cmd.spawn().unwrap();
    let staging_seen = || {
        top_level(dir.path())
            .iter()
            .any(|n| n.starts_with(".out.partial-"))
    };
    let t0 = Instant::now();
    while !staging_seen() && t0.elapsed() < Duration::from_secs(20) {
        std::thread::sleep(Duration::from_millis(20));
    }
    assert!(staging_seen(), "no staging directory appeared");
    std::thread::sleep(Duration::from_millis(300));
    let status = std::process::Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    let exit = child.wait().unwrap();
    assert!(
        !exit.success(),
        "the long render finished before the signal"
    );
    assert_eq!(tree(&out), before, "the earlier render changed");
}

#[test]
fn help_says_which_frame_is_written() {
    let o = parallax(&["render", "--help"]).output().unwrap();
    let help = text(&o);
    assert!(o.status.success(), "{help}");
    assert!(!help.contains("frame 000000 is written"), "{help}");
    assert!(
        help.contains("--sample-frame, else --frame K with --town"),
        "{help}"
    );
    assert!(help.contains("replaced whole"), "{help}");
}
