//! [`Viewer3dApp`]: the eframe app. Each frame it reads the panel and the camera input,
//! emits the plan of the view when something changed, and has the GPU raymarcher draw it
//! into the texture the central panel shows.

use std::time::{Duration, Instant};

use craterfield::march3d::compile::CompileOptions;
use craterfield::march3d::{Camera3d, Plan};
use egui::Key;
use egui_wgpu::RenderState;
use glam::{Vec2, Vec3};

use super::bench::{BenchLog, BenchSetup};
use super::camera::{CameraMode, ViewInput};
use super::count::{CountJob, CountReport, CountState, count_size};
use super::panel::{PANEL_WIDTH, PanelAction, PanelView, panel_contents};
use super::source::SceneSource;
use super::timing::RecentTimes;
use super::view::{Drawn, MarchView};
use super::world::{PlanStats, World};
use crate::common::FrameDriver;

/// How often a frame checks on a running count.
const COUNT_POLL: Duration = Duration::from_millis(100);

/// The longest frame step the camera moves by (a stalled frame must not fling it away).
const MAX_DT: f32 = 0.1;

/// The 3D world viewer (see the [module docs](super)).
pub struct Viewer3dApp {
    driver: FrameDriver,
    /// Scenes the picker offers.
    sources: Vec<SceneSource>,
    source: SceneSource,
    world: Option<World>,
    /// Why the scene could not be opened.
    load_error: Option<String>,
    /// Why the last frame could not be drawn.
    render_error: Option<String>,
    mode: CameraMode,
    continuous: bool,
    view: MarchView,
    adapter: String,
    count: CountState,
    bench: Option<BenchLog>,
    times: RecentTimes,
    image_rect: Option<egui::Rect>,
    image_size: Option<[u32; 2]>,
}

impl Viewer3dApp {
    /// The viewer on eframe's wgpu device, showing `source`; `bench` hides the panel, draws
    /// continuously and prints frame and pass times at the driver's last frame. A scene
    /// that does not load is an error shown in the panel, not a failure; only a missing
    /// wgpu renderer or a raymarcher that cannot start is.
    pub fn new(
        cc: &eframe::CreationContext<'_>,
        source: SceneSource,
        driver: FrameDriver,
        bench: bool,
    ) -> Result<Viewer3dApp, String> {
        let rs = cc
            .wgpu_render_state
            .as_ref()
            .ok_or("viewer3d needs eframe's wgpu renderer, and it has none")?;
        let info = rs.adapter.get_info();
        let mut sources: Vec<SceneSource> = SceneSource::builtins().collect();
        if !sources.contains(&source) {
            sources.push(source.clone());
        }
        let mut app = Viewer3dApp {
            driver,
            sources,
            source: source.clone(),
            world: None,
            load_error: None,
            render_error: None,
            mode: CameraMode::default(),
            continuous: bench,
            view: MarchView::new(rs)?,
            adapter: format!("{} ({:?})", info.name, info.backend),
            count: CountState::Idle,
            bench: bench.then(BenchLog::default),
            times: RecentTimes::default(),
            image_rect: None,
            image_size: None,
        };
        app.open(source);
        Ok(app)
    }

    /// The scene shown or tried last.
    pub fn source(&self) -> &SceneSource {
        &self.source
    }

    /// The shown scene's name, if one is loaded.
    pub fn scene_name(&self) -> Option<&str> {
        self.world.as_ref().map(World::name)
    }

    /// Why the scene could not be opened or the view not drawn, as the panel shows it.
    pub fn error(&self) -> Option<&str> {
        self.load_error.as_deref().or(self.render_error.as_deref())
    }

    /// The emitter options the panel's switches set.
    pub fn compile_options(&self) -> Option<&CompileOptions> {
        self.world.as_ref().map(World::options)
    }

    /// The plan of the last drawn view.
    pub fn plan(&self) -> Option<&Plan> {
        self.current_plan().map(|(plan, _)| plan)
    }

    /// The statistics of the last drawn view's plan.
    pub fn plan_stats(&self) -> Option<&PlanStats> {
        self.current_plan().map(|(_, stats)| stats)
    }

