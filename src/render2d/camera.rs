//! The 2D camera: which world rectangle maps onto which pixels.

use glam::Vec2;
use serde::{Deserialize, Serialize};

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
    /// height follows the aspect ratio).
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
