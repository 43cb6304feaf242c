//! The result of a comparison: every metric's value, the thresholds it exceeded, and the
//! per-pixel error maps the heat-map is drawn from.

use std::fmt;

use serde::Serialize;

use super::DiffOptions;
use super::metrics::PixelStats;

/// One of the checked metrics.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
#[non_exhaustive]
pub enum Metric {
    /// Fraction of pixels whose error exceeds the pixel tolerance.
    DifferingFraction,
    /// Mean per-pixel error.
    Mean,
    /// Largest per-pixel error.
    Max,
    /// The configured percentile of the per-pixel error.
    Percentile,
    /// Mean FLIP perceptual error.
    Flip,
}

impl Metric {
    /// The metric's name as reports print it.
    pub fn name(self) -> &'static str {
        match self {
            Metric::DifferingFraction => "differing_fraction",
            Metric::Mean => "mean",
            Metric::Max => "max",
            Metric::Percentile => "percentile",
            Metric::Flip => "flip",
        }
    }
}

/// A metric over its threshold.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Failure {
    /// Which metric.
    pub metric: Metric,
    /// Its value.
    pub value: f64,
    /// The threshold it exceeded.
    pub limit: f64,
}

impl fmt::Display for Failure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} {} > {}",
            self.metric.name(),
            fmt_value(self.value),
            fmt_value(self.limit)
        )
    }
}

/// What [`super::compare`] measured.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DiffReport {
    /// Image width, pixels.
    pub width: u32,
    /// Image height, pixels.
    pub height: u32,
    /// The pixel tolerance used.
    pub pixel_tolerance: u8,
    /// Pixels whose error exceeds the tolerance.
    pub differing_pixels: u64,
    /// `differing_pixels` over all pixels (0..=1).
    pub differing_fraction: f64,
    /// Mean per-pixel error (0..=255).
    pub mean: f64,
    /// Largest per-pixel error.
    pub max: u8,
    /// Which percentile `percentile_value` is.
    pub percentile: f64,
    /// That percentile of the per-pixel error (nearest rank).
    pub percentile_value: u8,
    /// Mean FLIP error (0..=1).
    pub flip: f64,
    /// Largest FLIP error of any pixel.
    pub flip_max: f64,
    /// Whether FLIP was computed. It is not on WebAssembly, where its C++ implementation
    /// does not build; `flip` and `flip_max` are 0 then, and only the pixel statistics
    /// are checked.
    pub flip_measured: bool,
    /// The thresholds exceeded, in the order of [`Metric`].
    pub failures: Vec<Failure>,
    #[serde(skip)]
    errors: Vec<u8>,
    #[serde(skip)]
    flip_map: Vec<f32>,
}

impl DiffReport {
    pub(crate) fn new(
        (width, height): (u32, u32),
        errors: Vec<u8>,
        stats: PixelStats,
        flip_map: Option<Vec<f32>>,
        options: &DiffOptions,
    ) -> DiffReport {
        let flip_measured = flip_map.is_some();
        let flip_map = flip_map.unwrap_or_default();
        let pixels = errors.len().max(1) as f64;
        let flip = flip_map.iter().map(|&v| f64::from(v)).sum::<f64>() / pixels;
        let flip_max = flip_map.iter().copied().fold(0.0f32, f32::max);
        let mut report = DiffReport {
            width,
            height,
            pixel_tolerance: options.pixel_tolerance,
            differing_pixels: stats.differing,
            differing_fraction: stats.differing as f64 / pixels,
            mean: stats.mean,
            max: stats.max,
            percentile: options.percentile,
            percentile_value: stats.percentile_value,
            flip,
            flip_max: f64::from(flip_max),
            flip_measured,
            failures: Vec::new(),
            errors,
            flip_map,
        };
        report.failures = report.check(options);
        report
    }

    /// The report of two identical images of this size (every metric zero).
    #[cfg(not(target_family = "wasm"))]
    pub(crate) fn identical(width: u32, height: u32, options: &DiffOptions) -> DiffReport {
        let pixels = width as usize * height as usize;
        let stats = PixelStats {
            differing: 0,
            mean: 0.0,
            max: 0,
            percentile_value: 0,
        };
        DiffReport::new(
            (width, height),
            vec![0; pixels],
            stats,
            Some(vec![0.0; pixels]),
            options,
        )
    }

    fn check(&self, o: &DiffOptions) -> Vec<Failure> {
        [
            (
                Metric::DifferingFraction,
                self.differing_fraction,
                o.max_differing_fraction,
            ),
            (Metric::Mean, self.mean, o.max_mean),
            (Metric::Max, f64::from(self.max), o.max_error),
            (
                Metric::Percentile,
                f64::from(self.percentile_value),
                o.max_percentile,
            ),
            (Metric::Flip, self.flip, o.max_flip),
        ]
        .into_iter()
        .filter(|&(metric, _, _)| metric != Metric::Flip || self.flip_measured)
        // A score that is not a number fails: it cannot be shown to be within its limit.
        .filter(|&(_, value, limit)| value.is_nan() || value > limit)
        .map(|(metric, value, limit)| Failure {
            metric,
            value,
            limit,
        })
        .collect()
    }

    /// Whether every metric is within its threshold.
    pub fn passed(&self) -> bool {
        self.failures.is_empty()
    }

    /// The failures joined into one line (`mean 3 > 0.5; flip 0.02 > 0.01`), empty when the
    /// report passed.
    pub fn failure_summary(&self) -> String {
        self.failures
            .iter()
            .map(Failure::to_string)
            .collect::<Vec<_>>()
            .join("; ")
    }

    /// Per-pixel error (largest channel difference), row-major.
    pub fn pixel_errors(&self) -> &[u8] {
        &self.errors
    }

    /// Per-pixel FLIP error in `[0, 1]`, row-major.
    pub fn flip_map(&self) -> &[f32] {
        &self.flip_map
    }
}

impl fmt::Display for DiffReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "{}x{} pixels, {} differ by more than {} ({:.4}%)",
            self.width,
            self.height,
            self.differing_pixels,
            self.pixel_tolerance,
            self.differing_fraction * 100.0
        )?;
        writeln!(
            f,
            "error: mean {:.4}, max {}, p{} {}",
            self.mean,
            self.max,
            fmt_value(self.percentile),
            self.percentile_value
        )?;
        if self.flip_measured {
            writeln!(f, "FLIP: mean {:.5}, max {:.4}", self.flip, self.flip_max)?;
        } else {
            writeln!(f, "FLIP: not measured on this target")?;
        }
        if self.passed() {
            write!(f, "PASS")
        } else {
            write!(f, "FAIL: {}", self.failure_summary())
        }
    }
}

/// A number without trailing zeros (`3`, `0.5`, `0.0012`, `inf`).
fn fmt_value(v: f64) -> String {
    if v.is_infinite() {
        return "inf".into();
    }
    let s = format!("{v:.6}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}
