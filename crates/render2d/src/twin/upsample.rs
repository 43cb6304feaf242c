//! Pass 3's interpolation, pixel by pixel as `docs/render2d-pipeline.md` writes it: the
//! quad holding the pixel, the distance (bilinear, cubic B-spline, Catmull-Rom or the
//! tangent-plane combination), the bilinear normal and the nearest texel's material. The
//! block path ([`super::blocks`]) evaluates the same expressions in the same order with
//! the per-column and per-row parts hoisted, so both give the same bits.

use glam::Vec2;

use super::reconstruct::check_texels;
use super::shade::unit_or;
use super::{LowRes, Texel, TwinError};
use crate::lattice::Lattice;
use crate::options::{Reconstruction, RenderOptions, Upsample};

/// Distance, normal and material of one pixel (distance in world units).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct PixelField {
    pub d: f32,
    pub normal: Vec2,
    pub material: u16,
}

/// Where a pixel falls along one lattice axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct AxisPos {
    /// First texel of the quad (`floor(q)` clamped to `0..=count-2`).
    pub cell: u32,
    /// Offset in the quad, clamped to `[0, 1]`.
    pub frac: f32,
    /// Nearest texel (`floor(q + 0.5)` clamped to the lattice).
    pub nearest: u32,
}

/// The axis position of lattice coordinate `q` on an axis of `count >= 2` texels.
pub(super) fn axis_pos(q: f32, count: u32) -> AxisPos {
    let last = i64::from(count) - 1;
    let cell = (q.floor() as i64).clamp(0, last - 1);
    AxisPos {
        cell: cell as u32,
        frac: (q - cell as f32).clamp(0.0, 1.0),
        nearest: ((q + 0.5).floor() as i64).clamp(0, last) as u32,
    }
}

/// Pass 3's inputs, checked: texels, pair values where the mode needs them, mode, filter.
pub(super) struct Textures<'a> {
    pub lattice: Lattice,
    pub texels: &'a [Texel],
    pub pairs: &'a [[f32; 4]],
    pub mode: Reconstruction,
    pub filter: Upsample,
    /// The field's slope bound (see [`super::slope_bound`]).
    pub slope: f32,
}

impl<'a> Textures<'a> {
    /// The textures of `lowres` for `options`; an error names a missing or short buffer.
    pub(super) fn new(
        lowres: &'a LowRes,
        options: &RenderOptions,
    ) -> Result<Textures<'a>, TwinError> {
        check_texels(lowres)?;
        // Refine shades its proven blocks from the planes interpolant.
        let mode = match options.reconstruction {
            Reconstruction::Refine => Reconstruction::Planes,
            mode => mode,
        };
        let pairs: &[[f32; 4]] = match (mode, &lowres.pairs) {
            (Reconstruction::Planes, None) => return Err(TwinError::MissingPairs),
            (Reconstruction::Planes, Some(p)) if p.len() != lowres.texels.len() => {
                return Err(TwinError::BufferSize {
                    buffer: "pairs",
                    len: p.len(),
                    expected: lowres.texels.len(),
                });
            }
            (Reconstruction::Planes, Some(p)) => p,
            _ => &[],
        };
        Ok(Textures {
            lattice: lowres.lattice,
            texels: &lowres.texels,
            pairs,
            mode,
            filter: options.upsample,
            slope: lowres.slope,
        })
    }

    /// Texel `(c, r)`, clamped to the lattice.
    pub(super) fn texel(&self, c: i64, r: i64) -> &Texel {
        let cols = i64::from(self.lattice.cols);
        let c = c.clamp(0, cols - 1);
        let r = r.clamp(0, i64::from(self.lattice.rows) - 1);
        &self.texels[(r * cols + c) as usize]
    }

    /// The quad's texels `k = 0: (c, r), 1: (c+1, r), 2: (c, r+1), 3: (c+1, r+1)`.
    pub(super) fn quad(&self, c: u32, r: u32) -> [Texel; 4] {
        let (c, r) = (i64::from(c), i64::from(r));
        [(0, 0), (1, 0), (0, 1), (1, 1)].map(|(dc, dr)| *self.texel(c + dc, r + dr))
    }

    /// World centres of the quad's texels.
    pub(super) fn quad_centers(&self, c: u32, r: u32) -> [Vec2; 4] {
        [(0, 0), (1, 0), (0, 1), (1, 1)].map(|(dc, dr)| self.lattice.texel_center(c + dc, r + dr))
    }

    /// The 4x4 distances around quad `(c, r)`, `[row][column]` from `(c-1, r-1)`.
    pub(super) fn neighbourhood(&self, c: u32, r: u32) -> [[f32; 4]; 4] {
        let (c, r) = (i64::from(c), i64::from(r));
        [0, 1, 2, 3].map(|j| [0, 1, 2, 3].map(|i| self.texel(c - 1 + i, r - 1 + j).d))
    }

    /// The max and min blend weights of the quad at `(c, r)`.
    pub(super) fn blends(&self, c: u32, r: u32) -> Blends {
        let cols = self.lattice.cols as usize;
        let at = |c: u32, r: u32| self.pairs[r as usize * cols + c as usize];
        let (p0, p1, p2) = (at(c, r), at(c + 1, r), at(c, r + 1));
        // s01 = right(0), s02 = down(0), s03 = diag(0), s12 = anti(0), s13 = down(1),
        // s23 = right(2).
        let (s01, s02, s03, s12, s13, s23) = (p0[0], p0[1], p0[2], p0[3], p1[1], p2[0]);
        let s = [
            [0.0, s01, s02, s03],
            [s01, 0.0, s12, s13],
            [s02, s12, 0.0, s23],
            [s03, s13, s23, 0.0],
        ];
        Blends {
            grow: s.map(|row| row.map(|v| smooth01(v.max(0.0)))),
            shrink: s.map(|row| row.map(|v| smooth01((-v).max(0.0)))),
        }
    }
}

