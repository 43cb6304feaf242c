//! [`RecentTimes`]: the last frames' times, whose medians the panel shows.

use std::collections::VecDeque;
use std::time::Instant;

use super::panel::TimingSummary;
use crate::common::Tails;

/// Frames the panel's medians cover.
const WINDOW: usize = 60;

/// A bounded window of recent samples.
#[derive(Debug, Default)]
struct Recent(VecDeque<f64>);

impl Recent {
    fn push(&mut self, value: f64) {
        if self.0.len() == WINDOW {
            self.0.pop_front();
        }
        self.0.push_back(value);
    }

    fn median(&self) -> Option<f64> {
        let values: Vec<f64> = self.0.iter().copied().collect();
        (!values.is_empty()).then(|| Tails::of(&values).median)
    }
}

/// Frame, CPU and pass times of the last frames.
#[derive(Debug, Default)]
pub(crate) struct RecentTimes {
    last_start: Option<Instant>,
    frame_ms: Recent,
    cpu_ms: Recent,
    pass_ms: Recent,
}

impl RecentTimes {
    /// Marks a frame's start.
    pub(crate) fn frame_started(&mut self, now: Instant) {
        if let Some(last) = self.last_start.replace(now) {
            self.frame_ms
                .push(now.duration_since(last).as_secs_f64() * 1e3);
        }
    }

    /// Records the CPU time the frame took from its start, less the `waited_ms` it spent
    /// waiting for the GPU.
    pub(crate) fn frame_done(&mut self, started: Instant, waited_ms: f64) {
        let ms = started.elapsed().as_secs_f64() * 1e3 - waited_ms;
        self.cpu_ms.push(ms.max(0.0));
    }

    /// Records a pass time.
    pub(crate) fn pass(&mut self, ms: f64) {
        self.pass_ms.push(ms);
    }

    /// The medians.
    pub(crate) fn summary(&self) -> TimingSummary {
        TimingSummary {
            frame_ms: self.frame_ms.median().unwrap_or(0.0),
            cpu_ms: self.cpu_ms.median().unwrap_or(0.0),
            pass_ms: self.pass_ms.median(),
        }
    }
}
