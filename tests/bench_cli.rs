//! `parallax bench` through the real binary: a tiny analytic scene measured
//! over two rounds, and bad arguments refused with a message naming them.

use std::process::Command;

fn bench(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_parallax"))
        .arg("bench")
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap()
}

/// The CPU-scaled figure of a report line "NAME  W unit wall  C cpu ...".
fn cpu_figure(text: &str, name: &str) -> f64 {
    let line = text
        .lines()
        .find(|l| l.starts_with(name))
        .unwrap_or_else(|| panic!("no line {name:?} in\n{text}"));
    let words: Vec<&str> = line.split_whitespace().collect();
    let k = words.iter().position(|w| *w == "cpu").unwrap();
    words[k - 1].parse().unwrap()
}

#[test]
fn two_rounds_on_a_small_scene_report_every_figure() {
    let o = bench(&[
        "scenes/analytic/boxes.toml",
        "--width",
        "64",
        "--height",
        "36",
        "--threads",
        "1",
        "--rounds",
        "2",
    ]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(text.contains("1 threads"), "{text}");
    assert!(text.contains("medians of 2 rounds"), "{text}");
    for name in [
        "GT pass",
        "path tracing",
        "path samples",
        "raw primary single",
        "raw primary tile4x2",
        "raw incoherent hit",
        "raw shading any",
    ] {
        let x = cpu_figure(&text, name);
        assert!(x.is_finite() && x > 0.0, "{name}: {x}\n{text}");
    }
    // Every camera sample traces its camera ray; max depth 5 bounds the rest
    // (a closest hit and at most sun + sky shadow rays per vertex).
    let per_sample: f64 = text
        .split(" rays/sample")
        .next()
        .and_then(|s| s.rsplit('(').next())
        .unwrap()
        .parse()
        .unwrap();
    assert!((1.0..=16.0).contains(&per_sample), "{per_sample}\n{text}");
}

#[test]
fn bad_arguments_are_named() {
    for (args, needle) in [
        (
            vec!["scenes/analytic/boxes.toml", "--rounds", "0"],
            "--rounds",
        ),
        (
            vec!["scenes/analytic/boxes.toml", "--threads", "0"],
            "--threads",
        ),
        (vec!["no/such/mesh.obj"], "no/such/mesh.obj"),
    ] {
        let o = bench(&args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
    }
}
