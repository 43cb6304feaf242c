//! Pass 1: the terrain sampled at every texel centre of the lattice by the SIMD batch
//! evaluator ([`Terrain::samples`]), stored as the GPU's `Rgba16Float` texture stores it.

use glam::Vec2;

use super::f16::round_f16;
use super::threads::{resolve, run_units};
use super::{LowRes, Texel, TwinError};
use crate::camera::MAX_IMAGE_SIDE;
use crate::lattice::Lattice;
use crate::options::Scale;
use craterfield_field::{Sample, Sdf, Terrain};

/// Most texels per batch call: large enough for the evaluator's cell grouping to pay off,
/// small enough that the point and sample buffers stay in cache.
const BATCH: usize = 4096;

/// Samples `terrain` at every texel of `lattice` on `threads` threads (0: all cores).
/// Distances and gradients are rounded through `f16`; the result is the same for every
/// thread count (the batch evaluator is bit-identical to [`Sdf::sample`]).
pub fn sdf_pass<F: Sdf + Sync>(
    terrain: &Terrain<F>,
    lattice: &Lattice,
    threads: usize,
) -> Result<LowRes, TwinError> {
    check_lattice(lattice)?;
    let mut texels = vec![Texel::default(); lattice.len()];
    let cols = lattice.cols as usize;
    // Several units per thread so that sky rows and terrain rows balance out.
    let balanced = (lattice.rows as usize).div_ceil(4 * resolve(threads));
    let rows_per_unit = balanced.min(BATCH / cols).max(1);
    let units: Vec<(u32, &mut [Texel])> = texels
        .chunks_mut(rows_per_unit * cols)
        .enumerate()
        .map(|(i, chunk)| ((i * rows_per_unit) as u32, chunk))
        .collect();
    run_units(units, threads, Scratch::default, |scratch, (row0, out)| {
        scratch.sample_rows(terrain, lattice, row0, out)
    })?;
    Ok(LowRes {
        lattice: *lattice,
        texels,
        pairs: None,
        slope: super::slope_bound(terrain.lipschitz()),
    })
}

/// A thread's point and sample buffers, reused across its units.
#[derive(Default)]
struct Scratch {
    points: Vec<Vec2>,
    samples: Vec<Sample>,
}

impl Scratch {
    /// Fills `out` (whole rows from `row0` on) with the texels of those rows.
    fn sample_rows<F: Sdf>(
        &mut self,
        terrain: &Terrain<F>,
        lattice: &Lattice,
        row0: u32,
        out: &mut [Texel],
    ) -> Result<(), TwinError> {
        let cols = lattice.cols;
        self.points.clear();
        self.points.extend((0..out.len() as u32).map(|i| {
            let (col, row) = (i % cols, row0 + i / cols);
            lattice.texel_center(col, row)
        }));
        let empty = Sample {
            distance: 0.0,
            gradient: Vec2::ZERO,
            material: 0,
        };
        self.samples.clear();
        self.samples.resize(out.len(), empty);
        terrain.samples(&self.points, &mut self.samples)?;
        for (texel, s) in out.iter_mut().zip(&self.samples) {
            *texel = Texel {
                d: round_f16(s.distance),
                g: Vec2::new(round_f16(s.gradient.x), round_f16(s.gradient.y)),
                material: s.material,
            };
        }
        Ok(())
    }
}

/// Rejects lattices no camera produces: too small, too large, or beyond `f32` range.
fn check_lattice(lattice: &Lattice) -> Result<(), TwinError> {
    // The finest scale needs the most texels.
    let (max_side, _) = Lattice::max_dims(MAX_IMAGE_SIDE, MAX_IMAGE_SIDE, Scale::Full);
    let sides_ok = (2..=max_side).contains(&lattice.cols) && (2..=max_side).contains(&lattice.rows);
    let h_ok = lattice.h.is_finite() && lattice.h > 0.0;
    let reach_ok = h_ok && {
        let corner = |c: i32, r: i32| {
            (c as f32 * lattice.h)
                .abs()
                .max((r as f32 * lattice.h).abs())
        };
        let far = corner(lattice.i0, lattice.j0).max(corner(
            lattice.i0.saturating_add(lattice.cols as i32),
            lattice.j0.saturating_sub(lattice.rows as i32),
        ));
        far <= 1.0e7
    };
    if sides_ok && reach_ok {
        Ok(())
    } else {
        Err(TwinError::BadLattice {
            lattice: *lattice,
            max_side,
        })
    }
}
