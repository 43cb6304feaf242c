//! The 2D camera: which world rectangle maps onto which pixels.

use glam::Vec2;
use serde::{Deserialize, Serialize};
use thiserror::Error;

/// Largest image side the renderers accept, pixels.
pub const MAX_IMAGE_SIDE: u32 = 16_384;
/// Most pixels in one image the renderers accept (256 MiB of RGBA).
pub const MAX_IMAGE_PIXELS: u64 = 64 * 1024 * 1024;

/// Why a camera cannot be rendered.
#[derive(Clone, Copy, Debug, PartialEq, Error)]
#[non_exhaustive]
pub enum CameraError {
    /// The image is empty, wider or taller than [`MAX_IMAGE_SIDE`], or holds more than
    /// [`MAX_IMAGE_PIXELS`] pixels.
    #[error(
        "image size {width}x{height} must be between 1x1 and {MAX_IMAGE_SIDE}x{MAX_IMAGE_SIDE} with at most {MAX_IMAGE_PIXELS} pixels"
    )]
    BadSize {
        /// Width, pixels.
        width: u32,
        /// Height, pixels.
        height: u32,
    },
    /// The camera centre is NaN or infinite.
    #[error("camera center {center} must be finite")]
    BadCenter {
        /// The centre.
        center: Vec2,
    },
    /// The zoom is not a positive finite number, or puts the view beyond `f32` range.
    #[error(
        "camera units_per_pixel = {value} must be positive, finite and keep the view within +-1e7 world units"
    )]
    BadZoom {
        /// The zoom.
        value: f32,
    },
}

/// An orthographic view: world y is up, pixel y is down.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Camera {
    /// World point at the centre of the image.
    pub center: Vec2,
    /// World units per pixel (1 at the default zoom).
    pub units_per_pixel: f32,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
}

impl Camera {
    /// A camera showing the world rectangle `min..max` in an image `width` pixels wide (the
    /// height follows the aspect ratio). Nothing is checked: a tall rectangle may need an
    /// image taller than any renderer accepts ([`Camera::validate`] says so), where
    /// [`Camera::fit_within`] keeps to a size.
    pub fn fit(min: Vec2, max: Vec2, width: u32) -> Camera {
        let size = max - min;
        let width = width.max(1);
        let units_per_pixel = size.x / width as f32;
        let height = ((size.y / units_per_pixel).round() as u32).max(1);
        Camera {
            center: (min + max) * 0.5,
            units_per_pixel,
            width,
            height,
        }
    }

    /// The largest camera showing `min..max` whole, with square pixels, in an image of at
    /// most `max_width x max_height` pixels (each at least 1): the aspect ratio decides
    /// which side is full.
    pub fn fit_within(min: Vec2, max: Vec2, max_width: u32, max_height: u32) -> Camera {
        let size = max - min;
        let (max_w, max_h) = (max_width.max(1), max_height.max(1));
        let by_width = size.x / max_w as f32;
        let by_height = size.y / max_h as f32;
        if by_width >= by_height || !by_height.is_finite() {
            return Camera::fit(min, max, max_w);
        }
        let width = ((size.x / by_height).round() as u32).clamp(1, max_w);
        Camera {
            center: (min + max) * 0.5,
            units_per_pixel: by_height,
            width,
            height: max_h,
        }
    }

    /// Checks the size (see [`MAX_IMAGE_SIDE`] and [`MAX_IMAGE_PIXELS`]), the centre and the
    /// zoom: every renderer calls it before allocating anything for the image.
    pub fn validate(&self) -> Result<(), CameraError> {
        let (w, h) = (self.width, self.height);
        let pixels = u64::from(w) * u64::from(h);
        if w == 0 || h == 0 || w > MAX_IMAGE_SIDE || h > MAX_IMAGE_SIDE || pixels > MAX_IMAGE_PIXELS
        {
            return Err(CameraError::BadSize {
                width: w,
                height: h,
            });
        }
        if !self.center.is_finite() {
            return Err(CameraError::BadCenter {
                center: self.center,
            });
        }
        let upp = self.units_per_pixel;
        let reach = self.center.abs().max_element() + upp * w.max(h) as f32 * 32.0;
        if !(upp.is_finite() && upp > 0.0 && reach <= 1.0e7) {
            return Err(CameraError::BadZoom { value: upp });
        }
        Ok(())
    }

    /// World position of the centre of pixel `(x, y)`.
    pub fn pixel_to_world(&self, x: u32, y: u32) -> Vec2 {
        let half = Vec2::new(self.width as f32, self.height as f32) * 0.5;
        let offset = Vec2::new(x as f32 + 0.5 - half.x, half.y - (y as f32 + 0.5));
        self.center + offset * self.units_per_pixel
    }

    /// Pixel coordinates (continuous, y down) of a world point.
    pub fn world_to_pixel(&self, p: Vec2) -> Vec2 {
        let half = Vec2::new(self.width as f32, self.height as f32) * 0.5;
        let d = (p - self.center) / self.units_per_pixel;
        Vec2::new(half.x + d.x, half.y - d.y)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_of_every_aspect_ratio_are_checked_before_anything_is_allocated() {
        let (min, max) = (Vec2::ZERO, Vec2::new(4096.0, 1024.0));
        assert!(Camera::fit(min, max, 1920).validate().is_ok());
        // Past the pixel budget without a side past its limit, past a side, and empty.
        for (w, h) in [
            (12_800, 5_333),
            (16_384, 4_097),
            (16_385, 1),
            (1, 16_385),
            (0, 10),
        ] {
            let cam = Camera {
                width: w,
                height: h,
                ..Camera::fit(min, max, 64)
            };
            assert_eq!(
                cam.validate(),
                Err(CameraError::BadSize {
                    width: w,
                    height: h
                })
            );
        }
        // Tall and wide rectangles fitted into a box keep their aspect ratio and fit it.
        for size in [
            Vec2::new(16.0, 131_072.0),
            Vec2::new(131_072.0, 16.0),
            Vec2::new(3.0, 2.0),
            Vec2::new(2.0, 3.0),
        ] {
            let cam = Camera::fit_within(Vec2::ZERO, size, 4096, 2048);
            assert!(cam.width <= 4096 && cam.height <= 2048, "{cam:?}");
            assert!(cam.width == 4096 || cam.height == 2048, "{cam:?}");
            let aspect = cam.width as f32 / cam.height as f32;
            let want = size.x / size.y;
            let tolerance = 1.0 / cam.width.min(cam.height) as f32 + 1e-3;
            // Rounding one side to whole pixels; a side of one pixel is as thin as it gets.
            let thin = cam.width == 1 || cam.height == 1;
            assert!(
                thin || (aspect / want - 1.0).abs() <= tolerance,
                "{size}: {cam:?}"
            );
            assert!(cam.validate().is_ok(), "{cam:?}");
        }
    }

    #[test]
    fn centres_and_zooms_outside_f32_comfort_are_refused() {
        let ok = Camera::fit(Vec2::ZERO, Vec2::splat(100.0), 100);
        let nan = Camera {
            center: Vec2::new(f32::NAN, 0.0),
            ..ok
        };
        assert!(matches!(nan.validate(), Err(CameraError::BadCenter { .. })));
        for upp in [0.0, -1.0, f32::INFINITY, f32::NAN, 1e9] {
            let cam = Camera {
                units_per_pixel: upp,
                ..ok
            };
            assert!(
                matches!(cam.validate(), Err(CameraError::BadZoom { .. })),
                "{upp}"
            );
        }
    }
}
