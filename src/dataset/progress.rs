//! Progress reporting: an indicatif bar on a terminal (frames, views, ETA,
//! Mrays/s), plain log lines otherwise (batch engines capture stderr), and
//! the final summary.

use std::io::IsTerminal;
use std::time::Instant;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use super::plan::Job;

/// Frame and ray counters of a run.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RunSummary {
    /// Frames rendered and written.
    pub done: u64,
    /// Frames found complete and skipped.
    pub skipped: u64,
    /// Frames that failed twice, with the error.
    pub failed: Vec<(String, String)>,
    /// Rays traced.
    pub rays: u64,
    /// Seconds spent on rendered frames (build, render, write).
    pub frame_seconds: f64,
    /// Seconds spent tracing rays.
    pub trace_seconds: f64,
}

impl RunSummary {
    /// One-line summary: done/skipped/failed, seconds per frame, Mrays/s.
    pub fn line(&self, wall_s: f64) -> String {
        let per_frame = if self.done > 0 {
            self.frame_seconds / self.done as f64
        } else {
            0.0
        };
        format!(
            "{} frames done, {} skipped, {} failed in {:.1} s; {:.2} s per frame, {:.2} Mrays/s",
            self.done,
            self.skipped,
            self.failed.len(),
            wall_s,
            per_frame,
            self.rays as f64 / self.trace_seconds.max(1e-9) / 1e6
        )
    }
}

/// Where progress goes.
pub struct Progress {
    bar: Option<ProgressBar>,
    views_per_frame: u64,
    total_frames: u64,
    started: Instant,
}

impl Progress {
    /// A reporter for `total_frames` frames of `views_per_frame` views each;
    /// a bar when stderr is a terminal, log lines otherwise.
    pub fn new(total_frames: u64, views_per_frame: u64) -> Progress {
        let bar = std::io::stderr().is_terminal().then(|| {
            let pb = ProgressBar::with_draw_target(
                Some(total_frames * views_per_frame),
                ProgressDrawTarget::stderr(),
            );
            pb.set_style(
                ProgressStyle::with_template(
                    "{spinner} [{bar:30}] {pos}/{len} views {msg} {elapsed} (eta {eta})",
                )
                .unwrap_or_else(|_| ProgressStyle::default_bar()),
            );
            pb
        });
        Progress {
            bar,
            views_per_frame,
            total_frames,
            started: Instant::now(),
        }
    }

    /// Views finished within the current frame (frame `k` of the run, 0-based).
    pub fn views(&self, k: u64, views_done: usize) {
        if let Some(pb) = &self.bar {
            pb.set_position(k * self.views_per_frame + views_done as u64);
        }
    }

    /// A frame finished (rendered, skipped or failed) as the `k`-th (1-based).
    pub fn frame(&self, k: u64, job: &Job, what: &str, s: &RunSummary) {
        let mrays = s.rays as f64 / s.trace_seconds.max(1e-9) / 1e6;
        match &self.bar {
            Some(pb) => {
                pb.set_position(k * self.views_per_frame);
                pb.set_message(format!(
                    "frames {k}/{} {mrays:.1} Mrays/s",
                    self.total_frames
                ));
            }
            None => eprintln!(
                "[{:>8.1} s] frame {k}/{} {} {what} ({mrays:.2} Mrays/s)",
                self.started.elapsed().as_secs_f64(),
                self.total_frames,
                job.id()
            ),
        }
    }

    /// Prints a message above the bar (or as a log line).
    pub fn note(&self, msg: &str) {
        match &self.bar {
            Some(pb) => pb.println(msg),
            None => eprintln!("{msg}"),
        }
    }

    /// Removes the bar.
    pub fn finish(&self) {
        if let Some(pb) = &self.bar {
            pb.finish_and_clear();
        }
    }
}
