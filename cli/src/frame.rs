//! One frame of a match as a picture: the terrain by the exact renderer, then the bodies
//! drawn over it as anti-aliased shapes (vehicles as capsules in their player's colour
//! with a health bar, projectiles as small dots, debris grey).

use craterfield::field2d::Level;
use craterfield::render2d::{
    Camera, ExactRenderOptions, MAX_IMAGE_PIXELS, MAX_IMAGE_SIDE, render_exact,
};
use craterfield::sim::{Body, BodyKind, World};
use glam::Vec2;
use image::RgbaImage;

/// Player colours, by player index (wrapping).
pub(crate) const PLAYER_COLORS: [[u8; 3]; 8] = [
    [230, 60, 50],
    [50, 120, 235],
    [250, 200, 40],
    [150, 70, 210],
    [40, 190, 170],
    [240, 130, 30],
    [235, 90, 170],
    [120, 210, 60],
];

const DEBRIS: [u8; 3] = [150, 150, 150];
const DEBRIS_EDGE: [u8; 3] = [80, 80, 84];
const OUTLINE: [u8; 3] = [20, 20, 24];

/// The camera a frame of `level` is drawn with: the level's bounds in an image `width`
/// pixels wide, the height following the aspect ratio. An image the renderers refuse
/// (a tall or thin level, or a width too large) is an error that says which width fits.
pub(crate) fn camera(level: &Level, width: u32) -> Result<Camera, String> {
    let b = level.bounds();
    let camera = Camera::fit(b.min, b.max, width);
    camera.validate().map_err(|e| {
        let size = b.max - b.min;
        let fits = Camera::fit_within(b.min, b.max, MAX_IMAGE_SIDE, MAX_IMAGE_SIDE);
        let budget = (MAX_IMAGE_PIXELS as f64 * f64::from(size.x / size.y)).sqrt();
        let widest = fits.width.min(budget.floor() as u32);
        format!(
            "cannot draw level \"{}\" ({} x {} units) {width} pixels wide: {e}; at most {widest} pixels wide fits",
            level.name(),
            size.x,
            size.y
        )
    })?;
    Ok(camera)
}

/// The world as `world` holds it now, in an image `width` pixels wide (see [`camera`]).
pub(crate) fn render(level: &Level, world: &World, width: u32) -> Result<RgbaImage, String> {
    let camera = camera(level, width)?;
    let palette: Vec<[u8; 3]> = level.materials().iter().map(|m| m.color).collect();
    let mut img = render_exact(
        world.terrain(),
        &palette,
        &camera,
        &ExactRenderOptions::default(),
    )
    .map_err(|e| e.to_string())?;
    let max_health = world.settings().vehicle.health.max(1);
    let mut canvas = Canvas {
        img: &mut img,
        camera: &camera,
    };
    // Debris first, then vehicles, then projectiles on top.
    for body in world.bodies() {
        if matches!(body.kind, BodyKind::Debris) {
            canvas.body(body, 1.0, DEBRIS, DEBRIS_EDGE, 0.6);
        }
    }
    for body in world.bodies() {
        if let Some(player) = body.player() {
            let color = PLAYER_COLORS[usize::from(player) % PLAYER_COLORS.len()];
            canvas.body(body, 3.0, color, OUTLINE, 1.2);
            canvas.health_bar(body, body.health as f32 / max_health as f32);
        }
    }
    for body in world.bodies() {
        if let BodyKind::Projectile { owner, .. } = body.kind {
            let color = PLAYER_COLORS[usize::from(owner) % PLAYER_COLORS.len()];
            canvas.body(body, 2.0, color, OUTLINE, 0.8);
        }
    }
    Ok(img)
}

struct Canvas<'a> {
    img: &'a mut RgbaImage,
    camera: &'a Camera,
}

