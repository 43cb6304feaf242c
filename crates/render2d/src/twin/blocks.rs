//! Pass 3 one lattice quad at a time. Pixel positions are computed once per column and per
//! row ([`Layout`]); a quad's pixels form a block whose per-quad work (texels, blend
//! weights, the column part of each tangent plane or cubic row) is done once, after which
//! each pixel row is a few branch-free loops over the block's columns. The expressions and
//! their order are those of [`super::upsample::pixel`], so every distance has the same bits.
//!
//! [`Kernel::bounds`] bounds the distance over a block and [`Kernel::row_bounds`] over one
//! of its rows: the pass fills blocks and rows proven all sky or all deep interior without
//! evaluating them.

use std::ops::Range;

use glam::Vec2;

use super::Texel;
use super::upsample::{
    AxisPos, Textures, axis_pos, bilinear_weights, cubic_weights, lipschitz_clamp, lowest_plane,
    plane, quad_slope,
};
use crate::camera::Camera;
use crate::options::{Reconstruction, Upsample};

/// Longest run of pixels a block spans per axis (a quad spans `s` or `s + 1` pixels; longer
/// runs, from cameras at the limit of `f32` precision, are cut).
const MAX_RUN: usize = 64;

/// Pixels along one image axis that fall in the same quad.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Run {
    /// The quad's first texel along the axis.
    pub cell: u32,
    /// The pixels.
    pub pixels: Range<usize>,
}

/// Per-pixel positions along one image axis, as the per-pixel path computes them.
pub(super) struct Axis {
    /// World coordinate of each pixel centre.
    pub world: Vec<f32>,
    /// Lattice position of each pixel.
    pub pos: Vec<AxisPos>,
    /// `f` of each pixel.
    pub frac: Vec<f32>,
    /// `1 - f` of each pixel.
    pub comp: Vec<f32>,
    /// The cubic filter's weights of each pixel (empty when the filter is not cubic).
    pub cubic: Vec<[f32; 4]>,
    /// Runs of pixels in one quad, in order.
    pub runs: Vec<Run>,
}

impl Axis {
    fn new(
        world: Vec<f32>,
        to_lattice: impl Fn(f32) -> f32,
        count: u32,
        cubic: Option<Upsample>,
    ) -> Axis {
        let pos: Vec<AxisPos> = world
            .iter()
            .map(|&w| axis_pos(to_lattice(w), count))
            .collect();
        let frac: Vec<f32> = pos.iter().map(|p| p.frac).collect();
        Axis {
            comp: frac.iter().map(|f| 1.0 - f).collect(),
            cubic: cubic.map_or_else(Vec::new, |filter| {
                frac.iter().map(|&f| cubic_weights(filter, f)).collect()
            }),
            runs: runs(&pos),
            world,
            pos,
            frac,
        }
    }
}

/// Splits pixels into runs of one quad each (cells never decrease along an axis).
fn runs(pos: &[AxisPos]) -> Vec<Run> {
    let mut out: Vec<Run> = Vec::new();
    for (i, p) in pos.iter().enumerate() {
        match out.last_mut() {
            Some(run) if run.cell == p.cell && run.pixels.len() < MAX_RUN => run.pixels.end = i + 1,
            _ => out.push(Run {
                cell: p.cell,
                pixels: i..i + 1,
            }),
        }
    }
    out
}

/// The columns and rows of one frame.
pub(super) struct Layout {
    pub columns: Axis,
    pub rows: Axis,
}

impl Layout {
    /// Pixel positions of `camera`'s image on the lattice of `tex`.
    pub(super) fn new(camera: &Camera, tex: &Textures) -> Layout {
        let lattice = tex.lattice;
        let cubic = match (tex.mode, tex.filter) {
            (Reconstruction::Planes, _) | (_, Upsample::Bilinear) => None,
            (_, filter) => Some(filter),
        };
        // Pixel centres and lattice coordinates are separable: x depends only on the
        // column, y only on the row.
        let xs = (0..camera.width)
            .map(|x| camera.pixel_to_world(x, 0).x)
            .collect();
        let ys = (0..camera.height)
            .map(|y| camera.pixel_to_world(0, y).y)
            .collect();
        Layout {
            columns: Axis::new(
                xs,
                |x| lattice.to_lattice(Vec2::new(x, 0.0)).x,
                lattice.cols,
                cubic,
            ),
            rows: Axis::new(
                ys,
                |y| lattice.to_lattice(Vec2::new(0.0, y)).y,
                lattice.rows,
                cubic,
            ),
        }
    }
}

