//! The `craterfield` command-line tool: the demo (default), level checks, replays and
//! benchmarks.

mod barrage;
mod bench;
mod bench_eval;
mod bench_fidelity;
#[cfg(feature = "peers")]
mod bench_field_long;
#[cfg(feature = "peers")]
mod bench_field_peers;
mod bench_march3d;
mod bench_reference3d;
mod bench_render2d;
mod bench_sim;
mod demo;
mod diff_cmd;
mod fidelity_scenes;
#[cfg(feature = "peers")]
mod field_scene;
mod frame;
mod march3d_cmd;
#[cfg(feature = "peers")]
mod peers;
#[cfg(feature = "peers")]
mod peers_field;
#[cfg(feature = "peers")]
mod peers_sim;
mod render_cmd;
mod render_frame;
mod replay_cmd;
mod rng;
mod script;
mod tails;

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

#[derive(Parser)]
#[command(
    name = "craterfield",
    version,
    about = "Destructible 2D SDF terrain and 3D SDF worlds: demo, level checks, replays, 3D renders, benchmarks"
)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Subcommand)]
enum Command {
    /// Load the default level, fire a scripted barrage, render it and write a summary; then
    /// play, record and picture a scripted four-player match (match.replay, match.png).
    Demo {
        /// Output folder.
        #[arg(long, default_value = "out/demo")]
        out: PathBuf,
        /// Number of explosions and fills in the barrage.
        #[arg(long, default_value_t = 600)]
        events: usize,
        /// Rendered image width in pixels (the world is fitted to it).
        #[arg(long, default_value_t = 3840)]
        width: u32,
        /// A level file to use instead of the embedded default level.
        #[arg(long)]
        level: Option<PathBuf>,
        /// Ticks of the scripted match (60 per second; 0 skips the match).
        #[arg(long, default_value_t = DEMO_MATCH_TICKS)]
        match_ticks: u32,
    },
    /// Replay files: verify, describe, render.
    Replay {
        #[command(subcommand)]
        command: ReplayCommand,
    },
    /// Level files.
    Level {
        #[command(subcommand)]
        command: LevelCommand,
    },
    /// Compare two images (pixel statistics and the FLIP perceptual score): exit 0 when
    /// within the thresholds, 1 when over, 2 when they cannot be compared.
    Diff(diff_cmd::Options),
    /// Render a level (after a seeded barrage, or at a replay's tick) in any mode, scale and
    /// view, on the GPU or the CPU; `--compare-exact` measures it against the exact render.
    Render(Box<render_cmd::Options>),
    /// Render a 3D SDF scene (builtin or RON file) with the CPU sphere tracer or the GPU
    /// raymarcher.
    March3d(march3d_cmd::Options),
    /// Release-mode benchmarks.
    Bench {
        #[command(subcommand)]
        command: BenchCommand,
    },
}

#[derive(Subcommand)]
enum LevelCommand {
    /// Validate a level file: exit 0, or print the error and exit 1.
    Check {
        /// The RON level file.
        file: PathBuf,
    },
}

#[derive(Subcommand)]
enum ReplayCommand {
    /// Re-simulate a replay and compare every stored state hash: exit 0 when all match,
    /// 1 naming the first divergent tick or why the file cannot be read.
    Verify {
        /// The replay file.
        file: PathBuf,
        /// The level it was recorded on (default: the embedded default level).
        #[arg(long)]
        level: Option<PathBuf>,
        /// Exit 0 even when the replay stores no state hash (then nothing is verified).
        #[arg(long)]
        allow_unverified: bool,
    },
    /// Print what a replay holds: version, level, players, length, settings, size.
    Info {
        /// The replay file.
        file: PathBuf,
        /// The level to compare its level hash with (default: the embedded default level).
        #[arg(long)]
        level: Option<PathBuf>,
    },
    /// Re-simulate a replay to a tick and write a PNG of the terrain and the bodies.
    Render {
        /// The replay file.
        file: PathBuf,
        /// The tick to picture (0 = the start; default: the last tick).
        #[arg(long)]
        tick: Option<u32>,
        /// The PNG to write.
        #[arg(long)]
        out: PathBuf,
        /// Image width in pixels (the world is fitted to it).
        #[arg(long, default_value_t = 1920)]
        width: u32,
        /// The level it was recorded on (default: the embedded default level).
        #[arg(long)]
        level: Option<PathBuf>,
    },
}

