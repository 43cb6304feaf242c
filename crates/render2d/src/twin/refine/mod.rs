//! Pass 3 in mode `refine`: every `BLOCK x BLOCK` pixel block of a quad is either proven
//! from the quad's four texels and the terrain's events, or evaluated exactly at every
//! pixel centre. `docs/render2d-pipeline.md` ("Refine") states the proof in full.
//!
//! For a block whose pixel centres span the rectangle `B`, with quad texels `k = 0..3`
//! (centres `C_k`, distances `d_k`, materials `m_k`, margins `mu_k`), `L` and `J` the
//! largest slope bound and border-jump allowance over the cells the quad touches
//! ([`Terrain::cell_bounds`]):
//!
//! * `R_k` is the largest distance from `C_k` to a corner of `B` (the farthest point of a
//!   rectangle from any point is a corner); `reach_k = L R_k + J + |d_k| / 1024 + upp / 1000`
//!   (the last two cover the `f16` rounding of `d_k` and the `f32` evaluations).
//! * Every pixel of `B` has its exact distance in `[lo, hi]`, `lo = max_k (d_k - reach_k)`,
//!   `hi = min_k (d_k + reach_k)`; where that decides nothing, the events of the cells `B`
//!   touches may ([`Terrain::rect_sign`]), first for the whole quad, then for the block.
//! * **Sky** when the distance is at least `upp / 2`: every pixel is its row's sky colour.
//! * **Solid** when it is at most `-(outline_px + 1/2) upp` and the material is proven, by
//!   either rule: every grid cell `B` touches has one constant material
//!   ([`Terrain::cell_material`]), and each pixel takes its cell's; or `B` and some `C_k` lie
//!   in one cell and `2 max(L, 1) R_k < mu_k` ([`Terrain::material_margin`]), and every pixel
//!   takes `m_k`. Each pixel is then fully covered with no outline. Blocks deeper than the
//!   interior depth everywhere are shaded from the planes interpolant; the others from exact
//!   samples on the GPU's corner grid (the pixel centres `(BLOCK i, BLOCK j)`), interpolated
//!   bilinearly over each grid square, the distance clamped to `hi`; the pixels of squares
//!   whose corners are creased ([`Prover::creased`]: a hard edge of the exact shade runs
//!   through them) are evaluated instead.
//! * Otherwise **uncertain**: every pixel is sampled with the terrain's batch evaluator and
//!   shaded exactly as [`crate::render_exact`] shades it.
//!
//! Sky and uncertain pixels are the exact render's, bit for bit; solid pixels have its
//! coverage and material, and differ from it only in the depth shade inside the terrain.
//!
//! The parts, each used only by the ones after it: [`stats`] (the frame's counts),
//! [`cells`] (what the proofs read), [`proof`] (the classes of blocks and the crease
//! rule), [`sink`] (where pixels go), [`evaluate`] (the exact evaluation of the rest),
//! [`corners`] (solid blocks shaded from corner samples), [`refiner`] (one unit of work)
//! and [`pass`] (the frame over threads).
//!
//! [`Terrain::cell_bounds`]: craterfield_field::Terrain::cell_bounds
//! [`Terrain::rect_sign`]: craterfield_field::Terrain::rect_sign
//! [`Terrain::cell_material`]: craterfield_field::Terrain::cell_material
//! [`Terrain::material_margin`]: craterfield_field::Terrain::material_margin
//! [`Prover::creased`]: proof::Prover::creased

mod cells;
mod corners;
mod evaluate;
mod pass;
mod proof;
mod refiner;
mod sink;
mod stats;

pub(super) use pass::{field_refined, render_refined};
pub use proof::BLOCK;
pub use stats::RefineStats;
