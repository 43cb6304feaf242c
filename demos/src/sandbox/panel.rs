//! The sandbox's side panel: brush, render options (applied live), overlays, statistics
//! and timings with their tails, the level file, and the recording (save, load, verify,
//! scrub, play).

#[cfg(not(target_family = "wasm"))]
use std::path::PathBuf;

use craterfield::render2d::{Reconstruction, Scale, Upsample};

use super::app::{SandboxApp, Timings};
use super::session::{Mode, Verified};
use crate::common::Tails;

const ERROR_COLOR: egui::Color32 = egui::Color32::from_rgb(255, 110, 100);

impl SandboxApp {
    pub(super) fn side_panel(&mut self, ui: &mut egui::Ui, frame: &eframe::Frame) {
        egui::ScrollArea::vertical().show(ui, |ui| {
            self.errors(ui);
            ui.collapsing("Level", |ui| self.level_controls(ui));
            ui.collapsing("Brush", |ui| self.brush_controls(ui));
            ui.collapsing("Render", |ui| self.render_controls(ui));
            ui.collapsing("Overlays", |ui| self.overlay_controls(ui));
            egui::CollapsingHeader::new("Recording")
                .default_open(true)
                .show(ui, |ui| self.recording(ui));
            egui::CollapsingHeader::new("Statistics")
                .default_open(true)
                .show(ui, |ui| self.statistics(ui, frame));
            ui.collapsing("Controls", help);
        });
    }

    fn errors(&mut self, ui: &mut egui::Ui) {
        if let Some(e) = &self.level_error {
            ui.group(|ui| {
                ui.colored_label(ERROR_COLOR, "Level error");
                ui.label(e.as_str());
            });
        }
        if let Err(e) = &self.terrain {
            ui.colored_label(ERROR_COLOR, format!("renderer: {e}"));
        }
        if let Some(m) = &self.message {
            ui.label(m.as_str());
        }
    }

    fn brush_controls(&mut self, ui: &mut egui::Ui) {
        ui.add(egui::Slider::new(&mut self.brush.radius, 4.0..=200.0).text("radius"));
        let materials = self.session.level().materials();
        egui::ComboBox::from_label("fill material")
            .selected_text(
                materials
                    .get(usize::from(self.brush.material))
                    .map_or("?", |m| m.name.as_str()),
            )
            .show_ui(ui, |ui| {
                for (i, m) in materials.iter().enumerate() {
                    ui.selectable_value(&mut self.brush.material, i as u16, m.name.as_str());
                }
            });
        ui.label(format!(
            "weapon (Q): {}",
            if self.weapon == 0 {
                "shell (carves)"
            } else {
                "dirt (fills)"
            }
        ));
    }

    fn render_controls(&mut self, ui: &mut egui::Ui) {
        let o = &mut self.options;
        ui.label("Scale");
        ui.horizontal_wrapped(|ui| {
            for s in Scale::ALL {
                ui.selectable_value(&mut o.scale, s, format!("1/{}", s.divisor()));
            }
        });
        ui.label("Mode");
        ui.horizontal_wrapped(|ui| {
            for m in Reconstruction::ALL {
                ui.selectable_value(&mut o.reconstruction, m, m.name());
            }
        });
        ui.label("Upsample");
        ui.horizontal_wrapped(|ui| {
            for u in Upsample::ALL {
                ui.selectable_value(&mut o.upsample, u, u.name());
            }
        });
    }

    fn overlay_controls(&mut self, ui: &mut egui::Ui) {
        let o = &mut self.overlays;
        ui.checkbox(&mut o.texels, "texel grid");
        ui.checkbox(&mut o.refine, "refined pixels (CPU twin, red)");
        if o.refine
            && let Some(px) = o.refined_pixels
        {
            ui.label(format!("{px} pixels evaluated exactly"));
        }
        ui.checkbox(&mut o.cells, "explosion-grid cells");
        ui.checkbox(&mut o.contacts, "contacts and normals");
    }