/// Weights of the tangent-plane combination: `grow[k][m]` pulls `R_k` up to plane `m`
/// (diverging gradients), `shrink[k][m]` down to it (converging).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Blends {
    pub grow: [[f32; 4]; 4],
    pub shrink: [[f32; 4]; 4],
}

/// `S(t) = t^2 (3 - 2t)`.
fn smooth01(t: f32) -> f32 {
    t * t * (3.0 - 2.0 * t)
}

/// Bilinear weights of the quad's texels at offset `(fx, fy)`.
pub(super) fn bilinear_weights(fx: f32, fy: f32) -> [f32; 4] {
    let (gx, gy) = (1.0 - fx, 1.0 - fy);
    [gx * gy, fx * gy, gx * fy, fx * fy]
}

/// `((w0 v0 + w1 v1) + w2 v2) + w3 v3`: the one summation order of every interpolant.
pub(super) fn weighted4(w: [f32; 4], v: [f32; 4]) -> f32 {
    w[0] * v[0] + w[1] * v[1] + w[2] * v[2] + w[3] * v[3]
}

/// The cubic filter's weights for texels `-1..=2` at offset `t`.
pub(super) fn cubic_weights(filter: Upsample, t: f32) -> [f32; 4] {
    let (t2, t3) = (t * t, t * t * t);
    match filter {
        Upsample::CatmullRom => [
            (-t3 + 2.0 * t2 - t) / 2.0,
            (3.0 * t3 - 5.0 * t2 + 2.0) / 2.0,
            (-3.0 * t3 + 4.0 * t2 + t) / 2.0,
            (t3 - t2) / 2.0,
        ],
        // The B-spline (bilinear never asks for cubic weights).
        _ => {
            let s = 1.0 - t;
            [
                s * s * s / 6.0,
                (3.0 * t3 - 6.0 * t2 + 4.0) / 6.0,
                (-3.0 * t3 + 3.0 * t2 + 3.0 * t + 1.0) / 6.0,
                t3 / 6.0,
            ]
        }
    }
}

/// Texel `t`'s tangent plane `d + g . (p - center)` at `p = (px, py)`.
pub(super) fn plane(t: &Texel, center: Vec2, px: f32, py: f32) -> f32 {
    t.d + (t.g.x * (px - center.x) + t.g.y * (py - center.y))
}