    /// The camera of the view.
    pub fn camera(&self) -> Option<Camera3d> {
        self.world.as_ref().and_then(|w| w.camera.camera())
    }

    /// The camera mode.
    pub fn camera_mode(&self) -> CameraMode {
        self.mode
    }

    /// The last count-mode result, once a count finished.
    pub fn count_report(&self) -> Option<&CountReport> {
        self.count.report()
    }

    /// Whether a count is running.
    pub fn counting(&self) -> bool {
        matches!(self.count, CountState::Running(_))
    }

    /// The raymarcher's pipeline cache `(hits, misses)`.
    pub fn pipeline_cache(&self) -> (u64, u64) {
        self.view.cache_counters()
    }

    /// Where the view was drawn in the window, in points.
    pub fn image_rect(&self) -> Option<egui::Rect> {
        self.image_rect
    }

    /// The marched image's size in pixels.
    pub fn image_size(&self) -> Option<[u32; 2]> {
        self.image_size
    }

    fn current_plan(&self) -> Option<&(Plan, PlanStats)> {
        self.world.as_ref().and_then(World::current_plan)
    }

    /// Loads `source`; on failure the viewer shows no scene and the panel says why.
    fn open(&mut self, source: SceneSource) {
        self.count = CountState::Idle;
        self.render_error = None;
        match source.load().and_then(|scene| World::new(&scene)) {
            Ok(world) => {
                self.world = Some(world);
                self.load_error = None;
            }
            Err(message) => {
                self.world = None;
                self.load_error = Some(message);
            }
        }
        self.source = source;
    }

    fn apply(&mut self, action: PanelAction) {
        match action {
            PanelAction::Open(source) => self.open(source),
            PanelAction::Optimization(o, on) => {
                if let Some(world) = &mut self.world {
                    world.set_optimization(o, on);
                }
            }
            PanelAction::Mode(mode) => self.mode = mode,
            PanelAction::Continuous(on) => self.continuous = on,
            PanelAction::Count => self.start_count(),
        }
    }

    /// Counts the last drawn view at a reduced size.
    fn start_count(&mut self) {
        let (Some((plan, _)), Some(camera), Some(size)) =
            (self.current_plan(), self.camera(), self.image_size)
        else {
            return;
        };
        let job = CountJob::start(plan.clone(), camera, count_size(size));
        self.count = CountState::Running(job);
    }

    fn side_panel(&mut self, ui: &mut egui::Ui) {
        let actions = egui::Panel::left("viewer3d panel")
            .resizable(false)
            .exact_size(PANEL_WIDTH)
            .show(ui, |ui| {
                egui::ScrollArea::vertical()
                    .show(ui, |ui| panel_contents(ui, &self.panel_view()))
                    .inner
            })
            .inner;
        for action in actions {
            self.apply(action);
        }
    }

    fn panel_view(&self) -> PanelView<'_> {
        PanelView {
            sources: &self.sources,
            current: &self.source,
            error: self.error(),
            options: self.compile_options(),
            mode: self.mode,
            continuous: self.continuous,
            plan: self.plan_stats(),
            timing: self.times.summary(),
            image_size: self.image_size,
            cache: self.pipeline_cache(),
            gpu_timed: self.view.gpu_timed(),
            count: &self.count,
        }
    }

    /// The central panel: camera input, then the view; returns the pass's milliseconds
    /// when one was drawn.
    fn central(&mut self, ui: &mut egui::Ui, rs: &RenderState) -> Option<f64> {
        let rect = ui.available_rect_before_wrap();
        let response = ui.allocate_rect(rect, egui::Sense::click_and_drag());
        response.widget_info(|| egui::WidgetInfo::labeled(egui::Role::Image, true, "3D view"));
        self.image_rect = Some(rect);
        if ui.input(|i| i.key_pressed(Key::F)) {
            self.mode = self.mode.toggled();
        }
        let Some(world) = &mut self.world else {
            paint_message(ui, rect, "No scene: pick one in the panel.");
            return None;
        };
        let input = camera_input(ui, &response);
        world.camera.apply(&input, self.mode);
        if input.keys_held() {
            ui.ctx().request_repaint();
        }
        let size = pixel_size(rect, ui.pixels_per_point());
        self.image_size = Some(size);
        match self.draw(rs, size) {
            Ok(drawn) => {
                self.render_error = None;
                let shown = egui::load::SizedTexture::new(drawn.texture, rect.size());
                egui::Image::from_texture(shown).paint_at(ui, rect);
                Some(drawn.pass_ms)
            }
            Err(message) => {
                paint_message(ui, rect, &message);
                self.render_error = Some(message);
                None
            }
        }
    }

    /// Emits the plan when needed and marches it into the view's texture.
    fn draw(&mut self, rs: &RenderState, size: [u32; 2]) -> Result<Drawn, String> {
        let world = self.world.as_mut().ok_or("no scene")?;
        let camera = world
            .camera
            .camera()
            .ok_or("the camera became degenerate")?;
        let (plan, _) = world.plan_for(&camera, size)?;
        self.view.draw(rs, plan, &camera, size)
    }

    fn print_bench(&self) {
        let Some(bench) = &self.bench else {
            return;
        };
        let setup = BenchSetup {
            scene: self.scene_name().unwrap_or("(none)"),
            adapter: self.adapter.clone(),
            size: self.image_size.unwrap_or_default(),
            cache: self.pipeline_cache(),
            gpu_timed: self.view.gpu_timed(),
        };
        println!("{}", bench.report(&setup));
    }
}