    fn statistics(&mut self, ui: &mut egui::Ui, frame: &eframe::Frame) {
        let world = self.session.world();
        let stats = world.terrain().stats();
        ui.label(format!(
            "tick {}   bodies {}",
            world.tick(),
            world.bodies().len()
        ));
        ui.label(format!("state hash {:#018x}", world.state_hash()));
        ui.label(format!(
            "events {}   grid cells {}   bricks {}",
            world.terrain().events_applied(),
            stats.cells,
            stats.bricks
        ));
        ui.label(format!("longest cell list {}", stats.max_cell_events));
        if let Ok(t) = &self.terrain {
            let (hits, misses) = t.cache_counters();
            ui.label(format!("pipeline cache {hits} hits, {misses} misses"));
        }
        if let Some(rs) = frame.wgpu_render_state() {
            ui.label(adapter_label(&rs.adapter.get_info()));
        }
        let t = &self.timings;
        let mut rows = vec![
            ("frame", Timings::tails(t.frame_ms.iter().copied())),
            ("tick (CPU)", Timings::tails(t.tick_ms.iter().copied())),
        ];
        for (i, name) in ["pass 1 (GPU)", "pass 2 (GPU)", "pass 3 (GPU)"]
            .into_iter()
            .enumerate()
        {
            if !t.gpu_ms.is_empty() {
                rows.push((name, Timings::tails(t.gpu_ms.iter().map(|p| p[i]))));
            }
        }
        timing_grid(ui, &rows);
        if t.gpu_ms.is_empty() {
            ui.label("GPU passes: no timestamp queries");
        }
    }

    fn recording(&mut self, ui: &mut egui::Ui) {
        let ticks = self.session.timeline().ticks();
        let mode = self.session.mode();
        ui.label(match mode {
            Mode::Live => format!(
                "recording: {ticks} ticks, {} edits",
                self.session.timeline().edits().len()
            ),
            Mode::Playback { playing } => format!(
                "{}: tick {} of {ticks}",
                if playing { "playing" } else { "paused" },
                self.session.world().tick()
            ),
        });
        // The slider follows the world, except while it is being dragged.
        if !ui.ctx().egui_is_using_pointer() {
            self.scrub_tick = self.session.world().tick().min(ticks);
        }
        let slider = ui.add(egui::Slider::new(&mut self.scrub_tick, 0..=ticks).text("tick"));
        if slider.changed() {
            let tick = self.scrub_tick;
            if let Err(e) = self.session.seek(tick) {
                self.message = Some(format!("seek failed: {e}"));
            }
        }
        ui.horizontal(|ui| {
            if ui.button("Play").clicked() {
                self.session.play();
            }
            if ui.button("Pause").clicked() {
                self.session.pause();
            }
            if ui.button("Go live").clicked() {
                self.session.go_live();
            }
        });
        if let Some((tick, _)) = self.session.divergence() {
            ui.colored_label(ERROR_COLOR, format!("playback diverged at tick {tick}"));
        }
        self.replay_file(ui);
        match self.session.verified() {
            Some(Verified::Passed { ticks, hashes }) => {
                ui.label(format!(
                    "replay verify: ok, {ticks} ticks, {hashes} hashes match"
                ));
            }
            Some(Verified::Failed(e)) => {
                ui.colored_label(ERROR_COLOR, format!("replay verify: failed: {e}"));
            }
            None => {}
        }
    }

    fn level_controls(&mut self, ui: &mut egui::Ui) {
        ui.label(format!("level: {}", self.session.level().name()));
        let cost = self.session.level().graph().eval_cost();
        ui.label(format!(
            "cost {} work units per evaluation ({} tape instructions; limit {})",
            cost.work,
            cost.instructions,
            craterfield::field2d::MAX_EVAL_WORK
        ));
        self.level_file(ui);
    }