/// The pixels of one quad: columns `xs`, rows `ys`.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Block {
    pub c: u32,
    pub r: u32,
    pub xs: Range<usize>,
    pub ys: Range<usize>,
}

impl Block {
    /// The quad where the column run `columns` meets the row run `rows`.
    pub(super) fn at(columns: &Run, rows: &Run) -> Block {
        Block {
            c: columns.cell,
            r: rows.cell,
            xs: columns.pixels.clone(),
            ys: rows.pixels.clone(),
        }
    }
}

/// Up to three `(plane m, weight)` blends of one combined plane, in ascending `m`.
#[derive(Clone, Copy, Debug, Default)]
struct Ops {
    items: [(usize, f32); 3],
    len: usize,
}

impl Ops {
    /// The non-zero weights of `row` except the diagonal `k`.
    fn of(row: &[f32; 4], k: usize) -> Ops {
        let mut ops = Ops::default();
        for (m, &w) in row.iter().enumerate() {
            if m != k && w > 0.0 {
                ops.items[ops.len] = (m, w);
                ops.len += 1;
            }
        }
        ops
    }

    fn as_slice(&self) -> &[(usize, f32)] {
        &self.items[..self.len]
    }
}

/// What a block's rows are computed from.
enum Interpolant {
    Planes {
        centers: [Vec2; 4],
    },
    Bilinear,
    Cubic {
        neighbourhood: [[f32; 4]; 4],
        filter: Upsample,
    },
}

/// One block, prepared.
pub(super) struct Kernel {
    pub block: Block,
    pub quad: [Texel; 4],
    interpolant: Interpolant,
    /// The field's slope bound, for the planes' Lipschitz clamp.
    slope: f32,
}

/// A thread's block buffers, reused from block to block.
#[derive(Default)]
pub(super) struct Scratch {
    /// Per column: the x part of each plane, or each cubic row sum.
    columns: [Vec<f32>; 4],
    planes: [Vec<f32>; 4],
    combined: Vec<f32>,
    /// The blends of each combined plane: up (diverging), then down (converging).
    grow: [Ops; 4],
    shrink: [Ops; 4],
    /// The distances of the last row computed, world units.
    pub dist: Vec<f32>,
}

impl Kernel {
    /// The block's texels: enough to bound it ([`Kernel::prepare`] before [`Kernel::row`]).
    pub(super) fn new(tex: &Textures, block: Block) -> Kernel {
        let (c, r) = (block.c, block.r);
        let quad = tex.quad(c, r);
        let interpolant = match (tex.mode, tex.filter) {
            (Reconstruction::Planes, _) => Interpolant::Planes {
                centers: tex.quad_centers(c, r),
            },
            (_, Upsample::Bilinear) => Interpolant::Bilinear,
            (_, filter) => Interpolant::Cubic {
                neighbourhood: tex.neighbourhood(c, r),
                filter,
            },
        };
        Kernel {
            block,
            quad,
            interpolant,
            slope: quad_slope(&quad, tex.slope),
        }
    }

    /// Fills the per-quad and per-column parts into `scratch`: the blend weights and
    /// `g_k.x (p.x - C_k.x)` of each plane, or the cubic filter's sum along each of the four
    /// texel rows.
    pub(super) fn prepare(&self, tex: &Textures, layout: &Layout, scratch: &mut Scratch) {
        let xs = self.block.xs.clone();
        let n = xs.len();
        for buf in scratch
            .columns
            .iter_mut()
            .chain(&mut scratch.planes)
            .chain([&mut scratch.combined, &mut scratch.dist])
        {
            buf.resize(n.max(buf.len()), 0.0);
        }
        match &self.interpolant {
            Interpolant::Planes { centers } => {
                let blends = tex.blends(self.block.c, self.block.r);
                scratch.grow = [0, 1, 2, 3].map(|k| Ops::of(&blends.grow[k], k));
                scratch.shrink = [0, 1, 2, 3].map(|k| Ops::of(&blends.shrink[k], k));
                for (k, out) in scratch.columns.iter_mut().enumerate() {
                    let (gx, cx) = (self.quad[k].g.x, centers[k].x);
                    for (o, &px) in out.iter_mut().zip(&layout.columns.world[xs.clone()]) {
                        *o = gx * (px - cx);
                    }
                }
            }
            Interpolant::Cubic { neighbourhood, .. } => {
                for (j, out) in scratch.columns.iter_mut().enumerate() {
                    let v = neighbourhood[j];
                    for (o, w) in out.iter_mut().zip(&layout.columns.cubic[xs.clone()]) {
                        *o = w[0] * v[0] + w[1] * v[1] + w[2] * v[2] + w[3] * v[3];
                    }
                }
            }
            Interpolant::Bilinear => {}
        }
    }

