//! Inside/outside images of a program over a rectangle, by brute force or by hierarchical
//! region specialization (the Prospero Challenge's task: a pixel is inside where the value
//! is below zero).
//!
//! Pixel `(i, j)` (row 0 at the top) samples the centre `x = min.x + (i + 0.5) w / n`,
//! `y = max.y - (j + 0.5) h / n`. The specialized render walks square tiles of decreasing
//! size: a tile whose bound is decided everywhere is filled, another gets the program
//! specialized to its pixel centres and is split further; the smallest tiles run the
//! parent's tape. Specialized programs compute the same bits as the whole one at every
//! point of their box, so both renders give the same image.

use glam::Vec2;

use super::{EvalError, Outputs, Program, Tape};
use craterfield_core::backend::Backend;

/// How to render.
#[derive(Clone, Debug, PartialEq)]
pub struct ImageOptions {
    /// Pixels per side (the image is square).
    pub size: u32,
    /// Lower-left corner of the region.
    pub min: Vec2,
    /// Upper-right corner of the region.
    pub max: Vec2,
    /// Tile sides from the largest down, each dividing the previous; the last is the
    /// smallest tile, evaluated with its parent's tape. Empty: brute force.
    pub tiles: Vec<u32>,
    /// The backend.
    pub backend: Backend,
    /// Threads (tiles of the first level are shared out).
    pub threads: usize,
    /// Whether the smallest tiles are bounded before they are evaluated (a bound costs
    /// about as much as evaluating a few dozen points).
    pub leaf_bounds: bool,
}

impl Default for ImageOptions {
    fn default() -> Self {
        ImageOptions {
            size: 1024,
            min: Vec2::splat(-1.0),
            max: Vec2::splat(1.0),
            tiles: vec![256, 64, 32],
            backend: Backend::best(),
            threads: 1,
            leaf_bounds: false,
        }
    }
}

/// Why an image could not be rendered.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ImageError {
    /// A size or tile size is unusable.
    #[error("image options: {0}")]
    Options(String),
    /// Evaluation failed.
    #[error(transparent)]
    Eval(#[from] EvalError),
}

/// Counts of what the specialized render did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ImageStats {
    /// Tiles decided by their bound and filled without evaluation.
    pub filled_tiles: u64,
    /// Programs specialized.
    pub specialized: u64,
    /// Pixels evaluated.
    pub evaluated_pixels: u64,
    /// Instructions executed per evaluated pixel, summed.
    pub instructions: u64,
}

impl ImageOptions {
    fn check(&self) -> Result<(), ImageError> {
        if self.size == 0 || self.size > 16_384 {
            return Err(ImageError::Options(format!(
                "size must be in 1..=16384, got {}",
                self.size
            )));
        }
        if !(self.min.is_finite() && self.max.is_finite())
            || self.min.x >= self.max.x
            || self.min.y >= self.max.y
        {
            return Err(ImageError::Options(format!(
                "region {} .. {} must be finite and non-empty",
                self.min, self.max
            )));
        }
        let mut prev = self.size;
        // `%` rather than `is_multiple_of`: the deterministic core also builds with the
        // older toolchain of the aarch64 cross tests.
        #[allow(clippy::manual_is_multiple_of)]
        for &t in &self.tiles {
            if t == 0 || prev % t != 0 {
                return Err(ImageError::Options(format!(
                    "tile size {t} does not divide {prev}"
                )));
            }
            prev = t;
        }
        Ok(())
    }

    /// The centre of pixel `(i, j)`.
    pub fn pixel(&self, i: u32, j: u32) -> Vec2 {
        let n = self.size as f32;
        let w = (self.max.x - self.min.x) / n;
        let h = (self.max.y - self.min.y) / n;
        Vec2::new(
            self.min.x + (i as f32 + 0.5) * w,
            self.max.y - (j as f32 + 0.5) * h,
        )
    }
}

