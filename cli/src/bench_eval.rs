//! `craterfield bench eval`: the tape evaluators on every backend this CPU has, measured in
//! this run, one thread unless a row says otherwise; with the feature `peers`, fidget 0.5 on
//! the prospero workloads side by side.
//!
//! Workloads: `default` (the default level, no explosions, 1M random points in the world,
//! batch distances), `default-10k` (the same after 10,000 explosions), `prospero-brute`
//! (prospero's whole tape at every pixel of the 1024x1024 image) and `prospero-specialized`
//! (the same image by region specialization). `-grad` rows are distance and gradient.

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use craterfield::backend::Backend;
use craterfield::field2d::import::graph_from_vm;
use craterfield::field2d::tape::Outputs;
use craterfield::field2d::tape::{ImageOptions, inside_image};
use craterfield::field2d::{Graph, Level, Sample, Terrain};
use glam::Vec2;
use serde::Serialize;

use crate::rng::Rng;

#[derive(Serialize, Clone)]
struct Row {
    workload: String,
    #[serde(rename = "impl")]
    implementation: String,
    threads: usize,
    ms: f64,
    points_per_s: f64,
}

#[derive(Serialize)]
struct Report {
    rows: Vec<Row>,
}

/// Best of a few runs (at least one; more while under about two seconds in total).
fn best_ms(mut run: impl FnMut() -> Result<f64, String>) -> Result<f64, String> {
    let start = Instant::now();
    let mut best = f64::INFINITY;
    for k in 0..5 {
        best = best.min(run()?);
        if k >= 1 && start.elapsed().as_secs_f64() > 2.0 {
            break;
        }
    }
    Ok(best)
}

fn timed(f: impl FnOnce() -> Result<(), String>) -> Result<f64, String> {
    let t = Instant::now();
    f()?;
    Ok(t.elapsed().as_secs_f64() * 1e3)
}

/// What to measure.
pub(crate) struct Options {
    pub json: bool,
    pub points: usize,
    pub prospero: Option<PathBuf>,
    pub only: Option<String>,
    pub backends: Vec<String>,
    pub tiles: Vec<u32>,
}

/// The backends to measure: those asked for (all available by default).
fn backends(names: &[String]) -> Result<Vec<Backend>, String> {
    if names.is_empty() {
        return Ok(Backend::available());
    }
    names
        .iter()
        .map(|n| {
            n.parse::<Backend>()
                .and_then(Backend::check)
                .map_err(|e| e.to_string())
        })
        .collect()
}

pub(crate) fn eval(o: Options) -> Result<ExitCode, String> {
    let Options {
        json,
        points,
        prospero,
        only,
        backends: names,
        tiles,
    } = o;
    let list = backends(&names)?;
    // A workload runs when the filter names it, a prefix of it, or a group it belongs to.
    let wanted = |w: &str| {
        only.as_deref()
            .is_none_or(|p| w.starts_with(p) || p.starts_with(w))
    };
    let points = points.clamp(1_000, 20_000_000);
    let mut rows = Vec::new();
    let mut notes = Vec::new();
    let level = Level::default_level();
    let b = level.bounds();
    let mut rng = Rng::new(7);
    let pts: Vec<Vec2> = (0..points)
        .map(|_| Vec2::new(rng.range(b.min.x, b.max.x), rng.range(b.min.y, b.max.y)))
        .collect();

    if wanted("default") {
        let mut terrain = level.terrain().map_err(|e| e.to_string())?;
        terrain_rows(&mut terrain, &pts, "default", &list, &mut rows, &mut notes)?;
    }
    if wanted("default-10k") {
        let (mut terrain, _) = crate::bench::build(&level, 10_000)?;
        terrain_rows(
            &mut terrain,
            &pts,
            "default-10k",
            &list,
            &mut rows,
            &mut notes,
        )?;
    }

    let path = prospero.unwrap_or_else(|| PathBuf::from("tests/data/prospero.vm"));
    match craterfield::files::read_text(&path, craterfield::field2d::import::MAX_VM_BYTES as u64) {
        _ if !wanted("prospero") => {}
        Ok(text) => {
            let parts = (wanted("prospero-brute"), wanted("prospero-specialized"));
            prospero_rows(&text, &path, &list, parts, &tiles, &mut rows, &mut notes)?
        }
        Err(e) => notes.push(format!(
            "prospero workloads skipped: cannot read {} ({e}); pass --prospero FILE",
            path.display()
        )),
    }

    if json {
        let report = Report { rows };
        println!(
            "{}",
            serde_json::to_string(&report).map_err(|e| e.to_string())?
        );
    } else {
        print_table(&rows, &notes);
    }
    Ok(ExitCode::SUCCESS)
}

