//! The side panel: the scene picker, the camera mode, a switch per emitter optimization,
//! the count-mode button and the statistics of the current view. The panel only reads the
//! app's state and returns what the user asked for, as [`PanelAction`]s.

use craterfield::march3d::compile::{CompileOptions, Optimization};

use super::camera::CameraMode;
use super::count::{CountReport, CountState};
use super::source::SceneSource;
use super::world::PlanStats;

/// The panel's width in points.
pub(crate) const PANEL_WIDTH: f32 = 270.0;

/// What the user asked for in the panel this frame.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum PanelAction {
    /// Open another scene.
    Open(SceneSource),
    /// Switch an optimization on or off.
    Optimization(Optimization, bool),
    /// Switch the camera mode.
    Mode(CameraMode),
    /// Redraw every frame (so frame times mean something) or only on input.
    Continuous(bool),
    /// Run the count mode on the current view.
    Count,
}

/// Frame times the panel shows (medians over the last frames).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct TimingSummary {
    /// Milliseconds between frame starts.
    pub(crate) frame_ms: f64,
    /// Milliseconds the viewer spent on the CPU in its frame (camera, plan, encoding).
    pub(crate) cpu_ms: f64,
    /// The marcher's pass in milliseconds, once one was drawn.
    pub(crate) pass_ms: Option<f64>,
}

/// What the panel shows.
pub(crate) struct PanelView<'a> {
    /// Scenes on offer: the builtins and the command line's file.
    pub(crate) sources: &'a [SceneSource],
    /// The scene shown (or tried).
    pub(crate) current: &'a SceneSource,
    /// Why the scene is not shown, or the last rendering error.
    pub(crate) error: Option<&'a str>,
    /// The emitter options, once a scene is loaded.
    pub(crate) options: Option<&'a CompileOptions>,
    /// The camera mode.
    pub(crate) mode: CameraMode,
    /// Whether the view redraws every frame.
    pub(crate) continuous: bool,
    /// The current plan's statistics.
    pub(crate) plan: Option<&'a PlanStats>,
    /// Frame times.
    pub(crate) timing: TimingSummary,
    /// Marched image size in pixels.
    pub(crate) image_size: Option<[u32; 2]>,
    /// Pipeline cache hits and misses.
    pub(crate) cache: (u64, u64),
    /// Whether pass times are GPU timestamps.
    pub(crate) gpu_timed: bool,
    /// The count mode's state.
    pub(crate) count: &'a CountState,
}

/// Draws the panel's contents; returns the user's requests.
pub(crate) fn panel_contents(ui: &mut egui::Ui, view: &PanelView<'_>) -> Vec<PanelAction> {
    let mut actions = Vec::new();
    ui.heading("craterfield viewer3d");
    scene_picker(ui, view, &mut actions);
    if let Some(error) = view.error {
        ui.colored_label(ui.visuals().error_fg_color, error);
    }
    ui.separator();
    camera_controls(ui, view.mode, &mut actions);
    if let Some(options) = view.options {
        ui.separator();
        optimization_switches(ui, options, &mut actions);
        ui.separator();
        count_section(ui, view.count, &mut actions);
    }
    ui.separator();
    plan_section(ui, view.plan);
    ui.separator();
    timing_section(ui, view, &mut actions);
    actions
}

fn scene_picker(ui: &mut egui::Ui, view: &PanelView<'_>, actions: &mut Vec<PanelAction>) {
    let mut picked = view.current.clone();
    egui::ComboBox::from_label("Scene")
        .selected_text(view.current.label())
        .show_ui(ui, |ui| {
            for source in view.sources {
                ui.selectable_value(&mut picked, source.clone(), source.label());
            }
        });
    if picked != *view.current {
        actions.push(PanelAction::Open(picked));
    }
}

fn camera_controls(ui: &mut egui::Ui, mode: CameraMode, actions: &mut Vec<PanelAction>) {
    let mut picked = mode;
    ui.horizontal(|ui| {
        ui.label("Camera");
        ui.radio_value(&mut picked, CameraMode::Orbit, "Orbit");
        ui.radio_value(&mut picked, CameraMode::Fly, "Fly");
    });
    if picked != mode {
        actions.push(PanelAction::Mode(picked));
    }
    let hint = match mode {
        CameraMode::Orbit => "drag or arrows: orbit, wheel: zoom, F: fly",
        CameraMode::Fly => "WASD/QE: move (Shift: fast), drag or arrows: look, F: orbit",
    };
    ui.weak(hint);
}

