//! How far a picture's interior shade is from the exact render's, and whether its errors
//! step at the `4 x 4` blocks that mode `refine` proves: one measure for the twin
//! (`tests/render_refine.rs`) and the GPU (`tests/gpu_render.rs`).

/// How far the interior shade of a picture is from the exact render's, over the pixels
/// the exact field puts deeper than the outline (there only the depth shade may differ).
#[derive(Debug, Default)]
pub(crate) struct ShadeSteps {
    /// Pixels deeper than the outline.
    pub(crate) solid: usize,
    /// Of those, pixels more than 8 levels from the exact colour.
    pub(crate) off: usize,
    /// Neighbouring pixel pairs of them whose error (picture minus exact) changes by more
    /// than 8 levels from one to the other, across the edge of a `4 x 4` block aligned
    /// with the image and inside one.
    pub(crate) edge_steps: usize,
    pub(crate) inner_steps: usize,
    /// All neighbouring pairs across block edges and inside blocks.
    pub(crate) edge_pairs: usize,
    pub(crate) inner_pairs: usize,
}

impl ShadeSteps {
    /// Whether the shade steps at blocks: more than 10 + 0.01% of the interior pixels off by
    /// more than 8 levels, or the error jumping across block edges more than twice as often
    /// as inside blocks (ten jumps of slack).
    pub(crate) fn stepped(&self) -> bool {
        let inner_rate = self.inner_steps as f64 / self.inner_pairs.max(1) as f64;
        let jumps = self.edge_steps as f64 > 2.0 * inner_rate * self.edge_pairs as f64 + 10.0;
        self.off > 10 + self.solid / 10_000 || jumps
    }
}

/// The errors of `image` against `exact` where `depth_px` (the exact distance, pixels) is
/// below `deep_px` (see [`ShadeSteps`]).
pub(crate) fn shade_steps(
    image: &image::RgbaImage,
    exact: &image::RgbaImage,
    depth_px: &[f32],
    deep_px: f32,
) -> ShadeSteps {
    let (w, h) = (image.width() as usize, image.height() as usize);
    let err = |x: usize, y: usize| {
        let (a, b) = (
            image.get_pixel(x as u32, y as u32),
            exact.get_pixel(x as u32, y as u32),
        );
        [0, 1, 2].map(|c| i32::from(a[c]) - i32::from(b[c]))
    };
    let solid = |x: usize, y: usize| depth_px[y * w + x] < deep_px;
    let mut s = ShadeSteps::default();
    for y in 0..h {
        for x in 0..w {
            if !solid(x, y) {
                continue;
            }
            let e = err(x, y);
            s.solid += 1;
            s.off += usize::from(e.iter().any(|v| v.abs() > 8));
            for (nx, ny, edge) in [(x + 1, y, (x + 1) % 4 == 0), (x, y + 1, (y + 1) % 4 == 0)] {
                if nx >= w || ny >= h || !solid(nx, ny) {
                    continue;
                }
                let f = err(nx, ny);
                let step = (0..3).any(|c| (e[c] - f[c]).abs() > 8);
                if edge {
                    s.edge_pairs += 1;
                    s.edge_steps += usize::from(step);
                } else {
                    s.inner_pairs += 1;
                    s.inner_steps += usize::from(step);
                }
            }
        }
    }
    s
}