/// The image (row-major, row 0 at the top) and what the render did.
pub fn inside_image(
    program: &Program,
    o: &ImageOptions,
) -> Result<(Vec<bool>, ImageStats), ImageError> {
    o.check()?;
    let n = o.size as usize;
    let mut image = vec![false; n * n];
    // Specialization decides on plain instructions; tapes are fused when they are made.
    let root = program;
    let threads = o.threads.clamp(1, 64);
    if o.tiles.is_empty() {
        let tape = root.fuse().tape(Outputs::Value);
        let rows: Vec<(usize, &mut [bool])> = image.chunks_mut(n).enumerate().collect();
        let stats = in_threads(rows, threads, |rows| brute_rows(&tape, o, rows))?;
        return Ok((image, stats));
    }
    let top = o.tiles[0] as usize;
    let per_row = n / top;
    // Bands of tile rows, each band's rows of pixels owned by one task.
    let bands: Vec<(usize, &mut [bool])> = image.chunks_mut(n * top).enumerate().collect();
    let stats = in_threads(bands, threads, |bands| {
        let mut st = ImageStats::default();
        for (band, px) in bands {
            for tx in 0..per_row {
                let tile = Tile {
                    x: tx * top,
                    y: band * top,
                    size: top,
                };
                render_tile(root, o, 0, tile, band * top, px, &mut st)?;
            }
        }
        Ok(st)
    })?;
    Ok((image, stats))
}

/// Runs `work` on `threads` shares of `items` (in order, so results do not depend on it).
fn in_threads<T: Send>(
    items: Vec<T>,
    threads: usize,
    work: impl Fn(Vec<T>) -> Result<ImageStats, ImageError> + Sync,
) -> Result<ImageStats, ImageError> {
    let threads = craterfield_core::threads::spawnable(threads).max(1);
    let mut shares: Vec<Vec<T>> = (0..threads).map(|_| Vec::new()).collect();
    for (k, item) in items.into_iter().enumerate() {
        shares[k % threads].push(item);
    }
    let results: Vec<Result<ImageStats, ImageError>> = if threads == 1 {
        shares.into_iter().map(&work).collect()
    } else {
        std::thread::scope(|s| {
            let handles: Vec<_> = shares
                .into_iter()
                .map(|share| s.spawn(|| work(share)))
                .collect();
            handles
                .into_iter()
                .map(|h| {
                    h.join().unwrap_or_else(|_| {
                        Err(ImageError::Options("a render thread failed".into()))
                    })
                })
                .collect()
        })
    };
    let mut total = ImageStats::default();
    for r in results {
        let s = r?;
        total.filled_tiles += s.filled_tiles;
        total.specialized += s.specialized;
        total.evaluated_pixels += s.evaluated_pixels;
        total.instructions += s.instructions;
    }
    Ok(total)
}

fn brute_rows(
    tape: &Tape,
    o: &ImageOptions,
    rows: Vec<(usize, &mut [bool])>,
) -> Result<ImageStats, ImageError> {
    let n = o.size;
    let mut pts = Vec::with_capacity(n as usize);
    let mut vals = vec![0.0f32; n as usize];
    let mut st = ImageStats::default();
    for (j, row) in rows {
        pts.clear();
        pts.extend((0..n).map(|i| o.pixel(i, j as u32)));
        tape.distances(&pts, &mut vals, o.backend)?;
        for (px, v) in row.iter_mut().zip(&vals) {
            *px = *v < 0.0;
        }
        st.evaluated_pixels += u64::from(n);
        st.instructions += u64::from(n) * tape.len() as u64;
    }
    Ok(st)
}

#[derive(Clone, Copy)]
struct Tile {
    x: usize,
    y: usize,
    size: usize,
}