impl Canvas<'_> {
    /// A body's capsule (or circle), at least `min_radius_px` thick, filled with `fill`
    /// inside an `edge_px` wide rim of `edge`.
    fn body(
        &mut self,
        body: &Body,
        min_radius_px: f32,
        fill: [u8; 3],
        edge: [u8; 3],
        edge_px: f32,
    ) {
        let (a, b) = body.segment();
        let upp = self.camera.units_per_pixel;
        let radius = (body.radius / upp).max(min_radius_px);
        let a = self.camera.world_to_pixel(a);
        let b = self.camera.world_to_pixel(b);
        self.shape(a, b, radius, |d| {
            // `d` is the signed distance in pixels (negative inside).
            let inner = (-d - edge_px + 0.5).clamp(0.0, 1.0);
            (mix(edge, fill, inner), (0.5 - d).clamp(0.0, 1.0))
        });
    }

    /// A two-pixel bar above a vehicle: green for the health left, dark for the rest.
    fn health_bar(&mut self, body: &Body, fraction: f32) {
        let upp = self.camera.units_per_pixel;
        let centre = self.camera.world_to_pixel(body.pos);
        let reach = (body.bounding_radius() / upp).max(3.0);
        let half = reach.max(6.0);
        let y = centre.y - reach - 4.0;
        let split = -half + 2.0 * half * fraction.clamp(0.0, 1.0);
        let green = [70, 220, 90];
        let empty = [40, 40, 40];
        self.shape(
            Vec2::new(centre.x - half, y),
            Vec2::new(centre.x + half, y),
            1.0,
            |d| ([0u8; 3], (0.5 - d).clamp(0.0, 1.0)),
        );
        // The bar's colours, drawn as a thinner line over the dark backing.
        let x_split = centre.x + split;
        self.shape(
            Vec2::new(centre.x - half, y),
            Vec2::new(x_split.max(centre.x - half), y),
            0.6,
            |d| (green, (0.5 - d).clamp(0.0, 1.0)),
        );
        if fraction < 1.0 {
            self.shape(
                Vec2::new(x_split, y),
                Vec2::new(centre.x + half, y),
                0.6,
                |d| (empty, (0.5 - d).clamp(0.0, 1.0)),
            );
        }
    }

    /// Blends `shade(signed distance)` = (colour, coverage) over every pixel near the
    /// segment `a..b` (pixel coordinates) thickened by `radius` pixels.
    fn shape(&mut self, a: Vec2, b: Vec2, radius: f32, shade: impl Fn(f32) -> ([u8; 3], f32)) {
        let (w, h) = self.img.dimensions();
        let lo = a.min(b) - Vec2::splat(radius + 1.0);
        let hi = a.max(b) + Vec2::splat(radius + 1.0);
        if !(hi.x >= 0.0 && hi.y >= 0.0 && lo.x < w as f32 && lo.y < h as f32) {
            return;
        }
        let x0 = lo.x.max(0.0) as u32;
        let y0 = lo.y.max(0.0) as u32;
        let x1 = (hi.x.ceil() as u32).min(w - 1);
        let y1 = (hi.y.ceil() as u32).min(h - 1);
        let ab = b - a;
        let len2 = ab.length_squared();
        for y in y0..=y1 {
            for x in x0..=x1 {
                let p = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
                let t = if len2 > 0.0 {
                    ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                let d = (p - (a + ab * t)).length() - radius;
                let (color, coverage) = shade(d);
                if coverage <= 0.0 {
                    continue;
                }
                let px = self.img.get_pixel_mut(x, y);
                let under = [px.0[0], px.0[1], px.0[2]];
                let c = mix(under, color, coverage);
                px.0 = [c[0], c[1], c[2], 255];
            }
        }
    }
}

fn mix(a: [u8; 3], b: [u8; 3], t: f32) -> [u8; 3] {
    let t = t.clamp(0.0, 1.0);
    [0, 1, 2].map(|i| (a[i] as f32 + (b[i] as f32 - a[i] as f32) * t).round() as u8)
}

/// Counts of the bodies by kind: (vehicles, projectiles, debris).
pub(crate) fn census(world: &World) -> (usize, usize, usize) {
    let mut n = (0, 0, 0);
    for b in world.bodies() {
        match b.kind {
            BodyKind::Vehicle { .. } => n.0 += 1,
            BodyKind::Projectile { .. } => n.1 += 1,
            BodyKind::Debris => n.2 += 1,
        }
    }
    n
}

#[cfg(test)]
mod tests {
    use super::*;
    use craterfield::sim::Settings;

    #[test]
    fn bodies_are_drawn_in_their_colours() {
        let level = Level::default_level();
        let mut world = World::new(&level, Settings::default(), 2).unwrap();
        let rock = Vec2::new(1900.0, 1400.0);
        world.add_debris(rock, 24.0).unwrap();
        let img = render(&level, &world, 960).unwrap();
        let camera = Camera::fit(level.bounds().min, level.bounds().max, 960);
        let at = |p: Vec2| {
            let q = camera.world_to_pixel(p);
            let px = img.get_pixel(q.x as u32, q.y as u32).0;
            [px[0], px[1], px[2]]
        };
        assert_eq!(at(rock), DEBRIS);
        let v0 = world.vehicle(0).unwrap().pos;
        assert_eq!(at(v0), PLAYER_COLORS[0]);
        let v1 = world.vehicle(1).unwrap().pos;
        assert_eq!(at(v1), PLAYER_COLORS[1]);
        assert_eq!(census(&world), (2, 0, 1));
    }
}
