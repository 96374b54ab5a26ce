//! The readable table of an evaluation: one block per group, four rows each
//! (all/noc × pooled/per-image mean).

use std::fmt::Write;

use super::{EvalReport, GroupReport, Metrics};

fn row(out: &mut String, group: &str, images: u64, set: &str, mean: &str, m: &Metrics) {
    let _ = writeln!(
        out,
        "{group:<22} {images:>7} {set:<4} {mean:<9} {:>9.4} {:>8.3} {:>8.3} {:>8.3} {:>8.3} {:>8.3}",
        m.epe, m.d1, m.bad1, m.bad2, m.bad3, m.density
    );
}

fn block(out: &mut String, name: &str, g: &GroupReport) {
    row(out, name, g.images, "all", "pooled", &g.all.pooled);
    row(out, "", g.images, "all", "per-image", &g.all.per_image_mean);
    row(out, "", g.images, "noc", "pooled", &g.noc.pooled);
    row(out, "", g.images, "noc", "per-image", &g.noc.per_image_mean);
}

/// Formats the report as a fixed-width table (EPE in px, the rest in %),
/// ending with the layout and the rule for missing predictions.
pub fn format_table(r: &EvalReport) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "{:<22} {:>7} {:<4} {:<9} {:>9} {:>8} {:>8} {:>8} {:>8} {:>8}",
        "group", "images", "set", "mean", "EPE px", "D1 %", "bad1 %", "bad2 %", "bad3 %", "dens %"
    );
    block(&mut out, "overall", &r.overall);
    let sections = [
        ("baseline", &r.per_baseline),
        ("config", &r.per_config),
        ("weather", &r.per_weather),
        ("town", &r.per_town),
    ];
    for (label, map) in sections {
        for (k, g) in map {
            block(&mut out, &format!("{label} {k}"), g);
        }
    }
    let _ = writeln!(
        out,
        "{} of {} ground-truth images evaluated; {} without prediction",
        r.images_evaluated,
        r.gt_images,
        r.missing_predictions.len()
    );
    for m in r.missing_predictions.iter().take(20) {
        let _ = writeln!(
            out,
            "  missing prediction: {}/{m}.{{pfm,png,exr,npy}}",
            r.pred
        );
    }
    if r.missing_predictions.len() > 20 {
        let _ = writeln!(out, "  … and {} more", r.missing_predictions.len() - 20);
    }
    let _ = writeln!(
        out,
        "pooled: pixel-weighted; per-image: mean over images with valid pixels"
    );
    let _ = writeln!(out, "predictions laid out as: {}", r.layout);
    let _ = writeln!(out, "fill {}: {}", r.fill, r.missing_rule);
    out
}