fn row(workload: &str, implementation: &str, threads: usize, ms: f64, points: usize) -> Row {
    Row {
        workload: workload.into(),
        implementation: implementation.into(),
        threads,
        ms,
        points_per_s: points as f64 / (ms / 1e3),
    }
}

fn terrain_rows(
    terrain: &mut Terrain<Graph>,
    pts: &[Vec2],
    workload: &str,
    list: &[Backend],
    rows: &mut Vec<Row>,
    notes: &mut Vec<String>,
) -> Result<(), String> {
    let mut d = vec![0.0f32; pts.len()];
    let mut s = vec![
        Sample {
            distance: 0.0,
            gradient: Vec2::ZERO,
            material: 0
        };
        pts.len()
    ];
    // Build every cell's tapes once, outside the timings.
    terrain.distances(pts, &mut d).map_err(|e| e.to_string())?;
    let mut first: Option<Vec<f32>> = None;
    for &backend in list {
        terrain.set_backend(backend).map_err(|e| e.to_string())?;
        let ms = best_ms(|| timed(|| terrain.distances(pts, &mut d).map_err(|e| e.to_string())))?;
        rows.push(row(workload, backend.name(), 1, ms, pts.len()));
        let ms = best_ms(|| timed(|| terrain.samples(pts, &mut s).map_err(|e| e.to_string())))?;
        rows.push(row(
            &format!("{workload}-grad"),
            backend.name(),
            1,
            ms,
            pts.len(),
        ));
        match &first {
            None => first = Some(d.clone()),
            Some(f) => {
                let same = f.iter().zip(&d).all(|(a, b)| a.to_bits() == b.to_bits());
                if !same {
                    return Err(format!("{workload}: {backend} disagrees with scalar"));
                }
            }
        }
    }
    // Context: the graph walker (the reference) and the unspecialized tapes.
    let sample = &pts[..pts.len().min(100_000)];
    let ms = timed(|| {
        let mut acc = 0.0f32;
        for &p in sample {
            acc += terrain.distance_brute_force(p);
        }
        std::hint::black_box(acc);
        Ok(())
    })?;
    notes.push(format!(
        "{workload}: reference walker (brute force over the event list, one point at a time) {:.0} points/s",
        sample.len() as f64 / (ms / 1e3)
    ));
    // The same batches without per-cell specialization: every point runs the whole base
    // tape, so evaluation dominates and the backends' ratio shows the lanes' own gain.
    terrain.set_specialize(false);
    terrain.distances(pts, &mut d).map_err(|e| e.to_string())?;
    let mut unspecialized = Vec::new();
    for &backend in list {
        terrain.set_backend(backend).map_err(|e| e.to_string())?;
        let ms = best_ms(|| timed(|| terrain.distances(pts, &mut d).map_err(|e| e.to_string())))?;
        unspecialized.push(format!("{backend} {ms:.1} ms"));
    }
    notes.push(format!(
        "{workload}: without per-cell specialization: {}",
        unspecialized.join(", ")
    ));
    terrain.set_specialize(true);
    Ok(())
}

