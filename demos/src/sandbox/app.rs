//! [`SandboxApp`]: the eframe application. Each frame it runs the ticks that real time owes,
//! handles the pointer over the terrain (brush, pan, zoom), draws the terrain with the GPU
//! renderer and the bodies and overlays on top, and shows the side panel.

use std::path::Path;

use web_time::Instant;

use craterfield::field2d::{Event, Level};
use craterfield::render2d::RenderOptions;
use glam::Vec2;

use super::bench::Bench;
use super::controls::{Keys, human_input};
use super::overlays::{Overlays, paint_bodies, paint_overlays};
use super::session::Session;
use super::terrain_view::TerrainView;
use super::view::{Screen, View};
use crate::common::{FrameDriver, Tails};

/// The label the terrain view carries for assistive technology and tests.
pub const TERRAIN_VIEW_LABEL: &str = "terrain view";

/// Frames of history behind the panel's timing tails.
const HISTORY: usize = 240;

/// The brush of mouse edits.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Brush {
    /// Disc radius, world units.
    pub radius: f32,
    /// Material of fills.
    pub material: u16,
}

impl Default for Brush {
    fn default() -> Self {
        Brush {
            radius: 40.0,
            material: 0,
        }
    }
}

/// Recent timings shown in the panel.
#[derive(Default)]
pub(super) struct Timings {
    pub(super) frame_ms: Vec<f64>,
    pub(super) tick_ms: Vec<f64>,
    pub(super) gpu_ms: Vec<[f64; 3]>,
    last_frame: Option<Instant>,
}

impl Timings {
    fn push<T>(v: &mut Vec<T>, x: T) {
        if v.len() == HISTORY {
            v.remove(0);
        }
        v.push(x);
    }

    pub(super) fn tails(values: impl Iterator<Item = f64>) -> Tails {
        Tails::of(&values.collect::<Vec<_>>())
    }
}

/// The destruction sandbox.
pub struct SandboxApp {
    pub(super) session: Session,
    pub(super) view: Option<View>,
    pub(super) terrain: Result<TerrainView, String>,
    pub(super) options: RenderOptions,
    pub(super) brush: Brush,
    pub(super) weapon: u8,
    pub(super) overlays: Overlays,
    pub(super) level_path: String,
    pub(super) replay_path: String,
    pub(super) level_error: Option<String>,
    pub(super) message: Option<String>,
    pub(super) timings: Timings,
    pub(super) scrub_tick: u32,
    stroke_last: Option<Vec2>,
    driver: FrameDriver,
    bench: Option<Bench>,
    #[cfg(target_family = "wasm")]
    pub(super) inbox: crate::web::FileInbox,
}

impl SandboxApp {
    /// The sandbox on eframe's device, opening `level_file` (or the default level; a file
    /// that does not load leaves the default level and shows its error).
    pub fn new(
        cc: &eframe::CreationContext<'_>,
        level_file: Option<&Path>,
        driver: FrameDriver,
        bench: bool,
    ) -> Result<SandboxApp, String> {
        let terrain = match &cc.wgpu_render_state {
            Some(rs) => TerrainView::new(rs, RenderOptions::default()),
            None => Err("eframe runs without wgpu: the sandbox draws with wgpu only".to_string()),
        };
        let mut app = SandboxApp {
            session: Session::new(Level::default_level())?,
            view: None,
            terrain,
            options: RenderOptions::default(),
            brush: Brush::default(),
            weapon: 0,
            overlays: Overlays::default(),
            level_path: String::new(),
            replay_path: "sandbox.replay".to_string(),
            level_error: None,
            message: None,
            timings: Timings::default(),
            scrub_tick: 0,
            stroke_last: None,
            driver,
            bench: bench.then(Bench::default),
            #[cfg(target_family = "wasm")]
            inbox: crate::web::FileInbox::default(),
        };
        if let Some(path) = level_file {
            app.level_path = path.display().to_string();
            app.load_level(path);
        }
        Ok(app)
    }

    /// The match.
    pub fn session(&self) -> &Session {
        &self.session
    }

    /// The view (set once the first frame knows the panel's size).
    pub fn view(&self) -> Option<View> {
        self.view
    }

    /// The render options the renderer uses now.
    pub fn render_options(&self) -> Option<&RenderOptions> {
        self.terrain.as_ref().ok().map(|t| t.options())
    }

    /// The error of the last level that did not load.
    pub fn level_error(&self) -> Option<&str> {
        self.level_error.as_deref()
    }

    /// The brush.
    pub fn brush(&self) -> Brush {
        self.brush
    }

    /// Loads a level file, starting a new match on it; on failure keeps the match and shows
    /// the error (node path and reason).
    pub fn load_level(&mut self, path: &Path) {
        match Level::load(path)
            .map_err(|e| e.to_string())
            .and_then(Session::new)
        {
            Ok(session) => {
                self.session = session;
                self.view = None;
                self.level_error = None;
                self.message = Some(format!("loaded level {}", path.display()));
            }
            Err(e) => self.level_error = Some(format!("{}: {e}", path.display())),
        }
    }

