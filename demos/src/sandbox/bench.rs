//! `--bench`: per-frame timings of a sandbox run (frame interval, CPU tick, the renderer's
//! CPU work and its three GPU passes), printed as median, p95, p99 and max at the end.

use std::fmt::Write;

use super::terrain_view::FrameCost;
use crate::common::Tails;

/// Timings gathered over a run.
#[derive(Debug, Default)]
pub(super) struct Bench {
    /// Interval between frames, milliseconds.
    pub(super) frame_ms: Vec<f64>,
    /// CPU time of each simulation tick, milliseconds.
    pub(super) tick_ms: Vec<f64>,
    /// The renderer's CPU time (prepare and recording), milliseconds.
    pub(super) render_cpu_ms: Vec<f64>,
    /// GPU time of passes 1, 2, 3, milliseconds.
    pub(super) pass_ms: [Vec<f64>; 3],
    /// Terrain image size, pixels.
    pub(super) size: [u32; 2],
}

impl Bench {
    /// Records one terrain draw.
    pub(super) fn record_draw(&mut self, cost: FrameCost, size: [u32; 2]) {
        self.render_cpu_ms.push(cost.cpu_ms);
        if let Some(ms) = cost.gpu_ms {
            for (v, x) in self.pass_ms.iter_mut().zip(ms) {
                v.push(x);
            }
        }
        self.size = size;
    }

    /// The report: one row per series. The first frame, which compiles the pipelines,
    /// is reported alone and left out of the tails.
    pub(super) fn report(&self, adapter: &str, timestamps: bool) -> String {
        let mut out = String::new();
        let [w, h] = self.size;
        let frames = self.render_cpu_ms.len();
        let first = self.frame_ms.first().copied().unwrap_or(0.0);
        let _ = writeln!(
            out,
            "sandbox --bench: {frames} frames, terrain view {w}x{h} pixels, adapter {adapter}"
        );
        let _ = writeln!(
            out,
            "first frame (compiles the pipelines): {first:.1} ms; the rows below leave it out"
        );
        let _ = writeln!(
            out,
            "{:<38} {:>8} {:>8} {:>8} {:>8} {:>7}",
            "ms", "median", "p95", "p99", "max", "count"
        );
        let mut rows: Vec<(&str, Tails)> = vec![
            ("frame interval", after_first(&self.frame_ms)),
            ("simulation tick (CPU)", Tails::of(&self.tick_ms)),
            (
                "terrain prepare + record (CPU)",
                after_first(&self.render_cpu_ms),
            ),
        ];
        if timestamps {
            rows.push((
                "pass 1: field at reduced scale (GPU)",
                after_first(&self.pass_ms[0]),
            ));
            rows.push((
                "pass 2: reconstruct / refine (GPU)",
                after_first(&self.pass_ms[1]),
            ));
            rows.push((
                "pass 3: upsample / draw (GPU)",
                after_first(&self.pass_ms[2]),
            ));
        }
        for (name, t) in rows {
            let _ = writeln!(out, "{name:<38} {} {:>7}", t.row(), t.count);
        }
        if !timestamps {
            let _ = writeln!(out, "GPU pass times: the adapter has no timestamp queries");
        }
        out
    }
}

/// The tails of `v` without its first value.
fn after_first(v: &[f64]) -> Tails {
    Tails::of(v.get(1..).unwrap_or_default())
}
