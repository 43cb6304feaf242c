//! `--bench`: frame times and the marcher's pass times over the run, printed as a table of
//! median, p95, p99 and max at the last frame.

use std::time::Instant;

use crate::common::Tails;

/// Frames left out at the start: the first ones compile the plan's pipeline and warm up
/// the driver.
const WARMUP_FRAMES: usize = 3;

/// The samples of a benchmark run.
#[derive(Debug, Default)]
pub(crate) struct BenchLog {
    last_start: Option<Instant>,
    frame_ms: Vec<f64>,
    pass_ms: Vec<f64>,
}

/// What the report names besides the timings.
pub(crate) struct BenchSetup<'a> {
    /// The scene.
    pub(crate) scene: &'a str,
    /// The adapter's name and backend.
    pub(crate) adapter: String,
    /// The marched image in pixels.
    pub(crate) size: [u32; 2],
    /// Pipeline cache hits and misses.
    pub(crate) cache: (u64, u64),
    /// Whether pass times are GPU timestamps (otherwise wall clock, submit to done).
    pub(crate) gpu_timed: bool,
}

impl BenchLog {
    /// Marks the start of a frame (the interval since the last start is a frame time).
    pub(crate) fn frame_started(&mut self, now: Instant) {
        if let Some(last) = self.last_start.replace(now) {
            self.frame_ms
                .push(now.duration_since(last).as_secs_f64() * 1e3);
        }
    }

    /// Adds the frame's pass time.
    pub(crate) fn pass(&mut self, ms: f64) {
        self.pass_ms.push(ms);
    }

    /// The table printed at the end of the run.
    pub(crate) fn report(&self, setup: &BenchSetup<'_>) -> String {
        let frames = Tails::of(skip_warmup(&self.frame_ms));
        let passes = Tails::of(skip_warmup(&self.pass_ms));
        let [w, h] = setup.size;
        format!(
            "viewer3d bench: scene {}, {w}x{h} px, adapter {}\n\
             {} frames timed (the first {WARMUP_FRAMES} left out); pipeline cache {} hits, \
             {} misses\n\
             {:<15} {:>8} {:>8} {:>8} {:>8}\n\
             frame ms        {}\n\
             march pass ms   {}   ({})",
            setup.scene,
            setup.adapter,
            frames.count,
            setup.cache.0,
            setup.cache.1,
            "",
            "median",
            "p95",
            "p99",
            "max",
            frames.row(),
            passes.row(),
            pass_clock(setup.gpu_timed),
        )
    }
}

fn skip_warmup(samples: &[f64]) -> &[f64] {
    samples.get(WARMUP_FRAMES..).unwrap_or_default()
}

/// How pass times were measured, for labels.
pub(crate) fn pass_clock(gpu_timed: bool) -> &'static str {
    if gpu_timed {
        "GPU timestamps"
    } else {
        "wall clock, submit to done"
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_report_has_a_row_per_measurement() {
        let mut log = BenchLog::default();
        let start = Instant::now();
        for i in 0..10 {
            log.frame_started(start + std::time::Duration::from_millis(i * 10));
        }
        (0..10).for_each(|ms| log.pass(f64::from(ms)));
        let text = log.report(&BenchSetup {
            scene: "forest",
            adapter: "test adapter".into(),
            size: [320, 180],
            cache: (9, 1),
            gpu_timed: true,
        });
        assert!(text.contains("320x180"), "{text}");
        assert!(text.contains("frame ms           10.00"), "{text}");
        assert!(text.contains("march pass ms"), "{text}");
        assert!(text.contains("GPU timestamps"), "{text}");
        assert!(text.contains("median"), "{text}");
    }
}
