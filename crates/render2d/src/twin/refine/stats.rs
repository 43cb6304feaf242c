//! What the `refine` mode did for one frame: the public [`RefineStats`], and the class
//! counts each unit of work tallies and the frame sums over threads.

use std::sync::atomic::{AtomicU64, Ordering};

use serde::Serialize;

/// What the `refine` mode did for one frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct RefineStats {
    /// Pixel blocks classified.
    pub blocks: u64,
    /// Blocks proven all sky.
    pub sky_blocks: u64,
    /// Blocks proven solid, with their materials.
    pub solid_blocks: u64,
    /// Blocks evaluated at every pixel.
    pub refined_blocks: u64,
    /// Pixels of the image.
    pub pixels: u64,
    /// Pixels evaluated exactly.
    pub refined_pixels: u64,
    /// Field evaluations of the frame: pass 1's texels, the material margins computed for
    /// them, the corners of solid blocks shaded from exact samples, and the refined pixels.
    pub exact_evaluations: u64,
}

impl RefineStats {
    /// Refined blocks over all blocks (0 for an empty frame).
    pub fn refined_block_fraction(&self) -> f64 {
        ratio(self.refined_blocks, self.blocks)
    }

    /// Refined pixels over all pixels (0 for an empty frame).
    pub fn refined_pixel_fraction(&self) -> f64 {
        ratio(self.refined_pixels, self.pixels)
    }
}

fn ratio(a: u64, b: u64) -> f64 {
    if b == 0 { 0.0 } else { a as f64 / b as f64 }
}

/// Class counts of one unit of work, added to [`Counters`] when the unit is done.
#[derive(Clone, Copy, Default)]
pub(super) struct Tally {
    pub(super) blocks: u64,
    pub(super) sky: u64,
    pub(super) solid: u64,
    pub(super) refined: u64,
    pub(super) refined_pixels: u64,
}

/// Class counts, summed over threads.
#[derive(Default)]
pub(super) struct Counters {
    blocks: AtomicU64,
    sky: AtomicU64,
    solid: AtomicU64,
    refined: AtomicU64,
    refined_pixels: AtomicU64,
    corners: AtomicU64,
}

impl Counters {
    /// Adds a unit's tally to the frame's counters (once per unit: per-block atomics
    /// would bounce one cache line between the threads).
    pub(super) fn flush(&self, tally: &mut Tally) {
        let t = std::mem::take(tally);
        for (counter, n) in [
            (&self.blocks, t.blocks),
            (&self.sky, t.sky),
            (&self.solid, t.solid),
            (&self.refined, t.refined),
            (&self.refined_pixels, t.refined_pixels),
        ] {
            counter.fetch_add(n, Ordering::Relaxed);
        }
    }

    /// Counts `n` corner-grid points sampled exactly.
    pub(super) fn add_corners(&self, n: u64) {
        self.corners.fetch_add(n, Ordering::Relaxed);
    }

    /// The frame's statistics: `texels` evaluated by pass 1, `margins` material margins
    /// computed, `pixels` in the image.
    pub(super) fn stats(&self, texels: u64, margins: u64, pixels: u64) -> RefineStats {
        let get = |a: &AtomicU64| a.load(Ordering::Relaxed);
        let refined_pixels = get(&self.refined_pixels);
        RefineStats {
            blocks: get(&self.blocks),
            sky_blocks: get(&self.sky),
            solid_blocks: get(&self.solid),
            refined_blocks: get(&self.refined),
            pixels,
            refined_pixels,
            exact_evaluations: texels + margins + refined_pixels + get(&self.corners),
        }
    }
}
