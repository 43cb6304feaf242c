//! `craterfield diff A.png B.png`: compares two images with `visdiff`, prints the report
//! (or JSON), optionally writes the difference heat-map, and exits 0 when every metric is
//! within its threshold, 1 when some is over, 2 when the images cannot be compared.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use craterfield::visdiff::{self, DiffOptions, DiffReport, HeatSource};
use serde::Serialize;

/// The command's arguments.
#[derive(clap::Args)]
pub(crate) struct Options {
    /// The reference image.
    pub a: PathBuf,
    /// The image compared with it.
    pub b: PathBuf,
    /// Write the difference heat-map (PNG) here.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// What the heat-map shows.
    #[arg(long, value_enum, default_value_t = Heat::Pixel)]
    pub heat: Heat,
    /// A pixel differs when some channel differs by more than this (0..=255).
    #[arg(long, default_value_t = DiffOptions::default().pixel_tolerance)]
    pub tolerance: u8,
    /// Largest accepted fraction (0..=1) of differing pixels.
    #[arg(long, default_value_t = DiffOptions::default().max_differing_fraction)]
    pub max_differing: f64,
    /// Largest accepted mean per-pixel error (0..=255).
    #[arg(long, default_value_t = DiffOptions::default().max_mean)]
    pub max_mean: f64,
    /// Largest accepted per-pixel error anywhere (0..=255; inf = unchecked).
    #[arg(long, default_value_t = DiffOptions::default().max_error)]
    pub max_error: f64,
    /// Which percentile of the per-pixel error to check (0 < p <= 100).
    #[arg(long, default_value_t = DiffOptions::default().percentile)]
    pub percentile: f64,
    /// Largest accepted value of that percentile (0..=255).
    #[arg(long, default_value_t = DiffOptions::default().max_percentile)]
    pub max_percentile: f64,
    /// Largest accepted FLIP score (mean perceptual error, 0..=1).
    #[arg(long, default_value_t = DiffOptions::default().max_flip)]
    pub max_flip: f64,
    /// Pixels per degree of visual angle the FLIP score assumes.
    #[arg(long, default_value_t = DiffOptions::default().pixels_per_degree)]
    pub ppd: f32,
    /// Print one JSON object instead of the text report.
    #[arg(long)]
    pub json: bool,
}

/// The heat-map's source, as the command line names it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub(crate) enum Heat {
    /// Largest channel difference, scaled to the largest in the pair.
    Pixel,
    /// FLIP perceptual error, 0..1.
    Perceptual,
}

#[derive(Serialize)]
struct JsonReport<'a> {
    a: &'a Path,
    b: &'a Path,
    passed: bool,
    heatmap: Option<&'a Path>,
    #[serde(flatten)]
    report: &'a DiffReport,
}

/// Exit code for images that cannot be compared.
const CANNOT_COMPARE: u8 = 2;

pub(crate) fn run(options: &Options) -> Result<ExitCode, String> {
    match diff(options) {
        Ok(report) => Ok(if report.passed() {
            ExitCode::SUCCESS
        } else {
            ExitCode::FAILURE
        }),
        Err(e) => {
            eprintln!("error: {e}");
            Ok(ExitCode::from(CANNOT_COMPARE))
        }
    }
}

fn diff(o: &Options) -> Result<DiffReport, String> {
    let diff_options = DiffOptions {
        pixel_tolerance: o.tolerance,
        max_differing_fraction: o.max_differing,
        max_mean: o.max_mean,
        max_error: o.max_error,
        percentile: o.percentile,
        max_percentile: o.max_percentile,
        max_flip: o.max_flip,
        pixels_per_degree: o.ppd,
    };
    let a = visdiff::load_png(&o.a).map_err(|e| e.to_string())?;
    let b = visdiff::load_png(&o.b).map_err(|e| e.to_string())?;
    let report = visdiff::compare(&a, &b, &diff_options)
        .map_err(|e| format!("{} vs {}: {e}", o.a.display(), o.b.display()))?;
    if let Some(out) = &o.out {
        let source = match o.heat {
            Heat::Pixel => HeatSource::Pixel,
            Heat::Perceptual => HeatSource::Perceptual,
        };
        visdiff::save_png(&visdiff::heatmap(&report, source), out).map_err(|e| e.to_string())?;
    }
    print_report(o, &report)?;
    Ok(report)
}

fn print_report(o: &Options, report: &DiffReport) -> Result<(), String> {
    if o.json {
        let json = JsonReport {
            a: &o.a,
            b: &o.b,
            passed: report.passed(),
            heatmap: o.out.as_deref(),
            report,
        };
        let text = serde_json::to_string_pretty(&json).map_err(|e| e.to_string())?;
        println!("{text}");
    } else {
        println!("{} vs {}", o.a.display(), o.b.display());
        println!("{report}");
        if let Some(out) = &o.out {
            println!("heat-map: {}", out.display());
        }
    }
    Ok(())
}