impl Tile {
    /// The box of the tile's pixel centres.
    fn bounds(&self, o: &ImageOptions) -> (Vec2, Vec2) {
        let (last_x, last_y) = (self.x + self.size - 1, self.y + self.size - 1);
        (
            o.pixel(self.x as u32, last_y as u32),
            o.pixel(last_x as u32, self.y as u32),
        )
    }
}

/// Renders `tile` with `program` at tile level `level`; `px` holds the image rows from
/// `row0` on.
fn render_tile(
    program: &Program,
    o: &ImageOptions,
    level: usize,
    tile: Tile,
    row0: usize,
    px: &mut [bool],
    st: &mut ImageStats,
) -> Result<(), ImageError> {
    if level + 1 == o.tiles.len() {
        // A single tile level: the tiles are the smallest ones, run with the whole tape.
        return leaves(program, o, tile, tile.size, row0, px, st);
    }
    let (lo, hi) = tile.bounds(o);
    let (spec, bound) = program.specialize_with_bound(lo, hi);
    if let Some(inside) = decided(bound) {
        fill(o, tile, row0, px, inside);
        st.filled_tiles += 1;
        return Ok(());
    }
    st.specialized += 1;
    let sub = o.tiles[level + 1] as usize;
    if level + 2 == o.tiles.len() {
        return leaves(&spec, o, tile, sub, row0, px, st);
    }
    for sy in (0..tile.size).step_by(sub) {
        for sx in (0..tile.size).step_by(sub) {
            let t = Tile {
                x: tile.x + sx,
                y: tile.y + sy,
                size: sub,
            };
            render_tile(&spec, o, level + 1, t, row0, px, st)?;
        }
    }
    Ok(())
}

/// The smallest tiles of `tile`: filled where the bound decides, else evaluated with
/// `program`'s tape (allocated once for them all).
fn leaves(
    program: &Program,
    o: &ImageOptions,
    tile: Tile,
    sub: usize,
    row0: usize,
    px: &mut [bool],
    st: &mut ImageStats,
) -> Result<(), ImageError> {
    let mut tape: Option<Tape> = None;
    let mut pts = Vec::with_capacity(sub * sub);
    let mut vals = vec![0.0f32; sub * sub];
    let n = o.size as usize;
    for sy in (0..tile.size).step_by(sub) {
        for sx in (0..tile.size).step_by(sub) {
            let t = Tile {
                x: tile.x + sx,
                y: tile.y + sy,
                size: sub,
            };
            if o.leaf_bounds {
                let (lo, hi) = t.bounds(o);
                if let Some(inside) = decided(program.bound(lo, hi)) {
                    fill(o, t, row0, px, inside);
                    st.filled_tiles += 1;
                    continue;
                }
            }
            let tape = tape.get_or_insert_with(|| program.fuse().tape(Outputs::Value));
            pts.clear();
            for j in t.y..t.y + sub {
                for i in t.x..t.x + sub {
                    pts.push(o.pixel(i as u32, j as u32));
                }
            }
            tape.distances(&pts, &mut vals, o.backend)?;
            for (k, v) in vals.iter().enumerate() {
                let (i, j) = (t.x + k % sub, t.y + k / sub);
                px[(j - row0) * n + i] = *v < 0.0;
            }
            st.evaluated_pixels += (sub * sub) as u64;
            st.instructions += (sub * sub * tape.len()) as u64;
        }
    }
    Ok(())
}

/// `Some(inside)` when the bound puts every value on one side of zero.
fn decided(b: super::interval::Range) -> Option<bool> {
    if b.nan {
        None
    } else if b.hi < 0.0 {
        Some(true)
    } else if b.lo >= 0.0 {
        Some(false)
    } else {
        None
    }
}

fn fill(o: &ImageOptions, t: Tile, row0: usize, px: &mut [bool], inside: bool) {
    let n = o.size as usize;
    for j in t.y..t.y + t.size {
        let row = (j - row0) * n;
        px[row + t.x..row + t.x + t.size].fill(inside);
    }
}
