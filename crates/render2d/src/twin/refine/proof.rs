//! The proof of one pixel block: from the quad's four texels, the slope bounds and the
//! events of the cells it touches, is the block all sky, all solid of a proven material,
//! or uncertain (evaluated at every pixel)? Also the crease rule that sends a square of
//! a shaded solid block back to exact evaluation.

use glam::Vec2;

use super::cells::{Cells, Quad, QuadBounds};
use crate::options::ShadeOptions;
use crate::twin::LowRes;
use crate::twin::shade::Shader;
use craterfield_field::terrain::RectSign;
use craterfield_field::{MaterialId, Sample, Sdf, Terrain};

/// Side of the pixel blocks that are proven or refined, pixels.
pub const BLOCK: usize = 4;

/// The material proof of a solid block.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Material {
    /// One material for every pixel.
    One(MaterialId),
    /// Each pixel's grid cell has a constant material.
    PerCell,
}

/// What a block is proven to be.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Class {
    Sky {
        lo: f32,
    },
    Solid {
        hi: f32,
        material: Material,
        /// Whether the block reaches depths whose shade depends on the distance: it is then
        /// shaded from exact samples on the corner grid instead of the texels.
        shaded: bool,
    },
    Uncertain,
}

/// The event sign of a whole quad, computed once the first block needs it.
pub(super) type QuadSign = Option<RectSign>;

/// Everything the proofs of one frame read, and their thresholds.
pub(super) struct Prover<'a, F: Sdf> {
    pub(super) cells: Cells<'a, F>,
    upp: f32,
    sky_at: f32,
    solid_at: f32,
    /// Deeper than this every solid pixel of a material and row has one colour.
    pub(super) deep_at: f32,
    /// Shallower than this the shade depends on the normal (the lit rim).
    lit_at: f32,
    /// Classify nothing: every block is evaluated (the full-resolution direct renderer).
    exact_only: bool,
}

impl<'a, F: Sdf> Prover<'a, F> {
    pub(super) fn new(
        terrain: &'a Terrain<F>,
        lowres: &'a LowRes,
        upp: f32,
        shade: &ShadeOptions,
        exact_only: bool,
    ) -> Self {
        Prover {
            cells: Cells::new(terrain, lowres),
            upp,
            sky_at: 0.5 * upp,
            solid_at: -(shade.outline_px.max(0.0) + 0.5) * upp,
            deep_at: -Shader::new(shade, 1).interior_depth() * upp,
            lit_at: -0.5 * shade.shade_depth_px * upp,
            exact_only,
        }
    }

    /// The proof of the block with pixel-centre rectangle `rect` (`[x0, y0, x1, y1]`) in
    /// `quad`, whose bounds are `bounds`.
    pub(super) fn classify(
        &self,
        quad: &Quad,
        bounds: QuadBounds,
        rect: [f32; 4],
        quad_sign: &mut QuadSign,
    ) -> Class {
        if self.exact_only || !(bounds.lipschitz.is_finite() && bounds.jump.is_finite()) {
            return Class::Uncertain;
        }
        let (mut lo, mut hi) = (f32::NEG_INFINITY, f32::INFINITY);
        let mut far = [0.0f32; 4];
        for (k, far_k) in far.iter_mut().enumerate() {
            *far_k = farthest_corner(quad.centers[k], rect);
            let d = quad.d[k];
            let reach = bounds.lipschitz * *far_k * (1.0 + 1.0e-5)
                + bounds.jump
                + d.abs() / 1024.0
                + self.upp / 1000.0;
            lo = lo.max(d - reach);
            hi = hi.min(d + reach);
        }
        if lo >= self.sky_at {
            return Class::Sky { lo };
        }
        let solid = matches!(
            hi.partial_cmp(&self.solid_at),
            Some(std::cmp::Ordering::Less | std::cmp::Ordering::Equal)
        );
        if !solid {
            let whole = *quad_sign.get_or_insert_with(|| self.event_sign(quad_sign_rect(quad)));
            let sign = match whole {
                RectSign::Unknown => self.event_sign(rect),
                proven => proven,
            };
            match sign {
                RectSign::Above => return Class::Sky { lo: self.sky_at },
                RectSign::Below => hi = self.solid_at,
                RectSign::Unknown => return Class::Uncertain,
            }
        }
        match self.material(quad, rect, far) {
            Some(material) => Class::Solid {
                hi,
                material,
                shaded: hi > self.deep_at,
            },
            None => Class::Uncertain,
        }
    }

