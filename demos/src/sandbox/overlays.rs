//! What the sandbox paints over the terrain picture: the bodies (vehicles, projectiles,
//! debris, the human's aim) and the optional overlays: the reduced-scale texel grid, the
//! explosion-grid cells with their event lists and bricks, and each body's last contact
//! (nearest surface point and normal).

use craterfield::render2d::{Lattice, RenderOptions};
use craterfield::sim::BodyKind;
use egui::{Color32, Painter, Stroke};
use glam::Vec2;

use super::session::Session;
use super::view::{Screen, View};

/// Which overlays are on.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Overlays {
    /// The reduced-scale lattice's texel boundaries.
    pub texels: bool,
    /// The CPU twin's refine picture with exactly evaluated pixels tinted red.
    pub refine: bool,
    /// Explosion-grid cells: event lists shaded by length, brick cells outlined.
    pub cells: bool,
    /// Nearest surface point and normal of every body's last contact check.
    pub contacts: bool,
    /// Exactly evaluated pixels of the last refine overlay.
    pub refined_pixels: Option<u64>,
}

/// Player colours (player 0 is the human).
const PLAYER_COLORS: [Color32; 4] = [
    Color32::from_rgb(250, 210, 60),
    Color32::from_rgb(230, 80, 70),
    Color32::from_rgb(90, 200, 120),
    Color32::from_rgb(120, 150, 250),
];

/// Paints the overlays that are on.
pub(super) fn paint_overlays(
    painter: &Painter,
    overlays: &Overlays,
    session: &Session,
    view: &View,
    screen: &Screen,
    options: &RenderOptions,
) {
    if overlays.cells {
        paint_cells(painter, session, view, screen);
    }
    if overlays.texels {
        paint_texels(painter, view, screen, options);
    }
    if overlays.contacts {
        paint_contacts(painter, session, view, screen);
    }
}

fn paint_texels(painter: &Painter, view: &View, screen: &Screen, options: &RenderOptions) {
    let camera = view.camera(screen.pixels());
    let Ok(lattice) = Lattice::new(&camera, options.scale) else {
        return;
    };
    let spacing = options.scale.divisor() as f32 * view.units_per_pixel;
    if view.length_to_points(screen, spacing) < 4.0 {
        return; // denser than that is a grey wash
    }
    let stroke = Stroke::new(1.0, Color32::from_rgba_unmultiplied(255, 255, 255, 60));
    let rect = screen.rect;
    let half = Vec2::splat(spacing * 0.5);
    let first = lattice.texel_center(0, 0) - Vec2::new(half.x, -half.y);
    for c in 0..=lattice.cols {
        let x = view
            .to_screen(screen, first + Vec2::new(c as f32 * spacing, 0.0))
            .x;
        painter.line_segment(
            [egui::pos2(x, rect.top()), egui::pos2(x, rect.bottom())],
            stroke,
        );
    }
    for r in 0..=lattice.rows {
        let y = view
            .to_screen(screen, first - Vec2::new(0.0, r as f32 * spacing))
            .y;
        painter.line_segment(
            [egui::pos2(rect.left(), y), egui::pos2(rect.right(), y)],
            stroke,
        );
    }
}

