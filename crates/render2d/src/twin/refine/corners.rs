//! Solid blocks shallower than the interior depth, shaded as the GPU shades them
//! (`shaders/refine_corners.wgsl`, `shaders/refine_draw.wgsl`): exact samples on the
//! corner grid of `BLOCK x BLOCK` squares aligned with the image, each sampled at most once
//! per unit of work, interpolated bilinearly over each square; creased squares and pixels
//! whose material lookup disagrees go to exact evaluation instead.

use std::ops::Range;

use glam::Vec2;

use super::evaluate::{BATCH, EMPTY, ExactQueue};
use super::proof::{BLOCK, Class, Material, Prover};
use super::sink::Sink;
use super::stats::Tally;
use crate::camera::Camera;
use crate::twin::TwinError;
use crate::twin::blocks::Layout;
use crate::twin::shade::mix;
use craterfield_field::{Sample, Sdf};

/// A solid block shaded from the exact samples on the corner grid.
struct Deferred {
    xs: Range<usize>,
    /// Rows relative to the unit's first.
    rows: Range<usize>,
    /// The first image row.
    y0: usize,
    hi: f32,
    material: Material,
}

/// The corner grid of one unit of work: the pixel centres `(BLOCK i, BLOCK j)`, the
/// corners of the `BLOCK x BLOCK` squares aligned with the image (the GPU's blocks,
/// `shaders/refine_corners.wgsl`), each sampled at most once per unit.
#[derive(Default)]
struct CornerGrid {
    /// The first grid row (`j`) of the unit.
    j0: usize,
    /// Grid points per row (`i = 0..cols`).
    cols: usize,
    /// Index in [`Corners::points`] per grid point, `u32::MAX` when not sampled.
    slots: Vec<u32>,
}

impl CornerGrid {
    /// An empty grid for image rows `rows` of an image `width` pixels wide.
    fn reset(&mut self, rows: Range<usize>, width: usize) {
        self.j0 = rows.start / BLOCK;
        let j1 = rows.end.saturating_sub(1) / BLOCK + 1;
        self.cols = width.saturating_sub(1) / BLOCK + 2;
        self.slots.clear();
        self.slots.resize((j1 - self.j0 + 1) * self.cols, u32::MAX);
    }

    fn slot(&self, i: usize, j: usize) -> usize {
        (j - self.j0) * self.cols + i
    }
}

/// A thread's shaded solid blocks of one unit of work and their corner samples.
#[derive(Default)]
pub(super) struct Corners {
    /// Solid blocks shaded from exact corner samples.
    deferred: Vec<Deferred>,
    /// The grid points those blocks are drawn from, in the order first needed.
    points: Vec<Vec2>,
    samples: Vec<Sample>,
    /// Which of `points` each grid point is.
    grid: CornerGrid,
}

impl Corners {
    /// Empties the queue for a unit of image rows `rows`, `width` pixels wide.
    pub(super) fn reset(&mut self, rows: Range<usize>, width: usize) {
        self.deferred.clear();
        self.points.clear();
        self.grid.reset(rows, width);
    }

    /// Queues the shaded solid blocks of a quad, whose pixel rows are `ys` and whose
    /// blocks are `classes` (row-major over `col_blocks`), and the corner points they are
    /// drawn from; `base` is the unit's first image row.
    pub(super) fn defer(
        &mut self,
        camera: &Camera,
        classes: &[Class],
        col_blocks: &[Range<usize>],
        ys: &Range<usize>,
        base: usize,
    ) {
        for (i, class) in classes.iter().enumerate() {
            let &Class::Solid {
                hi,
                material,
                shaded: true,
            } = class
            else {
                continue;
            };
            let xs = col_blocks[i % col_blocks.len()].clone();
            let start = ys.start + (i / col_blocks.len()) * BLOCK;
            let rows_abs = start..(start + BLOCK).min(ys.end);
            // The corners of every grid square the block's pixels fall in.
            for j in rows_abs.start / BLOCK..=(rows_abs.end - 1) / BLOCK + 1 {
                for i in xs.start / BLOCK..=(xs.end - 1) / BLOCK + 1 {
                    let slot = self.grid.slot(i, j);
                    if self.grid.slots[slot] == u32::MAX {
                        self.grid.slots[slot] = self.points.len() as u32;
                        // The pixel centre (BLOCK i, BLOCK j), also past the image's edge.
                        let (x, y) = ((i * BLOCK) as u32, (j * BLOCK) as u32);
                        self.points.push(camera.pixel_to_world(x, y));
                    }
                }
            }
            self.deferred.push(Deferred {
                xs,
                rows: rows_abs.start - base..rows_abs.end - base,
                y0: rows_abs.start,
                hi,
                material,
            });
        }
    }