fn prospero_rows(
    text: &str,
    path: &Path,
    list: &[Backend],
    (do_brute, do_spec): (bool, bool),
    tiles: &[u32],
    rows: &mut Vec<Row>,
    notes: &mut Vec<String>,
) -> Result<(), String> {
    let graph = graph_from_vm(text).map_err(|e| format!("{}: {e}", path.display()))?;
    let program = graph.program();
    let pixels = 1024 * 1024;
    let brute = ImageOptions {
        tiles: vec![],
        ..ImageOptions::default()
    };
    let mut spec = ImageOptions::default();
    if !tiles.is_empty() {
        spec.tiles = tiles.to_vec();
    }
    let mut check = ImageCheck::default();
    let fused = program.fuse().tape(Outputs::Value);
    let plain = program.tape(Outputs::Value);
    notes.push(format!(
        "prospero: {} SSA instructions; tape {} instructions ({} without fusion), {} registers",
        program.len(),
        fused.len(),
        plain.len(),
        fused.registers()
    ));
    for &backend in list.iter().filter(|_| do_brute) {
        let o = ImageOptions {
            backend,
            ..brute.clone()
        };
        let mut img = Vec::new();
        let ms = best_ms(|| {
            timed(|| {
                img = inside_image(&program, &o).map_err(|e| e.to_string())?.0;
                Ok(())
            })
        })?;
        check.check(&format!("prospero-brute {backend}"), &img)?;
        rows.push(row("prospero-brute", backend.name(), 1, ms, pixels));
    }
    for &backend in list.iter().filter(|_| do_spec) {
        for threads in [1, 2] {
            let o = ImageOptions {
                backend,
                threads,
                ..spec.clone()
            };
            let mut out = None;
            let ms = best_ms(|| {
                timed(|| {
                    out = Some(inside_image(&program, &o).map_err(|e| e.to_string())?);
                    Ok(())
                })
            })?;
            let (img, stats) = out.ok_or("no image")?;
            check.check(&format!("prospero-specialized {backend}"), &img)?;
            rows.push(row(
                "prospero-specialized",
                backend.name(),
                threads,
                ms,
                pixels,
            ));
            if backend == Backend::widest() && threads == 1 {
                notes.push(format!(
                    "prospero-specialized: {} tiles filled, {} specialized, {} pixels evaluated, {:.1} instructions per evaluated pixel",
                    stats.filled_tiles,
                    stats.specialized,
                    stats.evaluated_pixels,
                    stats.instructions as f64 / stats.evaluated_pixels.max(1) as f64
                ));
            }
        }
    }
    fusion_note(&program, notes)?;
    peers(text, rows, notes, &mut check)?;
    let inside = check
        .reference
        .as_ref()
        .map_or(0, |r| r.iter().filter(|b| **b).count());
    notes.push(format!(
        "prospero: {inside} of {pixels} pixels inside, the same image from every craterfield run"
    ));
    notes.append(&mut check.peer_diffs);
    Ok(())
}

/// Every render of the image must equal the first; a peer's differences are reported.
#[derive(Default)]
struct ImageCheck {
    reference: Option<Vec<bool>>,
    peer_diffs: Vec<String>,
}

impl ImageCheck {
    fn check(&mut self, what: &str, img: &[bool]) -> Result<(), String> {
        let Some(r) = &self.reference else {
            self.reference = Some(img.to_vec());
            return Ok(());
        };
        let diff = r.iter().zip(img).filter(|(a, b)| a != b).count() + r.len().abs_diff(img.len());
        if diff == 0 {
            Ok(())
        } else if what.starts_with("fidget") {
            self.peer_diffs.push(format!(
                "{what}: {diff} pixels differ from craterfield's image"
            ));
            Ok(())
        } else {
            Err(format!("{what}: {diff} pixels differ from the first image"))
        }
    }
}