impl eframe::App for Viewer3dApp {
    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        let started = Instant::now();
        let step = self.driver.begin_frame(ui.ctx());
        self.times.frame_started(started);
        if let Some(bench) = &mut self.bench {
            bench.frame_started(started);
        }
        let Some(rs) = frame.wgpu_render_state().cloned() else {
            ui.label("viewer3d needs eframe's wgpu renderer.");
            return;
        };
        if self.count.poll() {
            ui.ctx().request_repaint_after(COUNT_POLL);
        }
        if self.bench.is_none() {
            self.side_panel(ui);
        }
        let pass_ms = egui::CentralPanel::default()
            .frame(egui::Frame::NONE)
            .show(ui, |ui| self.central(ui, &rs))
            .inner;
        if let Some(ms) = pass_ms {
            self.times.pass(ms);
            if let Some(bench) = &mut self.bench {
                bench.pass(ms);
            }
        }
        if self.continuous {
            ui.ctx().request_repaint();
        }
        self.times.frame_done(started, pass_ms.unwrap_or(0.0));
        if step.last {
            self.print_bench();
        }
    }
}

/// The camera input of this frame: drags and the wheel over the view, keys anywhere.
fn camera_input(ui: &egui::Ui, response: &egui::Response) -> ViewInput {
    let drag = if response.dragged() {
        response.drag_delta()
    } else {
        egui::Vec2::ZERO
    };
    let scroll = if response.hovered() {
        ui.input(|i| i.smooth_scroll_delta.y)
    } else {
        0.0
    };
    ui.input(|i| {
        // +1, -1 or 0 for a pair of opposite keys.
        let axis = |plus, minus| {
            f32::from(u8::from(i.key_down(plus))) - f32::from(u8::from(i.key_down(minus)))
        };
        ViewInput {
            drag: Vec2::new(drag.x, drag.y),
            scroll,
            walk: Vec3::new(
                axis(Key::D, Key::A),
                axis(Key::E, Key::Q),
                axis(Key::W, Key::S),
            ),
            turn: Vec2::new(
                axis(Key::ArrowRight, Key::ArrowLeft),
                axis(Key::ArrowUp, Key::ArrowDown),
            ),
            fast: i.modifiers.shift,
            dt: i.stable_dt.min(MAX_DT),
        }
    })
}

/// The size in pixels of `rect` (points), at least one pixel a side.
fn pixel_size(rect: egui::Rect, pixels_per_point: f32) -> [u32; 2] {
    let side = |points: f32| (points * pixels_per_point).round().max(1.0) as u32;
    [side(rect.width()), side(rect.height())]
}

/// Text in the middle of the view where no image can be shown.
fn paint_message(ui: &egui::Ui, rect: egui::Rect, text: &str) {
    ui.painter().text(
        rect.center(),
        egui::Align2::CENTER_CENTER,
        text,
        egui::FontId::proportional(16.0),
        ui.visuals().text_color(),
    );
}