#[derive(Subcommand)]
enum BenchCommand {
    /// Single-point queries, raycasts and explosion inserts on the default level.
    Field {
        /// Print one JSON object instead of a table.
        #[arg(long)]
        json: bool,
        /// Query points per configuration.
        #[arg(long, default_value_t = 400_000)]
        points: usize,
        /// Also compare with polygon terrain (i_overlay inserts, an edge grid and parry2d
        /// queries) on a 4096x1024 level with 10,000 explosions; needs the feature `peers`.
        #[arg(long)]
        peers: bool,
    },
    /// The tape evaluators on every backend (and fidget with the feature `peers`).
    Eval {
        /// Print one JSON object instead of a table.
        #[arg(long)]
        json: bool,
        /// Random points of the `default` workloads.
        #[arg(long, default_value_t = 1_000_000)]
        points: usize,
        /// The prospero expression (default: tests/data/prospero.vm).
        #[arg(long)]
        prospero: Option<PathBuf>,
        /// Only workloads whose name starts with this (e.g. `prospero`).
        #[arg(long)]
        only: Option<String>,
        /// Only these backends, comma-separated (e.g. `avx2,scalar`).
        #[arg(long, value_delimiter = ',')]
        backends: Vec<String>,
        /// Tile sides of the specialized prospero render, largest first (default 256,64,32).
        #[arg(long, value_delimiter = ',')]
        tiles: Vec<u32>,
    },
    /// The simulation: ms per tick by body count, snapshot and restore, replay and wire
    /// sizes, on the default level after 10,000 explosions, one thread.
    Sim(bench_sim::Options),
    /// Fidelity of the reduced-scale pipeline per reconstruction method and scale against
    /// exact evaluation: mismatched pixels, thin-feature recall, contour offset.
    Fidelity(bench_fidelity::Options),
    /// Render times at 1920x1080 on the default level after 10,000 explosions: full-resolution
    /// direct evaluation vs the reduced-scale pipeline at every scale and mode on the GPU, and
    /// the CPU twin.
    Render2d(bench_render2d::Options),
    /// The 3D renderers: the paper scenes on the CPU tracer (seconds per frame, flops per
    /// cycle, speedup over scalar) and the forest world's emitter optimizations (SDF
    /// evaluations and steps per pixel, GPU time), each switched off in turn.
    March3d(bench_march3d::Options),
}

/// Ticks of the demo's scripted match (20 s at 60 Hz).
const DEMO_MATCH_TICKS: u32 = 1200;

fn main() -> ExitCode {
    quiet_headless_vulkan();
    let cli = Cli::parse();
    let result = match cli.command.unwrap_or(Command::Demo {
        out: PathBuf::from("out/demo"),
        events: 600,
        width: 3840,
        level: None,
        match_ticks: DEMO_MATCH_TICKS,
    }) {
        Command::Demo {
            out,
            events,
            width,
            level,
            match_ticks,
        } => demo::run(&out, events, width, level.as_deref(), match_ticks),
        Command::Replay { command } => match command {
            ReplayCommand::Verify {
                file,
                level,
                allow_unverified,
            } => replay_cmd::verify(&file, level.as_deref(), allow_unverified),
            ReplayCommand::Info { file, level } => replay_cmd::info(&file, level.as_deref()),
            ReplayCommand::Render {
                file,
                tick,
                out,
                width,
                level,
            } => replay_cmd::render(&file, tick, &out, width, level.as_deref()),
        },
        Command::Level {
            command: LevelCommand::Check { file },
        } => level_check(&file),
        Command::Diff(options) => diff_cmd::run(&options),
        Command::Render(options) => render_cmd::run(&options),
        Command::March3d(options) => march3d_cmd::run(&options),
        Command::Bench {
            command:
                BenchCommand::Field {
                    json,
                    points,
                    peers,
                },
        } => bench::field(json, points, peers),
        Command::Bench {
            command:
                BenchCommand::Eval {
                    json,
                    points,
                    prospero,
                    only,
                    backends,
                    tiles,
                },
        } => bench_eval::eval(bench_eval::Options {
            json,
            points,
            prospero,
            only,
            backends,
            tiles,
        }),
        Command::Bench {
            command: BenchCommand::Sim(options),
        } => bench_sim::sim(options),
        Command::Bench {
            command: BenchCommand::Fidelity(options),
        } => bench_fidelity::fidelity(&options),
        Command::Bench {
            command: BenchCommand::Render2d(options),
        } => bench_render2d::run(&options),
        Command::Bench {
            command: BenchCommand::March3d(options),
        } => bench_march3d::run(&options),
    };
    match result {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

/// On a machine without a desktop, Mesa's Vulkan device-selection layer (loaded by the
/// Vulkan loader for every adapter search) tries to reach a Wayland compositor and prints
/// `XDG_RUNTIME_DIR is invalid or not set` twice into every command's output. The layer
/// only orders GPUs by the display they drive, which a headless run does not have, so the
/// process restarts itself once with the layer's own off switch set. Environment variables
/// are set only through the new process, never by mutating this one's.
fn quiet_headless_vulkan() {
    #[cfg(target_os = "linux")]
    {
        use std::os::unix::process::CommandExt;
        let set = |name: &str| std::env::var_os(name).is_some_and(|v| !v.is_empty());
        let runtime_dir_ok =
            std::env::var_os("XDG_RUNTIME_DIR").is_some_and(|d| std::path::Path::new(&d).is_dir());
        if runtime_dir_ok || set("WAYLAND_DISPLAY") || set("DISPLAY") || set("NODEVICE_SELECT") {
            return;
        }
        let Ok(exe) = std::env::current_exe() else {
            return;
        };
        // `exec` returns only when the restart failed: carry on as we are then.
        let _ = std::process::Command::new(exe)
            .args(std::env::args_os().skip(1))
            .env("NODEVICE_SELECT", "1")
            .exec();
    }
}

fn level_check(file: &std::path::Path) -> Result<ExitCode, String> {
    match craterfield::field2d::Level::load(file) {
        Ok(level) => {
            let info = level.graph().root_info();
            let cost = level.graph().eval_cost();
            println!(
                "{}: ok: level \"{}\", {} nodes, {:?} distance, Lipschitz bound {:.3}, cost {} work units per evaluation ({} tape instructions; limit {})",
                file.display(),
                level.name(),
                level.graph().node_count(),
                info.exactness,
                info.lipschitz,
                cost.work,
                cost.instructions,
                craterfield::field2d::MAX_EVAL_WORK
            );
            Ok(ExitCode::SUCCESS)
        }
        Err(e) => {
            println!("{}: {e}", file.display());
            Ok(ExitCode::FAILURE)
        }
    }
}