    /// Samples the deferred blocks' grid corners and draws each pixel by bilinear
    /// interpolation of the exact distances and gradients at the corners of its grid square
    /// (the distance clamped to the proof's bound), as the GPU draws its shaded blocks
    /// (`shaders/refine_draw.wgsl`). Pixels of creased squares ([`Prover::creased`]) and
    /// pixels whose material lookup disagrees are queued for exact evaluation; a block
    /// with creased pixels moves from solid to refined in `tally`. Returns the number of
    /// corner points sampled.
    pub(super) fn draw<F: Sdf, S: Sink>(
        &mut self,
        prover: &Prover<'_, F>,
        layout: &Layout,
        sink: &mut S,
        exact: &mut ExactQueue,
        tally: &mut Tally,
    ) -> Result<u64, TwinError> {
        self.samples.clear();
        self.samples.resize(self.points.len(), EMPTY);
        for (points, out) in self
            .points
            .chunks(BATCH)
            .zip(self.samples.chunks_mut(BATCH))
        {
            prover.cells.terrain.samples(points, out)?;
        }
        let sampled = self.points.len() as u64;
        let (grid, samples) = (&self.grid, &self.samples);
        let sample = |i: usize, j: usize| samples[grid.slots[grid.slot(i, j)] as usize];
        for b in &self.deferred {
            let mut creased = 0;
            for (yi, y) in b.rows.clone().zip(b.y0..) {
                let (j, ty) = (y / BLOCK, (y % BLOCK) as f32 / BLOCK as f32);
                // The grid square of the previous pixel, its corner samples and verdict.
                let mut square: Option<(usize, [Sample; 4], bool)> = None;
                for x in b.xs.clone() {
                    let (i, tx) = (x / BLOCK, (x % BLOCK) as f32 / BLOCK as f32);
                    let (s, evaluate) = match square {
                        Some((at, s, evaluate)) if at == i => (s, evaluate),
                        _ => {
                            let s = [
                                sample(i, j),
                                sample(i + 1, j),
                                sample(i, j + 1),
                                sample(i + 1, j + 1),
                            ];
                            let evaluate = prover.creased(&s);
                            square = Some((i, s, evaluate));
                            (s, evaluate)
                        }
                    };
                    let p = Vec2::new(layout.columns.world[x], layout.rows.world[y]);
                    if evaluate {
                        creased += 1;
                        exact.push(p, x, yi);
                        continue;
                    }
                    let v = |s: &Sample| [s.distance, s.gradient.x, s.gradient.y];
                    let (v00, v10, v01, v11) = (v(&s[0]), v(&s[1]), v(&s[2]), v(&s[3]));
                    let [d, gx, gy] = std::array::from_fn(|c| {
                        mix(mix(v00[c], v10[c], tx), mix(v01[c], v11[c], tx), ty)
                    });
                    let g = Vec2::new(gx, gy);
                    match prover.pixel_material(b.material, p) {
                        Some(m) => sink.proven(x, yi, d.min(b.hi), g.normalize_or_zero(), m),
                        None => exact.push(p, x, yi),
                    }
                }
            }
            if creased > 0 {
                // Evaluated (in part) after all: counted as refined.
                tally.solid -= 1;
                tally.refined += 1;
                tally.refined_pixels += creased;
            }
        }
        self.deferred.clear();
        self.points.clear();
        Ok(sampled)
    }
}
