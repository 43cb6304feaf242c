//! Pass 2: reconstruction on the reduced-scale lattice. Mode `divergence` lowers the
//! distance where the packed gradient's divergence says "thin solid"; mode `planes` computes
//! the pair values that tell pass 3 which tangent planes to combine by `max` (diverging
//! gradients) or `min` (converging). Outputs are rounded through `f16` like the GPU's
//! `Rgba16Float` targets.

use glam::Vec2;

use super::f16::round_f16;
use super::{LowRes, Texel, TwinError};
use crate::lattice::Lattice;
use crate::options::Reconstruction;

/// Applies pass 2 in `mode` to the output of pass 1 (once: running `divergence` twice
/// pads twice). `pairs` is set in mode `planes` and cleared in the others.
pub fn reconstruct(lowres: &mut LowRes, mode: Reconstruction) -> Result<(), TwinError> {
    check_texels(lowres)?;
    match mode {
        Reconstruction::Off => lowres.pairs = None,
        Reconstruction::Divergence => {
            lowres.texels = divergence(&lowres.lattice, &lowres.texels);
            lowres.pairs = None;
        }
        Reconstruction::Planes | Reconstruction::Refine => {
            lowres.pairs = Some(pair_values(&lowres.lattice, &lowres.texels));
        }
    }
    Ok(())
}

/// `texels` has one entry per texel of the lattice.
pub(super) fn check_texels(lowres: &LowRes) -> Result<(), TwinError> {
    let expected = lowres.lattice.len();
    if lowres.texels.len() == expected {
        Ok(())
    } else {
        Err(TwinError::BufferSize {
            buffer: "texels",
            len: lowres.texels.len(),
            expected,
        })
    }
}

/// Texel lookups with the lattice's clamp-to-edge rule.
struct Grid<'a> {
    texels: &'a [Texel],
    cols: i64,
    rows: i64,
}

impl Grid<'_> {
    fn clamped(&self, c: i64, r: i64) -> &Texel {
        let (c, r) = (c.clamp(0, self.cols - 1), r.clamp(0, self.rows - 1));
        &self.texels[(r * self.cols + c) as usize]
    }

    fn inside(&self, c: i64, r: i64) -> Option<&Texel> {
        let inside = (0..self.cols).contains(&c) && (0..self.rows).contains(&r);
        inside.then(|| &self.texels[(r * self.cols + c) as usize])
    }
}

fn grid<'a>(lattice: &Lattice, texels: &'a [Texel]) -> Grid<'a> {
    Grid {
        texels,
        cols: i64::from(lattice.cols),
        rows: i64::from(lattice.rows),
    }
}

/// The divergence heuristic: `d' = d - k h` with
/// `k = clamp(sign(gxx) gxx^2 + sign(gyy) gyy^2, 0, 1)`.
fn divergence(lattice: &Lattice, texels: &[Texel]) -> Vec<Texel> {
    let g = grid(lattice, texels);
    let mut out = texels.to_vec();
    for (i, texel) in out.iter_mut().enumerate() {
        let (c, r) = (i as i64 % g.cols, i as i64 / g.cols);
        let gxx = (g.clamped(c + 1, r).g.x - g.clamped(c - 1, r).g.x) * 0.5;
        // Row r - 1 is world-up.
        let gyy = (g.clamped(c, r - 1).g.y - g.clamped(c, r + 1).g.y) * 0.5;
        let k = (signed_square(gxx) + signed_square(gyy)).clamp(0.0, 1.0);
        texel.d = round_f16(texel.d - k * lattice.h);
    }
    out
}

/// `sign(v) v^2`.
fn signed_square(v: f32) -> f32 {
    v.abs() * v
}

/// The four pair values `[right, down, diag, anti]` of every texel.
fn pair_values(lattice: &Lattice, texels: &[Texel]) -> Vec<[f32; 4]> {
    let g = grid(lattice, texels);
    (0..texels.len())
        .map(|i| {
            let (c, r) = (i as i64 % g.cols, i as i64 / g.cols);
            let pair = |a: (i64, i64), b: (i64, i64)| match (g.inside(a.0, a.1), g.inside(b.0, b.1))
            {
                (Some(ta), Some(tb)) => pair_value(ta.g, tb.g, b.0 - a.0, b.1 - a.1),
                _ => 0.0,
            };
            [
                pair((c, r), (c + 1, r)),
                pair((c, r), (c, r + 1)),
                pair((c, r), (c + 1, r + 1)),
                pair((c + 1, r), (c, r + 1)),
            ]
        })
        .collect()
}