    /// Computes the distances of image row `y` of the block into `scratch.dist[..n]`.
    pub(super) fn row(&self, layout: &Layout, y: usize, scratch: &mut Scratch) {
        let n = self.block.xs.len();
        let rows = &layout.rows;
        let (fy, gy) = (rows.frac[y], rows.comp[y]);
        let comp = &layout.columns.comp[self.block.xs.clone()];
        let frac = &layout.columns.frac[self.block.xs.clone()];
        let Scratch {
            columns,
            planes,
            combined,
            grow,
            shrink,
            dist,
        } = scratch;
        let dist = &mut dist[..n];
        match &self.interpolant {
            Interpolant::Planes { centers } => {
                let py = rows.world[y];
                for (k, out) in planes.iter_mut().enumerate() {
                    let t = &self.quad[k];
                    let ay = t.g.y * (py - centers[k].y);
                    for (p, &ax) in out[..n].iter_mut().zip(&columns[k][..n]) {
                        *p = t.d + (ax + ay);
                    }
                }
                let wy = [gy, gy, fy, fy];
                for k in 0..4 {
                    let r = &mut combined[..n];
                    r.copy_from_slice(&planes[k][..n]);
                    for &(m, a) in grow[k].as_slice() {
                        for (r, &p) in r.iter_mut().zip(&planes[m][..n]) {
                            *r += a * (r.max(p) - *r);
                        }
                    }
                    for &(m, b) in shrink[k].as_slice() {
                        for (r, &p) in r.iter_mut().zip(&planes[m][..n]) {
                            *r += b * (r.min(p) - *r);
                        }
                    }
                    let wx = if k & 1 == 0 { comp } else { frac };
                    accumulate(dist, r, wx, wy[k], k == 0);
                }
                let xs = &layout.columns.world[self.block.xs.clone()];
                for (d, &px) in dist.iter_mut().zip(xs) {
                    *d = lipschitz_clamp(*d, &self.quad, centers, px, py, self.slope);
                }
            }
            Interpolant::Bilinear => {
                let d = self.quad.map(|t| t.d);
                for ((o, &gx), &fx) in dist.iter_mut().zip(comp).zip(frac) {
                    let w = [gx * gy, fx * gy, gx * fy, fx * fy];
                    *o = w[0] * d[0] + w[1] * d[1] + w[2] * d[2] + w[3] * d[3];
                }
            }
            Interpolant::Cubic { .. } => {
                let w = rows.cubic[y];
                let [c0, c1, c2, c3] = columns;
                let sums = c0.iter().zip(c1.iter()).zip(c2.iter()).zip(c3.iter());
                for (o, (((v0, v1), v2), v3)) in dist.iter_mut().zip(sums) {
                    *o = w[0] * v0 + w[1] * v1 + w[2] * v2 + w[3] * v3;
                }
            }
        }
    }

    /// Material of the texel nearest to pixel `(x, y)` of the block: one of the quad's,
    /// since `floor(q + 0.5)` is `c` or `c + 1` along each axis.
    pub(super) fn material(&self, layout: &Layout, x: usize, y: usize) -> u16 {
        if let Interpolant::Planes { centers } = &self.interpolant {
            let (px, py) = (layout.columns.world[x], layout.rows.world[y]);
            return self.quad[lowest_plane(&self.quad, centers, px, py)].material;
        }
        let right = layout.columns.pos[x].nearest > self.block.c;
        let below = layout.rows.pos[y].nearest > self.block.r;
        self.quad[usize::from(right) + 2 * usize::from(below)].material
    }

