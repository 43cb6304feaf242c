//! The exact evaluation of the pixels no proof covers: queued over one unit of work, then
//! sampled with the terrain's batch evaluator, at most [`BATCH`] points a call, and handed
//! to the sink as the exact render shades them.

use glam::Vec2;

use super::sink::Sink;
use crate::twin::TwinError;
use craterfield_field::{Sample, Sdf, Terrain};

/// Most pixels evaluated per batch call.
pub(super) const BATCH: usize = 4096;

/// A sample to fill buffers with before the evaluator overwrites it.
pub(super) const EMPTY: Sample = Sample {
    distance: 0.0,
    gradient: Vec2::ZERO,
    material: 0,
};

/// The pixels of one unit of work queued for exact evaluation, in queue order.
#[derive(Default)]
pub(super) struct ExactQueue {
    points: Vec<Vec2>,
    /// Column and sink row of each point.
    pixels: Vec<(usize, usize)>,
    samples: Vec<Sample>,
}

impl ExactQueue {
    /// Empties the queue for the next unit.
    pub(super) fn clear(&mut self) {
        self.points.clear();
        self.pixels.clear();
    }

    /// Queues pixel `x` of sink row `yi`, whose centre is `p`.
    pub(super) fn push(&mut self, p: Vec2, x: usize, yi: usize) {
        self.points.push(p);
        self.pixels.push((x, yi));
    }

    /// Samples the queued pixels exactly and hands them to the sink.
    pub(super) fn evaluate<F: Sdf, S: Sink>(
        &mut self,
        terrain: &Terrain<F>,
        sink: &mut S,
    ) -> Result<(), TwinError> {
        for (points, pixels) in self.points.chunks(BATCH).zip(self.pixels.chunks(BATCH)) {
            self.samples.clear();
            self.samples.resize(points.len(), EMPTY);
            terrain.samples(points, &mut self.samples)?;
            for (&(x, yi), s) in pixels.iter().zip(&self.samples) {
                sink.exact(x, yi, s);
            }
        }
        Ok(())
    }
}