/// The slope used around a quad: the largest gradient magnitude among its texels (the
/// field's local rate of change; 1 for a distance field) with a 5% margin, at least 1 and at
/// most the field's global bound `slope`.
pub(super) fn quad_slope(quad: &[Texel; 4], slope: f32) -> f32 {
    let local = quad
        .iter()
        .map(|t| (t.g.x * t.g.x + t.g.y * t.g.y).sqrt())
        .fold(1.0f32, f32::max)
        * 1.05;
    local.min(slope)
}

/// The field changes by at most `slope` per world unit around the quad, so at `(px, py)` it
/// lies within `d_k +- slope |p - C_k|` of every quad texel: the planes' interpolant is
/// clamped into that interval. Where a texel certifies empty (or solid) space around it, no
/// plane can draw a phantom there.
pub(super) fn lipschitz_clamp(
    d: f32,
    quad: &[Texel; 4],
    centers: &[Vec2; 4],
    px: f32,
    py: f32,
    slope: f32,
) -> f32 {
    let (mut lo, mut hi) = (f32::NEG_INFINITY, f32::INFINITY);
    for (t, c) in quad.iter().zip(centers) {
        let (dx, dy) = (px - c.x, py - c.y);
        let reach = slope * (dx * dx + dy * dy).sqrt();
        lo = lo.max(t.d - reach);
        hi = hi.min(t.d + reach);
    }
    let crossed = lo > hi;
    if crossed {
        // Only f16 rounding of the texels can cross the bounds.
        return 0.5 * (lo + hi);
    }
    d.max(lo).min(hi)
}

/// Which quad texel's plane is lowest at `(px, py)` (the first on ties): in mode `planes`
/// the pixel takes that texel's material, the union's rule (the most-inside part wins)
/// extrapolated along the planes, instead of the nearest texel's blocky choice.
pub(super) fn lowest_plane(quad: &[Texel; 4], centers: &[Vec2; 4], px: f32, py: f32) -> usize {
    let mut best = 0;
    let mut lowest = plane(&quad[0], centers[0], px, py);
    for k in 1..4 {
        let v = plane(&quad[k], centers[k], px, py);
        if v < lowest {
            (best, lowest) = (k, v);
        }
    }
    best
}

/// The interpolated gradient, normalized (zero stays zero).
pub(super) fn normal(quad: &[Texel; 4], w: [f32; 4]) -> Vec2 {
    let g = Vec2::new(
        weighted4(w, quad.map(|t| t.g.x)),
        weighted4(w, quad.map(|t| t.g.y)),
    );
    unit_or(g, Vec2::ZERO)
}

/// `R_k` of the tangent-plane combination: plane `k` pulled up to the planes it diverges
/// from, then down to those it converges with (`m` ascending; zero weights skipped).
fn combined_plane(planes: &[f32; 4], blends: &Blends, k: usize) -> f32 {
    let mut r = planes[k];
    for (m, &a) in blends.grow[k].iter().enumerate() {
        if m != k && a > 0.0 {
            r += a * (r.max(planes[m]) - r);
        }
    }
    for (m, &b) in blends.shrink[k].iter().enumerate() {
        if m != k && b > 0.0 {
            r += b * (r.min(planes[m]) - r);
        }
    }
    r
}