    /// Bounds of the distance over the whole block.
    pub(super) fn bounds(&self, layout: &Layout) -> Bounds {
        let (lo, hi, magnitude) = match &self.interpolant {
            Interpolant::Planes { centers } => self.plane_bounds(layout, centers),
            Interpolant::Bilinear => value_bounds(self.quad.iter().map(|t| t.d)),
            Interpolant::Cubic {
                neighbourhood,
                filter,
            } => {
                let (lo, hi, magnitude) = value_bounds(neighbourhood.iter().flatten().copied());
                // At most 1/8 of Catmull-Rom's weight per axis is negative, so at most
                // (1.25^2 - 1) / 2 < 0.3 in 2D; the B-spline's weights are non-negative.
                let overshoot = overshoot(*filter, 0.3) * (hi - lo);
                // Rounding is relative to the terms, which negative weights can inflate.
                (lo - overshoot, hi + overshoot, 2.0 * magnitude)
            }
        };
        Bounds {
            lo,
            hi,
            margin: magnitude * 1.0e-5 + (hi - lo) * 1.0e-5,
        }
    }

    /// Bounds `(lo, hi)` of the distance over image row `y` of the block (after
    /// [`Kernel::prepare`]), without margin: the block's [`Bounds::margin`] covers them.
    pub(super) fn row_bounds(&self, layout: &Layout, y: usize, scratch: &Scratch) -> (f32, f32) {
        match &self.interpolant {
            Interpolant::Planes { centers } => {
                // Planes are affine along the row: their values at the row's end pixels
                // (computed exactly as `row` computes them) bound it.
                let (py, last) = (layout.rows.world[y], self.block.xs.len() - 1);
                let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
                for (k, t) in self.quad.iter().enumerate() {
                    let ay = t.g.y * (py - centers[k].y);
                    for ax in [scratch.columns[k][0], scratch.columns[k][last]] {
                        let v = t.d + (ax + ay);
                        (lo, hi) = (lo.min(v), hi.max(v));
                    }
                }
                self.widen_for_clamp(lo, hi)
            }
            Interpolant::Bilinear => {
                // Linear along the row: its values at f = 0 and f = 1 bound it.
                let (fy, gy) = (layout.rows.frac[y], layout.rows.comp[y]);
                let d = self.quad.map(|t| t.d);
                let (a, b) = (gy * d[0] + fy * d[2], gy * d[1] + fy * d[3]);
                (a.min(b), a.max(b))
            }
            Interpolant::Cubic {
                neighbourhood,
                filter,
            } => {
                // The row's value is the x filter over the four column sums along it.
                let w = layout.rows.cubic[y];
                let sums =
                    [0, 1, 2, 3].map(|i| (0..4).map(|j| w[j] * neighbourhood[j][i]).sum::<f32>());
                let (lo, hi, _) = value_bounds(sums.into_iter());
                let overshoot = overshoot(*filter, 0.125) * (hi - lo);
                (lo - overshoot, hi + overshoot)
            }
        }
    }

    /// Every combined plane lies between the smallest and largest plane at each pixel
    /// (blends are convex), and the pixel distance is a convex combination of them; a
    /// plane is affine, so its extremes over the block are at the block's corner pixels.
    fn plane_bounds(&self, layout: &Layout, centers: &[Vec2; 4]) -> (f32, f32, f32) {
        let (xs, ys) = (&self.block.xs, &self.block.ys);
        let corners_x = [
            layout.columns.world[xs.start],
            layout.columns.world[xs.end - 1],
        ];
        let corners_y = [layout.rows.world[ys.start], layout.rows.world[ys.end - 1]];
        let (mut lo, mut hi, mut magnitude) = (f32::INFINITY, f32::NEG_INFINITY, 0.0f32);
        for (t, c) in self.quad.iter().zip(centers) {
            magnitude = magnitude.max(t.d.abs());
            for px in corners_x {
                for py in corners_y {
                    let v = plane(t, *c, px, py);
                    lo = lo.min(v);
                    hi = hi.max(v);
                    let terms = t.g.x * (px - c.x);
                    let size = t.d.abs() + terms.abs() + (t.g.y * (py - c.y)).abs();
                    magnitude = magnitude.max(size);
                }
            }
        }
        let (lo, hi) = self.widen_for_clamp(lo, hi);
        (lo, hi, magnitude)
    }

