//! One unit of work of the refine pass: each quad of its rows is cut into blocks, each
//! block classified by the [`Prover`], the proven pixels drawn, the shaded solid blocks
//! handed to [`Corners`] and the rest queued for exact evaluation, the whole unit's
//! evaluations going to the batch evaluator together.

use std::ops::Range;

use glam::Vec2;

use super::cells::Quad;
use super::corners::Corners;
use super::evaluate::ExactQueue;
use super::proof::{BLOCK, Class, Material, Prover};
use super::sink::Sink;
use super::stats::{Counters, RefineStats, Tally};
use crate::camera::Camera;
use crate::options::ShadeOptions;
use crate::twin::blocks::{Block, Kernel, Layout, Run, Scratch, pixel_weights};
use crate::twin::upsample::{Textures, normal};
use crate::twin::{LowRes, TwinError};
use craterfield_field::terrain::RectSign;
use craterfield_field::{Sdf, Terrain};

/// A thread's buffers.
#[derive(Default)]
pub(super) struct RefineScratch {
    blocks: Scratch,
    classes: Vec<Class>,
    /// The pixel columns of each block of the current quad.
    col_blocks: Vec<Range<usize>>,
    tally: Tally,
    /// The first image row of the unit being drawn: sink rows count from it.
    base: usize,
    /// Pixels queued for exact evaluation.
    exact: ExactQueue,
    /// Solid blocks shaded from exact corner samples.
    corners: Corners,
}

/// One frame's refine pass.
pub(super) struct Refiner<'a, F: Sdf> {
    pub(super) prover: Prover<'a, F>,
    tex: &'a Textures<'a>,
    layout: &'a Layout,
    /// The frame's camera (the corner grid's points lie also past the image's edge).
    camera: Camera,
    counters: Counters,
}

impl<'a, F: Sdf + Sync> Refiner<'a, F> {
    /// The refine pass of one frame (`exact_only`: prove nothing, evaluate every block).
    pub(super) fn new(
        terrain: &'a Terrain<F>,
        lowres: &'a LowRes,
        tex: &'a Textures<'a>,
        layout: &'a Layout,
        camera: &Camera,
        shade: &ShadeOptions,
        exact_only: bool,
    ) -> Self {
        Refiner {
            prover: Prover::new(terrain, lowres, camera.units_per_pixel, shade, exact_only),
            tex,
            layout,
            camera: *camera,
            counters: Counters::default(),
        }
    }

    /// Classifies and draws the consecutive quad rows `bands` (one unit of work). The exact
    /// evaluations of the whole unit go to the batch evaluator together: a quad row alone
    /// holds a few uncertain pixels per grid cell, too few to fill the SIMD lanes of one
    /// cell's pass.
    pub(super) fn band<S: Sink>(
        &self,
        scratch: &mut RefineScratch,
        bands: &[Run],
        sink: &mut S,
    ) -> Result<(), TwinError> {
        scratch.exact.clear();
        scratch.base = bands.first().map_or(0, |b| b.pixels.start);
        let end = bands.last().map_or(0, |b| b.pixels.end);
        let width = self.layout.columns.world.len();
        scratch
            .corners
            .reset(scratch.base..end.max(scratch.base), width);
        for rows in bands {
            for columns in &self.layout.columns.runs {
                let block = Block::at(columns, rows);
                self.quad(scratch, block, sink);
            }
        }
        let corners = scratch.corners.draw(
            &self.prover,
            self.layout,
            sink,
            &mut scratch.exact,
            &mut scratch.tally,
        )?;
        self.counters.add_corners(corners);
        self.counters.flush(&mut scratch.tally);
        scratch.exact.evaluate(self.prover.cells.terrain, sink)
    }