fn optimization_switches(
    ui: &mut egui::Ui,
    options: &CompileOptions,
    actions: &mut Vec<PanelAction>,
) {
    ui.label("Emitter optimizations");
    ui.horizontal_wrapped(|ui| {
        for o in Optimization::ALL {
            let mut on = options.on(o);
            if ui.checkbox(&mut on, o.name()).changed() {
                actions.push(PanelAction::Optimization(o, on));
            }
        }
    });
}

fn count_section(ui: &mut egui::Ui, count: &CountState, actions: &mut Vec<PanelAction>) {
    let running = matches!(count, CountState::Running(_));
    let button = egui::Button::new("Count evaluations (CPU)");
    if ui.add_enabled(!running, button).clicked() {
        actions.push(PanelAction::Count);
    }
    match count {
        CountState::Idle => {}
        CountState::Running(_) => {
            ui.label("counting on the CPU tracer…");
        }
        CountState::Done(report) => count_report(ui, report),
        CountState::Failed(message) => {
            ui.colored_label(
                ui.visuals().error_fg_color,
                format!("count failed: {message}"),
            );
        }
    }
}

fn count_report(ui: &mut egui::Ui, r: &CountReport) {
    let [w, h] = r.size;
    ui.label(format!("counted at {w}x{h} px in {:.2} s", r.seconds));
    ui.monospace("per px   mean median  p99   max");
    ui.monospace(format!(
        "evals {:>7.1} {:>6.0} {:>5.0} {:>5.0}",
        r.evals_mean, r.evals.median, r.evals.p99, r.evals.max
    ));
    ui.monospace(format!(
        "steps {:>7.1} {:>6.0} {:>5.0} {:>5.0}",
        r.steps_mean, r.steps.median, r.steps.p99, r.steps.max
    ));
    ui.label(format!("{:.3} GFLOP per counted frame", r.gflop));
}

fn plan_section(ui: &mut egui::Ui, plan: Option<&PlanStats>) {
    let Some(p) = plan else {
        ui.label("no plan");
        return;
    };
    ui.label(format!("plan {:016x}", p.key));
    let tier = if p.steps < p.full_steps {
        format!("step tier: {} of {} steps", p.steps, p.full_steps)
    } else {
        format!("steps: {} (the full budget)", p.steps)
    };
    ui.label(tier);
    ui.label(format!(
        "objects: {} visible of {}, {} culled",
        p.visible,
        p.objects,
        p.culled()
    ));
    ui.label(format!(
        "LOD: {} far (simplified), {} nodes",
        p.far_lod, p.nodes
    ));
    if let Some(h) = p.early_out {
        ui.label(format!("terrain only above y = {h:.1}"));
    }
}

fn timing_section(ui: &mut egui::Ui, view: &PanelView<'_>, actions: &mut Vec<PanelAction>) {
    let t = view.timing;
    let mut continuous = view.continuous;
    if ui
        .checkbox(&mut continuous, "Redraw continuously")
        .changed()
    {
        actions.push(PanelAction::Continuous(continuous));
    }
    if let Some([w, h]) = view.image_size {
        ui.label(format!("image {w}x{h} px"));
    }
    // Between frames drawn only on input, the interval is the user's pause, not a cost.
    let frame = if view.continuous {
        format!("frame {:.1} ms, ", t.frame_ms)
    } else {
        String::new()
    };
    ui.label(format!("{frame}viewer CPU {:.1} ms", t.cpu_ms));
    let pass = match t.pass_ms {
        Some(ms) => format!(
            "march pass {ms:.1} ms ({})",
            super::bench::pass_clock(view.gpu_timed)
        ),
        None => "march pass: not drawn yet".to_string(),
    };
    ui.label(pass);
    let (hits, misses) = view.cache;
    ui.label(format!("pipeline cache: {hits} hits, {misses} misses"));
}