/// What fusion saves on the whole prospero tape (widest backend), in all and pattern by
/// pattern (each pattern alone on top of none).
fn fusion_note(
    program: &craterfield::field2d::tape::Program,
    notes: &mut Vec<String>,
) -> Result<(), String> {
    use craterfield::field2d::tape::FuseOptions;
    let b = Backend::widest();
    let pts: Vec<Vec2> = (0..256 * 256)
        .map(|k| {
            let (i, j) = (k % 256, k / 256);
            Vec2::new(
                (i as f32 + 0.5) / 128.0 - 1.0,
                1.0 - (j as f32 + 0.5) / 128.0,
            )
        })
        .collect();
    let mut out = vec![0.0; pts.len()];
    let none = FuseOptions::NONE;
    let configs = [
        ("none", none),
        (
            "hypot only",
            FuseOptions {
                hypot: true,
                ..none
            },
        ),
        (
            "affine only",
            FuseOptions {
                affine: true,
                ..none
            },
        ),
        (
            "chains only",
            FuseOptions {
                chains: true,
                ..none
            },
        ),
        ("all", FuseOptions::default()),
    ];
    let mut parts = Vec::new();
    let mut base = 0.0;
    for (name, o) in configs {
        let tape = program.fuse_with(o).tape(Outputs::Value);
        let ms =
            best_ms(|| timed(|| tape.distances(&pts, &mut out, b).map_err(|e| e.to_string())))?;
        if name == "none" {
            base = ms;
        }
        parts.push(format!(
            "{name} {} instructions {ms:.2} ms ({:+.0}%)",
            tape.len(),
            (ms / base - 1.0) * 100.0
        ));
    }
    notes.push(format!(
        "fusion ({b}, whole prospero tape, 65,536 points): {}",
        parts.join("; ")
    ));
    Ok(())
}

#[cfg(feature = "peers")]
fn peers(
    text: &str,
    rows: &mut Vec<Row>,
    notes: &mut Vec<String>,
    check: &mut ImageCheck,
) -> Result<(), String> {
    use crate::peers;
    let pixels = 1024 * 1024;
    type Run = fn(&str, u32) -> Result<peers::PeerRun, String>;
    let brutes: [(&str, Run); 2] = [
        ("fidget-jit", peers::jit_brute),
        ("fidget-vm", peers::vm_brute),
    ];
    for (name, f) in brutes {
        let mut img = Vec::new();
        let ms = best_ms(|| {
            let r = f(text, 1024)?;
            img = r.image;
            Ok(r.ms)
        })?;
        check.check(&format!("{name} brute"), &img)?;
        rows.push(row("prospero-brute", name, 1, ms, pixels));
    }
    type Pruned = fn(&str, u32, usize) -> Result<peers::PeerRun, String>;
    let pruned: [(&str, Pruned); 2] = [
        ("fidget-jit", peers::jit_pruned),
        ("fidget-vm", peers::vm_pruned),
    ];
    for (name, f) in pruned {
        for threads in [1, 2] {
            let mut img = Vec::new();
            let ms = best_ms(|| {
                let r = f(text, 1024, threads)?;
                img = r.image;
                Ok(r.ms)
            })?;
            check.check(&format!("{name} pruned"), &img)?;
            rows.push(row("prospero-specialized", name, threads, ms, pixels));
        }
    }
    notes.push(
        "default, default-10k: no fidget row; the level's noise (integer lattice hash), height profile and polygons (data-dependent loops) have no fidget expression".into(),
    );
    Ok(())
}

#[cfg(not(feature = "peers"))]
fn peers(
    _text: &str,
    _rows: &mut Vec<Row>,
    notes: &mut Vec<String>,
    _check: &mut ImageCheck,
) -> Result<(), String> {
    notes.push(
        "peer rows (fidget 0.5) need the CLI feature `peers`: cargo run --release -p craterfield-cli --features peers -- bench eval".into(),
    );
    Ok(())
}

fn print_table(rows: &[Row], notes: &[String]) {
    println!("craterfield bench eval (release; threads as listed)");
    println!(
        "{:<22} {:<11} {:>7} {:>11} {:>15} {:>10}",
        "workload", "impl", "threads", "ms", "points/s", "vs scalar"
    );
    for r in rows {
        let scalar = rows
            .iter()
            .find(|s| s.workload == r.workload && s.implementation == "scalar" && s.threads == 1)
            .map(|s| format!("{:.1}x", s.ms / r.ms))
            .unwrap_or_default();
        println!(
            "{:<22} {:<11} {:>7} {:>11.2} {:>15.0} {:>10}",
            r.workload, r.implementation, r.threads, r.ms, r.points_per_s, scalar
        );
    }
    for n in notes {
        println!("- {n}");
    }
}
