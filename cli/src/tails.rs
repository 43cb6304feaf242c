//! Median and tails (p95, p99, max) of measured times, the figures every benchmark table
//! prints beside each other.

use serde::Serialize;

/// Median, p95, p99 and max of a set of times (in the unit they were given in).
#[derive(Serialize, Clone, Copy, Debug)]
pub(crate) struct Tails {
    pub median: f64,
    pub p95: f64,
    pub p99: f64,
    pub max: f64,
}

impl Tails {
    /// The figures of `times` (NaN for none). Percentiles are nearest-rank: the smallest
    /// time with at least that share of the times at or below it; the median is the upper
    /// middle one.
    pub(crate) fn of(mut times: Vec<f64>) -> Tails {
        times.sort_by(f64::total_cmp);
        let at = |q: f64| {
            let rank = ((times.len() as f64 * q).ceil() as usize).clamp(1, times.len().max(1));
            times.get(rank - 1).copied().unwrap_or(f64::NAN)
        };
        Tails {
            median: times.get(times.len() / 2).copied().unwrap_or(f64::NAN),
            p95: at(0.95),
            p99: at(0.99),
            max: times.last().copied().unwrap_or(f64::NAN),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Tails;

    #[test]
    fn tails_of_one_to_a_hundred() {
        let t = Tails::of((1..=100).rev().map(f64::from).collect());
        assert_eq!((t.median, t.p95, t.p99, t.max), (51.0, 95.0, 99.0, 100.0));
        assert!(Tails::of(Vec::new()).median.is_nan());
    }
}