    /// Loads and verifies a replay file of the current level.
    pub fn load_replay(&mut self, path: &Path) {
        self.message = Some(match self.session.load_replay(path) {
            Ok(()) => format!("loaded replay {}", path.display()),
            Err(e) => format!("replay not loaded: {e}"),
        });
        self.scrub_tick = 0;
    }

    /// Saves the recording.
    pub fn save_replay(&mut self, path: &Path) {
        self.message = Some(match self.session.save_replay(path) {
            Ok(()) => format!(
                "saved {} ticks to {}",
                self.session.timeline().ticks(),
                path.display()
            ),
            Err(e) => format!("replay not saved: {e}"),
        });
    }

    /// Opens a file handed over as bytes (dropped onto a browser page, or chosen with its
    /// file picker): a `.replay` is loaded and verified, anything else is read as a level.
    pub fn open_file(&mut self, name: &str, bytes: &[u8]) {
        if name.ends_with(".replay") {
            self.message = Some(match self.session.load_replay_bytes(bytes) {
                Ok(()) => format!("loaded replay {name}"),
                Err(e) => format!("replay not loaded: {name}: {e}"),
            });
            self.scrub_tick = 0;
            return;
        }
        let level = std::str::from_utf8(bytes)
            .map_err(|e| format!("not UTF-8 text: {e}"))
            .and_then(|text| Level::from_ron(text).map_err(|e| e.to_string()));
        match level.and_then(Session::new) {
            Ok(session) => {
                self.session = session;
                self.view = None;
                self.level_error = None;
                self.message = Some(format!("loaded level {name}"));
            }
            Err(e) => self.level_error = Some(format!("{name}: {e}")),
        }
    }

    /// Files dropped onto the window; in a browser also those chosen with the page's file
    /// picker, which arrive a few frames later (a browser reads files asynchronously).
    fn dropped_files(&mut self, ctx: &egui::Context) {
        let dropped = ctx.input(|i| i.raw.dropped_files.clone());
        #[cfg(not(target_family = "wasm"))]
        for file in dropped {
            self.open_path(file.path());
        }
        #[cfg(target_family = "wasm")]
        {
            for file in dropped {
                crate::web::read_dropped(file, &self.inbox, ctx);
            }
            for picked in self.inbox.take() {
                match picked {
                    Ok((name, bytes)) => self.open_file(&name, &bytes),
                    Err(e) => self.level_error = Some(e),
                }
            }
        }
    }

    #[cfg(not(target_family = "wasm"))]
    fn open_path(&mut self, path: &Path) {
        if path.extension().is_some_and(|e| e == "replay") {
            self.replay_path = path.display().to_string();
            self.load_replay(path);
        } else {
            self.level_path = path.display().to_string();
            self.load_level(path);
        }
    }

    fn step_simulation(&mut self, ctx: &egui::Context, pointer: Option<Vec2>) {
        let keys = ctx.input(Keys::read);
        if ctx.input(|i| i.key_pressed(egui::Key::Q)) {
            self.weapon ^= 1;
        }
        let vehicle = self.session.world().vehicle(0).map(|b| b.pos);
        let input = human_input(keys, vehicle, pointer, self.weapon);
        let dt = f64::from(ctx.input(|i| i.stable_dt));
        if let Err(e) = self.session.update(dt, input) {
            self.message = Some(format!("simulation stopped: {e}"));
            self.session.pause();
        }
        for ms in self.session.take_tick_ms() {
            Timings::push(&mut self.timings.tick_ms, ms);
            if let Some(b) = &mut self.bench {
                b.tick_ms.push(ms);
            }
        }
    }

    /// Queues a carve (or fill) at `at` with the brush.
    fn edit(&mut self, at: Vec2, fill: bool) {
        let e = if fill {
            Event::fill(at, self.brush.radius, self.brush.material)
        } else {
            Event::carve(at, self.brush.radius)
        };
        let queued = e
            .map_err(|e| e.to_string())
            .and_then(|e| self.session.queue_edit(e));
        if let Err(e) = queued {
            self.message = Some(format!("edit refused: {e}"));
        }
    }

    /// Pointer over the terrain: clicks edit, shift-drags paint strokes, plain drags pan,
    /// the wheel zooms about the cursor.
    fn handle_pointer(&mut self, ui: &egui::Ui, response: &egui::Response, screen: &Screen) {
        let Some(view) = self.view.as_mut() else {
            return;
        };
        let world_at = |view: &View, pos: egui::Pos2| view.to_world(screen, pos);
        let shift = ui.input(|i| i.modifiers.shift);
        if let Some(pos) = response.interact_pointer_pos().or(response.hover_pos()) {
            let scroll = ui.input(|i| i.smooth_scroll_delta.y);
            if scroll != 0.0 && response.hovered() {
                view.zoom_about(screen, pos, (scroll / 200.0).exp());
            }
        }
        let view_now = *view;
        let button = if response.clicked() {
            Some(false)
        } else if response.secondary_clicked() {
            Some(true)
        } else {
            None
        };
        if let (Some(fill), Some(pos)) = (button, response.interact_pointer_pos()) {
            self.edit(world_at(&view_now, pos), fill);
        }
        let dragging = response.dragged_by(egui::PointerButton::Primary)
            || response.dragged_by(egui::PointerButton::Secondary);
        if dragging && shift {
            self.paint_stroke(&view_now, screen, response);
        } else if dragging && let Some(view) = self.view.as_mut() {
            view.pan(screen, response.drag_delta());
        }
        if !dragging {
            self.stroke_last = None;
        }
    }