    /// Classifies the blocks of one quad, draws the proven ones and queues the others.
    fn quad<S: Sink>(&self, scratch: &mut RefineScratch, block: Block, sink: &mut S) {
        let layout = self.layout;
        let quad = Quad::new(self.tex, block.c, block.r);
        let bounds = self.prover.cells.quad_bounds(&quad);
        let (xs, ys) = (block.xs.clone(), block.ys.clone());
        let mut col_blocks = std::mem::take(&mut scratch.col_blocks);
        col_blocks.clear();
        col_blocks.extend(chunks(xs.clone()));
        scratch.classes.clear();
        // A quad of one block proves its signs over the block alone: the quad-wide sign
        // would walk the same events over nearly the same rectangle first.
        let single = col_blocks.len() == 1 && ys.len() <= BLOCK;
        let mut quad_sign = single.then_some(RectSign::Unknown);
        for by in chunks(ys.clone()) {
            let (ya, yb) = (layout.rows.world[by.start], layout.rows.world[by.end - 1]);
            for bx in &col_blocks {
                let (x0, x1) = (
                    layout.columns.world[bx.start],
                    layout.columns.world[bx.end - 1],
                );
                let rect = [x0, ya.min(yb), x1, ya.max(yb)];
                scratch
                    .classes
                    .push(self.prover.classify(&quad, bounds, rect, &mut quad_sign));
            }
        }
        count(&mut scratch.tally, &scratch.classes, &col_blocks, ys.len());
        let interpolated = |c: &Class| match c {
            Class::Sky { .. } => S::VALUES,
            Class::Solid { shaded, .. } => !shaded && S::VALUES,
            Class::Uncertain => false,
        };
        let kernel = Kernel::new(self.tex, block);
        if scratch.classes.iter().any(interpolated) {
            kernel.prepare(self.tex, layout, &mut scratch.blocks);
        }
        let per_row = col_blocks.len();
        let classes = std::mem::take(&mut scratch.classes);
        for (local, y) in ys.clone().enumerate() {
            let row = (local / BLOCK) * per_row..(local / BLOCK + 1) * per_row;
            // The sink's row: rows count from the first of the unit.
            let yi = y - scratch.base;
            if classes[row.clone()].iter().any(interpolated) {
                kernel.row(layout, y, &mut scratch.blocks);
            }
            for (bx, &class) in col_blocks.iter().zip(&classes[row]) {
                // Sky of an image is already filled, and shaded solid blocks are drawn
                // later from their corners: no pixel of theirs to visit here.
                let visit = match class {
                    Class::Sky { .. } => S::VALUES,
                    Class::Solid { shaded, .. } => !shaded,
                    Class::Uncertain => true,
                };
                if !visit {
                    continue;
                }
                if let Class::Solid {
                    material: Material::One(m),
                    ..
                } = class
                    && !S::VALUES
                {
                    sink.deep(bx.clone(), yi, m);
                    continue;
                }
                for x in bx.clone() {
                    let i = x - xs.start;
                    let p = Vec2::new(layout.columns.world[x], layout.rows.world[y]);
                    match class {
                        Class::Sky { lo } if S::VALUES => {
                            let d = scratch.blocks.dist[i].max(lo);
                            let n = normal(&kernel.quad, pixel_weights(layout, x, y));
                            sink.proven(x, yi, d, n, kernel.material(layout, x, y));
                        }
                        Class::Sky { .. } => {}
                        Class::Solid { shaded: true, .. } => {}
                        Class::Solid { material, .. } if !S::VALUES => {
                            match self.prover.pixel_material(material, p) {
                                Some(m) => sink.deep(x..x + 1, yi, m),
                                None => scratch.exact.push(p, x, yi),
                            }
                        }
                        Class::Solid { hi, material, .. } => {
                            match self.prover.pixel_material(material, p) {
                                Some(m) => {
                                    let d = scratch.blocks.dist[i].min(hi);
                                    let n = normal(&kernel.quad, pixel_weights(layout, x, y));
                                    sink.proven(x, yi, d, n, m);
                                }
                                None => scratch.exact.push(p, x, yi),
                            }
                        }
                        Class::Uncertain => scratch.exact.push(p, x, yi),
                    }
                }
            }
        }
        scratch
            .corners
            .defer(&self.camera, &classes, &col_blocks, &ys, scratch.base);
        scratch.classes = classes;
        scratch.col_blocks = col_blocks;
    }

    /// The frame's statistics, with `texels` evaluated by pass 1 and `pixels` in the image.
    pub(super) fn stats(&self, texels: u64, pixels: u64) -> RefineStats {
        let margins = self.prover.cells.margins_computed();
        self.counters.stats(texels, margins, pixels)
    }
}

/// Tallies the classes of one quad's blocks into the thread's counts.
fn count(tally: &mut Tally, classes: &[Class], col_blocks: &[Range<usize>], rows: usize) {
    for (i, class) in classes.iter().enumerate() {
        let (bx, by) = (i % col_blocks.len(), i / col_blocks.len());
        match class {
            Class::Sky { .. } => tally.sky += 1,
            Class::Solid { .. } => tally.solid += 1,
            Class::Uncertain => {
                let block_rows = (rows - by * BLOCK).min(BLOCK);
                tally.refined_pixels += (col_blocks[bx].len() * block_rows) as u64;
                tally.refined += 1;
            }
        }
    }
    tally.blocks += classes.len() as u64;
}

/// `range` cut into runs of at most [`BLOCK`].
fn chunks(range: Range<usize>) -> impl Iterator<Item = Range<usize>> {
    range
        .clone()
        .step_by(BLOCK)
        .map(move |s| s..(s + BLOCK).min(range.end))
}
