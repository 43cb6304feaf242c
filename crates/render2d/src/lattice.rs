//! Where the reduced-scale texels sit: a world-anchored lattice covering the camera's view
//! plus the margin the later passes read.
//!
//! Texel centres lie on world multiples of the spacing `h = divisor * units_per_pixel`, so
//! panning the camera moves the picture without the sampled field swimming. Column `c` and
//! row `r` (rows go down, like image rows) are centred on the world point
//! `((i0 + c) * h, (j0 - r) * h)`. Lattice coordinates of a world point `p` are
//! `(p.x / h - i0, j0 - p.y / h)`: texel `(c, r)` sits at integer coordinates `(c, r)`.
//! The GPU renderer receives the same numbers in its uniforms (see `gpu::uniforms`).

use glam::Vec2;

use super::camera::{Camera, CameraError};
use super::options::Scale;

/// Texels kept beyond the view on every side: bicubic taps read 2 texels around a pixel,
/// reconstruction 1 more.
pub(crate) const MARGIN: i32 = 3;

/// The texel lattice of one camera at one scale.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lattice {
    /// World units between neighbouring texel centres.
    pub h: f32,
    /// World lattice index of column 0 (its centre is at `x = i0 * h`).
    pub i0: i32,
    /// World lattice index of row 0 (its centre is at `y = j0 * h`; rows go down).
    pub j0: i32,
    /// Columns.
    pub cols: u32,
    /// Rows.
    pub rows: u32,
}

impl Lattice {
    /// The lattice covering `camera`'s view plus `MARGIN` texels at `scale`.
    pub fn new(camera: &Camera, scale: Scale) -> Result<Lattice, CameraError> {
        camera.validate()?;
        let upp = camera.units_per_pixel;
        let h = upp * scale.divisor() as f32;
        let half = Vec2::new(camera.width as f32, camera.height as f32) * 0.5 * upp;
        let (min, max) = (camera.center - half, camera.center + half);
        let i_min = (min.x / h).floor() as i32 - MARGIN;
        let i_max = (max.x / h).ceil() as i32 + MARGIN;
        let j_min = (min.y / h).floor() as i32 - MARGIN;
        let j_max = (max.y / h).ceil() as i32 + MARGIN;
        Ok(Lattice {
            h,
            i0: i_min,
            j0: j_max,
            cols: (i_max - i_min + 1) as u32,
            rows: (j_max - j_min + 1) as u32,
        })
    }

    /// The most columns and rows any camera of this image size and scale can need (for
    /// allocating textures once per resize).
    pub fn max_dims(width: u32, height: u32, scale: Scale) -> (u32, u32) {
        let s = scale.divisor();
        let span = |px: u32| px.div_ceil(s) + 2 + 2 * MARGIN as u32;
        (span(width), span(height))
    }

    /// World position of texel `(col, row)`'s centre.
    pub fn texel_center(&self, col: u32, row: u32) -> Vec2 {
        Vec2::new(
            (self.i0 + col as i32) as f32 * self.h,
            (self.j0 - row as i32) as f32 * self.h,
        )
    }

    /// Lattice coordinates of world point `p` (texel `(c, r)` is at `(c, r)`).
    pub fn to_lattice(&self, p: Vec2) -> Vec2 {
        Vec2::new(p.x / self.h - self.i0 as f32, self.j0 as f32 - p.y / self.h)
    }

    /// Number of texels.
    pub fn len(&self) -> usize {
        self.cols as usize * self.rows as usize
    }

    /// Whether the lattice has no texels (never true for a lattice from [`Lattice::new`]).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera(center: Vec2, upp: f32, w: u32, h: u32) -> Camera {
        Camera {
            center,
            units_per_pixel: upp,
            width: w,
            height: h,
        }
    }

    #[test]
    fn covers_the_view_with_margin_and_fits_max_dims() {
        for (c, upp) in [
            (Vec2::new(0.0, 0.0), 1.0),
            (Vec2::new(1234.5, -77.25), 1.0),
            (Vec2::new(-5000.3, 800.9), 2.5),
        ] {
            for scale in Scale::ALL {
                let cam = camera(c, upp, 1920, 1080);
                let l = Lattice::new(&cam, scale).unwrap();
                let (mc, mr) = Lattice::max_dims(1920, 1080, scale);
                assert!(
                    l.cols <= mc && l.rows <= mr,
                    "{scale:?}: {l:?} vs {mc}x{mr}"
                );
                for (x, y) in [(0, 0), (1919, 1079), (0, 1079), (1919, 0)] {
                    let q = l.to_lattice(cam.pixel_to_world(x, y));
                    let m = MARGIN as f32 - 1.0;
                    assert!(q.x >= m && q.y >= m, "{q}");
                    assert!(q.x <= l.cols as f32 - 1.0 - m && q.y <= l.rows as f32 - 1.0 - m);
                }
                let p = l.texel_center(5, 7);
                assert!((l.to_lattice(p) - Vec2::new(5.0, 7.0)).abs().max_element() < 1e-3);
            }
        }
    }

    #[test]
    fn rejects_absurd_cameras() {
        let ok = camera(Vec2::ZERO, 1.0, 64, 64);
        assert!(Lattice::new(&ok, Scale::Sixteenth).is_ok());
        for bad in [
            camera(Vec2::ZERO, 1.0, 0, 64),
            camera(Vec2::ZERO, 1.0, 64, 100_000),
            camera(Vec2::new(f32::NAN, 0.0), 1.0, 64, 64),
            camera(Vec2::ZERO, 0.0, 64, 64),
            camera(Vec2::ZERO, f32::INFINITY, 64, 64),
            camera(Vec2::ZERO, 1.0e9, 64, 64),
        ] {
            assert!(Lattice::new(&bad, Scale::Sixteenth).is_err(), "{bad:?}");
        }
    }
}