    /// A shift-drag lays discs every half brush radius along the pointer's path.
    fn paint_stroke(&mut self, view: &View, screen: &Screen, response: &egui::Response) {
        let Some(pos) = response.interact_pointer_pos() else {
            return;
        };
        let at = view.to_world(screen, pos);
        let fill = response.dragged_by(egui::PointerButton::Secondary);
        let spacing = self.brush.radius * 0.5;
        match self.stroke_last {
            Some(last) if (at - last).length() < spacing => {}
            _ => {
                self.edit(at, fill);
                self.stroke_last = Some(at);
            }
        }
    }

    fn central(&mut self, ui: &mut egui::Ui, frame: &eframe::Frame) {
        let rect = ui.available_rect_before_wrap();
        let screen = Screen {
            rect,
            pixels_per_point: ui.ctx().pixels_per_point(),
        };
        let level_bounds = self.session.level().bounds();
        let view = *self
            .view
            .get_or_insert_with(|| View::fit(level_bounds, screen.pixels()));
        let response = ui
            .allocate_rect(rect, egui::Sense::click_and_drag())
            .on_hover_cursor(egui::CursorIcon::Crosshair);
        response
            .widget_info(|| egui::WidgetInfo::labeled(egui::Role::Image, true, TERRAIN_VIEW_LABEL));
        let pointer = response.hover_pos().map(|p| view.to_world(&screen, p));
        self.step_simulation(ui.ctx(), pointer);
        self.handle_pointer(ui, &response, &screen);
        let view = self.view.unwrap_or(view);
        self.paint_terrain(ui, frame, &screen, &view);
        let painter = ui.painter_at(rect);
        paint_overlays(
            &painter,
            &self.overlays,
            &self.session,
            &view,
            &screen,
            &self.options,
        );
        paint_bodies(&painter, &self.session, &view, &screen, self.weapon);
    }

    fn paint_terrain(
        &mut self,
        ui: &egui::Ui,
        frame: &eframe::Frame,
        screen: &Screen,
        view: &View,
    ) {
        let camera = view.camera(screen.pixels());
        let palette: Vec<[u8; 3]> = self
            .session
            .level()
            .materials()
            .iter()
            .map(|m| m.color)
            .collect();
        let uv = egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0));
        let (Ok(terrain_view), Some(rs)) = (&mut self.terrain, frame.wgpu_render_state()) else {
            return;
        };
        terrain_view.set_options(self.options.clone());
        let terrain = self.session.world().terrain();
        let drawn = if self.overlays.refine {
            terrain_view
                .refine_overlay(ui.ctx(), terrain, &palette, &camera)
                .map(|(id, px)| {
                    self.overlays.refined_pixels = Some(px);
                    id
                })
        } else {
            terrain_view.draw(rs, terrain, &palette, &camera)
        };
        match drawn {
            Ok(id) => {
                ui.painter()
                    .image(id, screen.rect, uv, egui::Color32::WHITE);
                let cost = terrain_view.last_cost();
                if let Some(ms) = cost.gpu_ms {
                    Timings::push(&mut self.timings.gpu_ms, ms);
                }
                if let Some(b) = &mut self.bench {
                    b.record_draw(cost, [camera.width, camera.height]);
                }
            }
            Err(e) => self.message = Some(format!("render failed: {e}")),
        }
    }

    fn record_frame_time(&mut self) {
        let now = Instant::now();
        if let Some(last) = self.timings.last_frame.replace(now) {
            let ms = (now - last).as_secs_f64() * 1e3;
            Timings::push(&mut self.timings.frame_ms, ms);
            if let Some(b) = &mut self.bench {
                b.frame_ms.push(ms);
            }
        }
    }
}

impl eframe::App for SandboxApp {
    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        let step = self.driver.begin_frame(ui.ctx());
        self.record_frame_time();
        self.dropped_files(ui.ctx());
        if self.session.mode() == super::session::Mode::Live {
            // The simulation runs on its own clock: keep frames coming.
            ui.ctx().request_repaint();
        }
        egui::Panel::right("sandbox controls")
            .resizable(false)
            .exact_size(340.0)
            .show(ui, |ui| self.side_panel(ui, frame));
        egui::CentralPanel::default()
            .frame(egui::Frame::NONE)
            .show(ui, |ui| self.central(ui, frame));
        if step.last
            && let Some(b) = &self.bench
        {
            let adapter = frame
                .wgpu_render_state()
                .map(|rs| rs.adapter.get_info().name)
                .unwrap_or_default();
            let timestamps = self.terrain.as_ref().is_ok_and(|t| t.has_timestamps());
            println!("{}", b.report(&adapter, timestamps));
        }
    }
}