    #[cfg(not(target_family = "wasm"))]
    fn level_file(&mut self, ui: &mut egui::Ui) {
        let label = ui.label("Level file");
        ui.text_edit_singleline(&mut self.level_path)
            .labelled_by(label.id);
        if ui.button("Load level").clicked() {
            self.load_level(&PathBuf::from(self.level_path.clone()));
        }
        ui.label("or drop a level (.ron) or a .replay onto the window");
    }

    #[cfg(not(target_family = "wasm"))]
    fn replay_file(&mut self, ui: &mut egui::Ui) {
        let label = ui.label("Replay file");
        ui.text_edit_singleline(&mut self.replay_path)
            .labelled_by(label.id);
        ui.horizontal(|ui| {
            if ui.button("Save replay").clicked() {
                self.save_replay(&PathBuf::from(self.replay_path.clone()));
            }
            if ui.button("Load replay").clicked() {
                self.load_replay(&PathBuf::from(self.replay_path.clone()));
            }
        });
    }

    /// In a browser: the page's file picker, and drag and drop onto the page.
    #[cfg(target_family = "wasm")]
    fn level_file(&mut self, ui: &mut egui::Ui) {
        if ui.button("Open level or replay…").clicked()
            && let Err(e) = crate::web::pick_files(&self.inbox, ui.ctx())
        {
            self.level_error = Some(format!("no file picker: {e}"));
        }
        ui.label("or drop a level (.ron) or a .replay onto the page");
    }

    /// In a browser: the recording is saved as a download, and loaded like a level.
    #[cfg(target_family = "wasm")]
    fn replay_file(&mut self, ui: &mut egui::Ui) {
        ui.horizontal(|ui| {
            if ui.button("Download replay").clicked() {
                let saved = self
                    .session
                    .replay_bytes()
                    .and_then(|bytes| crate::web::download(&self.replay_path, &bytes));
                self.message = Some(match saved {
                    Ok(()) => format!("saved {} ticks", self.session.timeline().ticks()),
                    Err(e) => format!("replay not saved: {e}"),
                });
            }
            if ui.button("Open replay…").clicked()
                && let Err(e) = crate::web::pick_files(&self.inbox, ui.ctx())
            {
                self.message = Some(format!("no file picker: {e}"));
            }
        });
    }
}

/// Timings as a table: milliseconds, median p95 p99 max.
fn timing_grid(ui: &mut egui::Ui, rows: &[(&str, Tails)]) {
    egui::Grid::new("timings").striped(true).show(ui, |ui| {
        for head in ["ms", "median", "p95", "p99", "max"] {
            ui.label(head);
        }
        ui.end_row();
        for (name, t) in rows {
            ui.label(*name);
            for v in [t.median, t.p95, t.p99, t.max] {
                // At most four digits, so the columns stay inside the fixed-width panel.
                let text = if v >= 100.0 {
                    format!("{v:.0}")
                } else {
                    format!("{v:.1}")
                };
                ui.monospace(text);
            }
            ui.end_row();
        }
    });
}

fn help(ui: &mut egui::Ui) {
    for line in [
        "left click: carve   right click: fill",
        "shift-drag: paint a stroke (right button fills)",
        "drag: pan   wheel: zoom about the cursor",
        "A/D or arrows: drive   W or up: jump",
        "space: fire   Q: switch weapon   S: stick mode",
        "mouse: aim (distance sets the power)",
    ] {
        ui.label(line);
    }
}

/// The adapter as the panel names it. A browser may keep the device's name to itself (an
/// empty string through WebGPU), so the backend and device type are always shown.
fn adapter_label(info: &wgpu::AdapterInfo) -> String {
    let name = if info.name.is_empty() {
        "(name not given)"
    } else {
        info.name.as_str()
    };
    format!(
        "adapter {name} ({:?}, {:?})",
        info.backend, info.device_type
    )
}