/// `s = clamp(div / 0.5, -1, 1)` of texels `a` and `b` (`b` is `dc` columns and `dr` rows
/// from `a`), with `div = (g_b - g_a) . (C_b - C_a) / h`; 0 where a gradient is shorter than
/// 0.5 (clamped or flat field: no tangent plane to trust).
fn pair_value(ga: Vec2, gb: Vec2, dc: i64, dr: i64) -> f32 {
    let short = |g: Vec2| (g.x * g.x + g.y * g.y).sqrt() < 0.5;
    if short(ga) || short(gb) {
        return 0.0;
    }
    // (C_b - C_a) / h in world directions: rows go down, world y goes up.
    let (sx, sy) = (dc as f32, -dr as f32);
    let div = (gb.x - ga.x) * sx + (gb.y - ga.y) * sy;
    round_f16((div / 0.5).clamp(-1.0, 1.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn texel(d: f32, gx: f32, gy: f32) -> Texel {
        Texel {
            d,
            g: Vec2::new(gx, gy),
            material: 0,
        }
    }

    fn lattice(cols: u32, rows: u32) -> Lattice {
        Lattice {
            h: 16.0,
            i0: 0,
            j0: 0,
            cols,
            rows,
        }
    }

    #[test]
    fn pairs_diverge_across_a_thin_solid_and_converge_across_a_gap() {
        // Texels left and right of a vertical line, gradients pointing away from it.
        assert_eq!(pair_value(Vec2::NEG_X, Vec2::X, 1, 0), 1.0);
        // Across a gap they point towards it.
        assert_eq!(pair_value(Vec2::X, Vec2::NEG_X, 1, 0), -1.0);
        // A horizontal line between rows r (above, gradient up) and r + 1 (below, down).
        assert_eq!(pair_value(Vec2::Y, Vec2::NEG_Y, 0, 1), 1.0);
        // Parallel gradients, a degenerate one, small divergence.
        assert_eq!(pair_value(Vec2::Y, Vec2::Y, 1, 1), 0.0);
        assert_eq!(pair_value(Vec2::new(0.3, 0.0), Vec2::X, 1, 0), 0.0);
        let small = pair_value(Vec2::Y, Vec2::new(0.1, 0.995), 1, 0);
        assert_eq!(small, round_f16(0.2));
    }

    #[test]
    fn planes_pairs_are_zero_off_the_lattice() {
        let mut low = LowRes {
            lattice: lattice(3, 2),
            texels: vec![
                texel(1.0, -1.0, 0.0),
                texel(1.0, 1.0, 0.0),
                texel(1.0, 1.0, 0.0),
                texel(1.0, -1.0, 0.0),
                texel(1.0, 1.0, 0.0),
                texel(1.0, 1.0, 0.0),
            ],
            pairs: None,
            slope: 1.5,
        };
        reconstruct(&mut low, Reconstruction::Planes).unwrap();
        let pairs = low.pairs.unwrap();
        // Anti: (1, 0) points +x, (0, 1) one column left and one row down points -x.
        assert_eq!(pairs[0], [1.0, 0.0, 1.0, 1.0]);
        assert_eq!(pairs[2], [0.0; 4]);
        assert_eq!(pairs[3], [1.0, 0.0, 0.0, 0.0]);
    }

    #[test]
    fn divergence_pads_ridges_by_up_to_one_texel() {
        // A vertical ridge at column 1: gradients -x to its left, +x to its right.
        let row = [
            texel(4.0, -1.0, 0.0),
            texel(4.0, 0.0, 0.0),
            texel(4.0, 1.0, 0.0),
        ];
        let texels: Vec<Texel> = row.iter().chain(&row).copied().collect();
        let out = divergence(&lattice(3, 2), &texels);
        // gxx = (1 - (-1)) / 2 = 1 at the ridge: k = 1, one texel lower.
        assert_eq!(out[1].d, 4.0 - 16.0);
        // Clamped edges: gxx = (0 - (-1)) / 2 at column 0 gives k = 0.25.
        assert_eq!(out[0].d, 0.0);
        assert_eq!(out[2].d, 0.0);
        let mut low = LowRes {
            lattice: lattice(3, 2),
            texels: texels[..5].to_vec(),
            pairs: None,
            slope: 1.5,
        };
        assert!(matches!(
            reconstruct(&mut low, Reconstruction::Divergence),
            Err(TwinError::BufferSize {
                len: 5,
                expected: 6,
                ..
            })
        ));
    }
}