    /// What the events of the cells `rect` touches force over it (all must agree).
    fn event_sign(&self, rect: [f32; 4]) -> RectSign {
        let cells = &self.cells;
        let [x0, y0, x1, y1] = rect;
        let (ix0, ix1) = cells.cell_span(x0, x1, 0);
        let (iy0, iy1) = cells.cell_span(y0, y1, 1);
        let inside = ix0 >= 0 && iy0 >= 0 && ix1 < cells.dims[0] && iy1 < cells.dims[1];
        let band = cells.terrain.options().band;
        if !inside || self.sky_at > band || self.solid_at < -band {
            return RectSign::Unknown;
        }
        let (min, max) = (Vec2::new(x0, y0), Vec2::new(x1, y1));
        let mut agreed = None;
        for iy in iy0..=iy1 {
            for ix in ix0..=ix1 {
                let cell = cells.index(ix, iy);
                let sign = match cells.discs(cell) {
                    Some(discs) => {
                        cells
                            .terrain
                            .rect_sign_of(discs, min, max, self.sky_at, self.solid_at)
                    }
                    None => RectSign::Unknown,
                };
                match (sign, agreed) {
                    (RectSign::Unknown, _) => return RectSign::Unknown,
                    (s, Some(a)) if s != a => return RectSign::Unknown,
                    (s, _) => agreed = Some(s),
                }
            }
        }
        agreed.unwrap_or(RectSign::Unknown)
    }

    /// The material proof of a block (see the `refine` module doc); `far[k]` is the largest
    /// distance from texel `k` to the block.
    fn material(&self, quad: &Quad, rect: [f32; 4], far: [f32; 4]) -> Option<Material> {
        let cells = &self.cells;
        let [x0, y0, x1, y1] = rect;
        let (ix0, ix1) = cells.cell_span(x0, x1, 0);
        let (iy0, iy1) = cells.cell_span(y0, y1, 1);
        let mut first = None;
        let mut all_same = true;
        let mut all_constant = true;
        'cells: for iy in iy0..=iy1 {
            for ix in ix0..=ix1 {
                match (cells.cell(ix, iy).material, first) {
                    (None, _) => {
                        all_constant = false;
                        break 'cells;
                    }
                    (Some(m), None) => first = Some(m),
                    (Some(m), Some(f)) => all_same &= m == f,
                }
            }
        }
        if all_constant {
            return Some(match first {
                Some(m) if all_same => Material::One(m),
                _ => Material::PerCell,
            });
        }
        if ix0 != ix1 || iy0 != iy1 {
            return None;
        }
        let cell = cells.cell(ix0, iy0);
        let index = cells.index(ix0, iy0);
        // The margin's switch functions have slope at most `L + 1`.
        let slope = cell.lipschitz.max(1.0) * 2.0;
        (0..4).find_map(|k| {
            let c = quad.centers[k];
            let same_cell = cells.cell_span(c.x, c.x, 0) == (ix0, ix0)
                && cells.cell_span(c.y, c.y, 1) == (iy0, iy0)
                && cells.grid.cell_index(c) == Some(index);
            let needed = slope * far[k] * (1.0 + 1.0e-5) + self.upp / 1000.0;
            (same_cell && needed < cells.margin(quad.texels[k]))
                .then_some(Material::One(quad.materials[k]))
        })
    }

    /// The material of pixel `p` of a block proven with `material` (`None`: the cell lookup
    /// disagreed with the proof, so the pixel is evaluated instead).
    pub(super) fn pixel_material(&self, material: Material, p: Vec2) -> Option<MaterialId> {
        match material {
            Material::One(m) => Some(m),
            Material::PerCell => self.cells.material_at(p),
        }
    }

    /// Whether a grid square with the exact samples `s` at its corners must be evaluated
    /// rather than interpolated: some corner lies in the lit rim and two corners' normals
    /// differ by more than [`CREASE`]. The interpolant is smooth, the exact shade is not
    /// where the normal jumps: at the contour where the distance reaches its clamp `-M`
    /// (past it the gradient is zero, so zoomed out, where the band is shallower than the
    /// rim, the rim stops there with a hard edge) and along creases (where the nearest
    /// surface changes, e.g. under the peak between two craters). Interpolated across, such
    /// edges become steps along the squares.
    pub(super) fn creased(&self, s: &[Sample; 4]) -> bool {
        if !s.iter().any(|s| s.distance > self.lit_at) {
            return false;
        }
        let n = s.map(|s| s.gradient.normalize_or_zero());
        (0..4).any(|a| (a + 1..4).any(|b| (n[a] - n[b]).length_squared() > CREASE * CREASE))
    }
}

/// The largest difference between the unit normals (zero where the gradient is) at the
/// corners of a grid square that is interpolated: about 23 degrees, so that the lit term
/// `0.35 dot(n, light)` of an interpolated pixel is within about 7% of the base colour.
const CREASE: f32 = 0.4;

/// The distance from `c` to the farthest corner of `rect` (`[x0, y0, x1, y1]`): the corner
/// with the larger offset on each axis, whose rounded distance is also the largest of the
/// four corners' rounded distances (squares and sums round monotonically).
fn farthest_corner(c: Vec2, rect: [f32; 4]) -> f32 {
    let [x0, y0, x1, y1] = rect;
    let dx = (x0 - c.x).abs().max((x1 - c.x).abs());
    let dy = (y0 - c.y).abs().max((y1 - c.y).abs());
    (dx * dx + dy * dy).sqrt()
}

/// The rectangle of a quad's texel square (it holds every pixel centre of the quad).
fn quad_sign_rect(quad: &Quad) -> [f32; 4] {
    let [c0, _, _, c3] = quad.centers;
    [
        c0.x.min(c3.x),
        c0.y.min(c3.y),
        c0.x.max(c3.x),
        c0.y.max(c3.y),
    ]
}