fn paint_cells(painter: &Painter, session: &Session, view: &View, screen: &Screen) {
    let grid = session.world().terrain().grid();
    let (nx, ny) = grid.dims();
    let size = grid.cell_size();
    let corner_a = view.to_world(screen, screen.rect.left_bottom());
    let corner_b = view.to_world(screen, screen.rect.right_top());
    let to_cell = |w: Vec2| ((w - grid.origin()) / size).floor();
    let (lo, hi) = (to_cell(corner_a), to_cell(corner_b));
    let range =
        |a: f32, b: f32, n: u32| (a.max(0.0) as u32)..((b + 1.0).clamp(0.0, n as f32) as u32);
    for iy in range(lo.y, hi.y, ny) {
        for ix in range(lo.x, hi.x, nx) {
            let min = grid.origin() + Vec2::new(ix as f32, iy as f32) * size;
            let Some(cell) = grid
                .cell_index(min + Vec2::splat(size * 0.5))
                .and_then(|i| grid.cell(i))
            else {
                continue;
            };
            let rect = egui::Rect::from_two_pos(
                view.to_screen(screen, min),
                view.to_screen(screen, min + Vec2::splat(size)),
            );
            let events = cell.events().len();
            if events > 0 {
                let alpha = (20 + events * 6).min(160) as u8;
                painter.rect_filled(
                    rect,
                    0.0,
                    Color32::from_rgba_unmultiplied(255, 120, 0, alpha),
                );
            }
            let outline = match cell.state().brick() {
                Some(_) => Stroke::new(1.5, Color32::from_rgb(80, 220, 255)),
                None => Stroke::new(0.5, Color32::from_rgba_unmultiplied(0, 0, 0, 70)),
            };
            painter.rect_stroke(rect, 0.0, outline, egui::StrokeKind::Inside);
        }
    }
}

fn paint_contacts(painter: &Painter, session: &Session, view: &View, screen: &Screen) {
    for body in session.world().bodies() {
        if body.surface == Vec2::ZERO || !body.clearance.is_finite() || body.clearance > 200.0 {
            continue;
        }
        let point = body.pos - body.surface * (body.clearance + body.radius);
        let at = view.to_screen(screen, point);
        let tip = at + egui::vec2(body.surface.x, -body.surface.y) * 24.0;
        painter.circle_filled(at, 3.0, Color32::from_rgb(255, 60, 200));
        painter.arrow(
            at,
            tip - at,
            Stroke::new(1.5, Color32::from_rgb(255, 60, 200)),
        );
    }
}

/// Paints the bodies at their interpolated positions, and the human's aim.
pub(super) fn paint_bodies(
    painter: &Painter,
    session: &Session,
    view: &View,
    screen: &Screen,
    weapon: u8,
) {
    for (body, pos) in session.interpolated() {
        let at = view.to_screen(screen, pos);
        let radius = view.length_to_points(screen, body.radius).max(2.0);
        match body.kind {
            BodyKind::Vehicle { player, stick, .. } => {
                let color = PLAYER_COLORS[usize::from(player) % PLAYER_COLORS.len()];
                let h = body.axis * body.half_length;
                let a = view.to_screen(screen, pos - h);
                let b = view.to_screen(screen, pos + h);
                painter.line_segment([a, b], Stroke::new(radius * 2.0, color));
                painter.circle_filled(a, radius, color);
                painter.circle_filled(b, radius, color);
                if stick {
                    painter.circle_stroke(at, radius * 2.2, Stroke::new(1.0, color));
                }
                let label = format!("P{player} {}", body.health);
                let label_at = at + egui::vec2(0.0, -radius - 12.0);
                painter.text(
                    label_at,
                    egui::Align2::CENTER_BOTTOM,
                    label,
                    egui::FontId::monospace(11.0),
                    color,
                );
            }
            BodyKind::Projectile { weapon, .. } => {
                let color = if weapon == 0 {
                    Color32::WHITE
                } else {
                    Color32::from_rgb(150, 100, 60)
                };
                painter.circle_filled(at, radius.max(3.0), color);
            }
            BodyKind::Debris => {
                painter.circle_filled(at, radius, Color32::from_gray(120));
            }
        }
    }
    paint_aim(painter, session, view, screen, weapon);
}

fn paint_aim(painter: &Painter, session: &Session, view: &View, screen: &Screen, weapon: u8) {
    let Some(me) = session.world().vehicle(0) else {
        return;
    };
    let pointer = painter
        .ctx()
        .pointer_hover_pos()
        .filter(|p| screen.rect.contains(*p));
    let Some(pointer) = pointer else {
        return;
    };
    let at = view.to_screen(screen, me.pos);
    let color = if weapon == 0 {
        Color32::WHITE
    } else {
        Color32::from_rgb(200, 150, 90)
    };
    painter.line_segment([at, pointer], Stroke::new(1.0, color.gamma_multiply(0.6)));
}
