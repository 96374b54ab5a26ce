//! Walks the output registry through a dataset root: every declared map of
//! a frame is written by the native writer at its `NativeLayout::path`, is
//! recognised by `native_path`, is the dataset's by the ownership rule, and
//! is checked by `verify` (reported when its manifest record goes). A map
//! declared without a writer, or written where nothing recognises it, fails.

use std::path::PathBuf;

use glam::{DMat3, DVec3, Vec3};

use super::manifest::{append_line, DatasetMeta, DATASET_JSON, MANIFEST_DIR};
use super::ownership::{slash, tests::line_of, Ownership};
use super::{parse_config, plan, verify_dataset};
use crate::camera::{Camera, Intrinsics, StereoRig};
use crate::film::Film;
use crate::integrator::gt::ViewGt;
use crate::output::frame::{write_native_frame, CameraFile, FrameSeeds, RigCameras, WriteOptions};
use crate::output::{native_path, write_json, FileRecord, NativeLayout, NativePath, MAPS};
use crate::render::{BaselineGt, FrameOutput, RenderStats};

const CONFIG: &str = "seed = 1\ntowns = [\"town01\"]\nconfigs = [\"normal\"]\n\
                      weathers = [\"clear\"]\nframes_per_sequence = 1\nwidth = 4\n\
                      height = 2\nbaselines_cm = [10.0, 54.0]\nhdr = true\n";

/// A 4×2 frame with every map filled, two baselines, three images.
fn frame() -> (StereoRig, FrameOutput) {
    let rig = StereoRig {
        left: Camera {
            intrinsics: Intrinsics::from_hfov(4, 2, 1.0),
            world_from_camera: DMat3::IDENTITY,
            center_world: DVec3::ZERO,
        },
        baselines_m: vec![0.1, 0.54],
    };
    let n = 8;
    let left = ViewGt {
        width: 4,
        height: 2,
        depth_z: vec![2.0; n],
        normal_world: vec![Vec3::Z; n],
        semantic: vec![7; n],
        instance: vec![300; n],
        mask: vec![1; n],
    };
    let baselines = rig
        .baselines_m
        .iter()
        .map(|&b| BaselineGt {
            baseline_m: b,
            disparity_left: vec![1.5; n],
            depth_right: vec![2.0; n],
            disparity_right: vec![1.5; n],
            occlusion: vec![255; n],
        })
        .collect();
    let mut film = Film::new(4, 2);
    film.rgb.fill(Vec3::splat(0.2));
    let out = FrameOutput {
        left,
        baselines,
        images: vec![film; 3],
        exposure_scale: 1.0,
        aov: Some(crate::render::AovImages::new(n)),
        stats: RenderStats::default(),
    };
    (rig, out)
}

fn camera_record(rig: &StereoRig) -> CameraFile {
    CameraFile {
        cameras: RigCameras::of(rig),
        exposure_scale: 1.0,
        exposure_ev: 0.0,
        sun_direction_world: None,
        weather: None,
        seed: 1,
        frame: 0,
        spp: 1,
        max_depth: 1,
        image_filter: false,
        denoiser: None,
        semantic_classes: Vec::new(),
        conventions: crate::output::frame::CONVENTIONS,
        seeds: FrameSeeds::default(),
        town: None,
    }
}

#[test]
fn every_declared_map_is_written_recognised_owned_and_verified() {
    let config = parse_config(CONFIG, "c.toml").unwrap();
    let job = plan(&config).remove(0);
    let dir = tempfile::tempdir().unwrap();
    let root = dir.path();
    let seq = root.join(job.sequence_dir());
    let (rig, out) = frame();
    let hdr = WriteOptions { hdr: true };
    let written = write_native_frame(&seq, 0, &rig, &out, camera_record(&rig), hdr).unwrap();
    let owner = Ownership::new(&config, []);
    let layout = NativeLayout::new(&seq);
    let mut declared: Vec<PathBuf> = Vec::new();
    for spec in MAPS {
        let baselines: Vec<Option<f64>> = if spec.per_baseline {
            config.baselines_cm.iter().map(|&cm| Some(cm)).collect()
        } else {
            vec![None]
        };
        for cm in baselines {
            let p = layout.path(spec.map, 0, cm);
            assert!(
                written.contains(&p),
                "{}: {} not written",
                spec.name,
                p.display()
            );
            let rel = p.strip_prefix(&seq).unwrap();
            let file = Some(NativePath::File { frame: 0 });
            assert_eq!(native_path(rel), file, "{}", spec.name);
            let rel = slash(p.strip_prefix(root).unwrap());
            assert!(owner.owns(&rel), "{}: {rel} not the dataset's", spec.name);
            declared.push(p);
        }
    }
    // The camera file is the only file that is not a map.
    assert_eq!(written.len(), declared.len() + 1);

    write_json(&root.join(DATASET_JSON), &DatasetMeta::new(&config, vec![])).unwrap();
    let records: Vec<FileRecord> = written
        .iter()
        .map(|p| FileRecord::of(root, p).unwrap())
        .collect();
    let manifest = root.join(MANIFEST_DIR).join("shard-1-of-1.jsonl");
    let write_line = |files: Vec<FileRecord>| {
        let _ = std::fs::remove_file(&manifest);
        let line = super::manifest::ManifestLine {
            files,
            ..line_of(&job, records[0].clone())
        };
        append_line(&manifest, &line).unwrap();
    };
    write_line(records.clone());
    let report = verify_dataset(root).unwrap();
    assert!(report.is_whole(), "{}", report.text());
    assert_eq!(report.files_checked, written.len());
    // Each map's file, once its record is gone, is an extra file of the dataset.
    for p in &declared {
        let rel = slash(p.strip_prefix(root).unwrap());
        write_line(records.iter().filter(|r| r.path != rel).cloned().collect());
        let report = verify_dataset(root).unwrap();
        assert_eq!(report.extra, vec![rel.clone()], "{}", report.text());
    }
}