/// The pixel at world point `p`, lattice coordinates `q`.
pub(super) fn pixel(tex: &Textures, p: Vec2, q: Vec2) -> PixelField {
    let x = axis_pos(q.x, tex.lattice.cols);
    let y = axis_pos(q.y, tex.lattice.rows);
    let quad = tex.quad(x.cell, y.cell);
    let w = bilinear_weights(x.frac, y.frac);
    let d = match (tex.mode, tex.filter) {
        (Reconstruction::Planes, _) => {
            let centers = tex.quad_centers(x.cell, y.cell);
            let planes = [0, 1, 2, 3].map(|k| plane(&quad[k], centers[k], p.x, p.y));
            let blends = tex.blends(x.cell, y.cell);
            let d = weighted4(w, [0, 1, 2, 3].map(|k| combined_plane(&planes, &blends, k)));
            lipschitz_clamp(d, &quad, &centers, p.x, p.y, quad_slope(&quad, tex.slope))
        }
        (_, Upsample::Bilinear) => weighted4(w, quad.map(|t| t.d)),
        (_, filter) => {
            let (wx, wy) = (cubic_weights(filter, x.frac), cubic_weights(filter, y.frac));
            let rows = tex
                .neighbourhood(x.cell, y.cell)
                .map(|row| weighted4(wx, row));
            weighted4(wy, rows)
        }
    };
    let material = match tex.mode {
        Reconstruction::Planes => {
            let centers = tex.quad_centers(x.cell, y.cell);
            quad[lowest_plane(&quad, &centers, p.x, p.y)].material
        }
        _ => {
            tex.texel(i64::from(x.nearest), i64::from(y.nearest))
                .material
        }
    };
    PixelField {
        d,
        normal: normal(&quad, w),
        material,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn axis_positions_clamp_to_the_lattice() {
        assert_eq!(
            axis_pos(3.25, 10),
            AxisPos {
                cell: 3,
                frac: 0.25,
                nearest: 3
            }
        );
        assert_eq!(axis_pos(3.5, 10).nearest, 4);
        let low = axis_pos(-2.0, 10);
        assert_eq!((low.cell, low.frac, low.nearest), (0, 0.0, 0));
        let high = axis_pos(42.0, 10);
        assert_eq!((high.cell, high.frac, high.nearest), (8, 1.0, 9));
    }

    #[test]
    fn filter_weights_sum_to_one_and_interpolate_or_approximate() {
        for t in [0.0, 0.2, 0.5, 0.9, 1.0] {
            for f in [Upsample::BSpline, Upsample::CatmullRom] {
                let w = cubic_weights(f, t);
                assert!((w.iter().sum::<f32>() - 1.0).abs() < 1e-6, "{f:?} {t}");
            }
        }
        // Catmull-Rom passes through the texels, the B-spline smooths them.
        assert_eq!(
            cubic_weights(Upsample::CatmullRom, 0.0),
            [0.0, 1.0, 0.0, 0.0]
        );
        let b = cubic_weights(Upsample::BSpline, 0.0);
        assert!((b[0] - 1.0 / 6.0).abs() < 1e-7 && (b[1] - 4.0 / 6.0).abs() < 1e-7);
    }

    #[test]
    fn diverging_planes_keep_a_thin_solid() {
        // Texels 0 and 2 left of a vertical 2-unit line at x = 8, texels 1 and 3 right of it.
        let t = |d: f32, gx: f32| Texel {
            d,
            g: Vec2::new(gx, 0.0),
            material: 0,
        };
        let planes_at = |px: f32| {
            let quad = [t(7.0, -1.0), t(7.0, 1.0), t(7.0, -1.0), t(7.0, 1.0)];
            let centers = [(0.0, 0.0), (16.0, 0.0), (0.0, -16.0), (16.0, -16.0)]
                .map(|(x, y)| Vec2::new(x, y));
            let planes = [0, 1, 2, 3].map(|k| plane(&quad[k], centers[k], px, -8.0));
            // Pairs across the line (0-1, 0-3, 2-1, 2-3) diverge fully.
            let grow = [
                [0.0, 1.0, 0.0, 1.0],
                [1.0, 0.0, 1.0, 0.0],
                [0.0, 1.0, 0.0, 1.0],
                [1.0, 0.0, 1.0, 0.0],
            ];
            let blends = Blends {
                grow,
                shrink: [[0.0; 4]; 4],
            };
            let w = bilinear_weights(px / 16.0, 0.5);
            weighted4(w, [0, 1, 2, 3].map(|k| combined_plane(&planes, &blends, k)))
        };
        assert_eq!(planes_at(8.0), -1.0);
        assert_eq!(planes_at(6.0), 1.0);
        assert_eq!(planes_at(11.0), 2.0);
    }
}
