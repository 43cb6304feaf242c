//! Vector overlays drawn over a rendered image with tiny-skia: markers for spawn points and
//! other world positions.

use glam::Vec2;
use image::RgbaImage;
use tiny_skia::{Color, FillRule, Paint, PathBuilder, PixmapMut, Stroke, Transform};

use super::camera::Camera;

/// Draw a ring marker of `radius_px` at each world point. Points outside the image are
/// skipped. Returns how many were drawn.
pub fn draw_markers(
    img: &mut RgbaImage,
    camera: &Camera,
    points: &[Vec2],
    radius_px: f32,
    rgb: [u8; 3],
) -> usize {
    let (w, h) = img.dimensions();
    // The image is opaque, so straight and premultiplied RGBA coincide.
    let Some(mut pixmap) = PixmapMut::from_bytes(img.as_mut(), w, h) else {
        return 0;
    };
    let mut paint = Paint::default();
    paint.set_color(Color::from_rgba8(rgb[0], rgb[1], rgb[2], 255));
    paint.anti_alias = true;
    let stroke = Stroke {
        width: (radius_px * 0.35).max(1.0),
        ..Stroke::default()
    };
    let mut drawn = 0;
    for p in points {
        let q = camera.world_to_pixel(*p);
        if !(q.x >= 0.0 && q.y >= 0.0 && q.x < w as f32 && q.y < h as f32) {
            continue;
        }
        let Some(circle) = PathBuilder::from_circle(q.x, q.y, radius_px) else {
            continue;
        };
        pixmap.stroke_path(&circle, &paint, &stroke, Transform::identity(), None);
        if let Some(dot) = PathBuilder::from_circle(q.x, q.y, radius_px * 0.3) {
            pixmap.fill_path(&dot, &paint, FillRule::Winding, Transform::identity(), None);
        }
        drawn += 1;
    }
    drawn
}
