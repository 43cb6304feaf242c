//! The `craterfield` command-line tool: the demo (default), level checks and benchmarks.

mod barrage;
mod bench;
mod bench_eval;
mod demo;
#[cfg(feature = "peers")]
mod peers;
mod rng;

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

#[derive(Parser)]
#[command(
    name = "craterfield",
    version,
    about = "Destructible 2D SDF terrain: demo, level checks, benchmarks"
)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Subcommand)]
enum Command {
    /// Load the default level, fire a scripted barrage, render it and write a summary.
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
    },
    /// Level files.
    Level {
        #[command(subcommand)]
        command: LevelCommand,
    },
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
enum BenchCommand {
    /// Single-point queries, raycasts and explosion inserts on the default level.
    Field {
        /// Print one JSON object instead of a table.
        #[arg(long)]
        json: bool,
        /// Query points per configuration.
        #[arg(long, default_value_t = 400_000)]
        points: usize,
    },
    /// The tape evaluators on every backend (and fidget with the feature `peers`).
    Eval {
        /// Print one JSON object instead of a table.
        #[arg(long)]
        json: bool,
        /// Random points of the `default` workloads.
        #[arg(long, default_value_t = 1_000_000)]
        points: usize,
        /// The prospero expression (default: ../shared/data/prospero.vm).
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
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command.unwrap_or(Command::Demo {
        out: PathBuf::from("out/demo"),
        events: 600,
        width: 3840,
        level: None,
    }) {
        Command::Demo {
            out,
            events,
            width,
            level,
        } => demo::run(&out, events, width, level.as_deref()),
        Command::Level {
            command: LevelCommand::Check { file },
        } => level_check(&file),
        Command::Bench {
            command: BenchCommand::Field { json, points },
        } => bench::field(json, points),
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
    };
    match result {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

fn level_check(file: &std::path::Path) -> Result<ExitCode, String> {
    match craterfield::field2d::Level::load(file) {
        Ok(level) => {
            let info = level.graph().root_info();
            println!(
                "{}: ok: level \"{}\", {} nodes, {:?} distance, Lipschitz bound {:.3}",
                file.display(),
                level.name(),
                level.graph().node_count(),
                info.exactness,
                info.lipschitz
            );
            Ok(ExitCode::SUCCESS)
        }
        Err(e) => {
            println!("{}: {e}", file.display());
            Ok(ExitCode::FAILURE)
        }
    }
}