    /// The Lipschitz clamp moves a value `v` into `[lb, ub]` with `lb <= max_k d_k` and
    /// `ub >= min_k d_k` (a crossed interval gives its midpoint, between the two), so the
    /// clamped value stays within `[min(lo, min_k d_k), max(hi, max_k d_k)]`.
    fn widen_for_clamp(&self, lo: f32, hi: f32) -> (f32, f32) {
        let ds = self.quad.map(|t| t.d);
        let (dmin, dmax) = ds
            .iter()
            .fold((f32::INFINITY, f32::NEG_INFINITY), |(a, b), &d| {
                (a.min(d), b.max(d))
            });
        (lo.min(dmin), hi.max(dmax))
    }
}

/// Bounds of a block's distance, world units: every pixel's computed distance (and, for
/// [`Kernel::row_bounds`], every row's bounds) lies in `lo - margin ..= hi + margin`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Bounds {
    pub lo: f32,
    pub hi: f32,
    /// Covers `f32` rounding in the pixels' and the bounds' arithmetic.
    pub margin: f32,
}

/// The fraction of the value range a filter can overshoot by, given the negative weight
/// share of Catmull-Rom.
fn overshoot(filter: Upsample, negative_share: f32) -> f32 {
    match filter {
        Upsample::CatmullRom => negative_share,
        _ => 0.0,
    }
}

/// Min, max and largest magnitude of `values`.
fn value_bounds(values: impl Iterator<Item = f32>) -> (f32, f32, f32) {
    values.fold(
        (f32::INFINITY, f32::NEG_INFINITY, 0.0f32),
        |(lo, hi, m), v| (lo.min(v), hi.max(v), m.max(v.abs())),
    )
}

/// `dist = w r` (first plane) or `dist += w r`, with `w = wx * wy` as the bilinear weights
/// multiply them.
fn accumulate(dist: &mut [f32], r: &[f32], wx: &[f32], wy: f32, first: bool) {
    if first {
        for ((d, &r), &wx) in dist.iter_mut().zip(r).zip(wx) {
            *d = (wx * wy) * r;
        }
    } else {
        for ((d, &r), &wx) in dist.iter_mut().zip(r).zip(wx) {
            *d += (wx * wy) * r;
        }
    }
}

/// The bilinear weights of the pixel at column `x`, row `y`.
pub(super) fn pixel_weights(layout: &Layout, x: usize, y: usize) -> [f32; 4] {
    bilinear_weights(layout.columns.frac[x], layout.rows.frac[y])
}

/// Splits `buf` (rows of `row_len` entries) into units of consecutive bands of `runs`, in
/// order, each unit the fewest bands that hold at least `min_rows` pixel rows (the last
/// may hold fewer).
pub(super) fn split_row_groups<'r, 'b, T>(
    runs: &'r [Run],
    mut buf: &'b mut [T],
    row_len: usize,
    min_rows: usize,
) -> Vec<(&'r [Run], &'b mut [T])> {
    let mut out = Vec::new();
    let mut first = 0;
    while first < runs.len() {
        let mut end = first;
        let mut rows = 0;
        while end < runs.len() && (end == first || rows < min_rows) {
            rows += runs[end].pixels.len();
            end += 1;
        }
        let (unit, rest) = std::mem::take(&mut buf).split_at_mut(rows * row_len);
        out.push((&runs[first..end], unit));
        buf = rest;
        first = end;
    }
    out
}

/// Splits `buf` (rows of `row_len` entries) into the bands of `runs`, in order.
pub(super) fn split_rows<'r, 'b, T>(
    runs: &'r [Run],
    mut buf: &'b mut [T],
    row_len: usize,
) -> Vec<(&'r Run, &'b mut [T])> {
    let mut out = Vec::with_capacity(runs.len());
    for run in runs {
        let (band, rest) = std::mem::take(&mut buf).split_at_mut(run.pixels.len() * row_len);
        out.push((run, band));
        buf = rest;
    }
    out
}
