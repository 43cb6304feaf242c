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
        Tails::of_sorted(&times)
    }

    /// The same of times already in ascending order.
    pub(crate) fn of_sorted(sorted: &[f64]) -> Tails {
        Tails {
            median: sorted.get(sorted.len() / 2).copied().unwrap_or(f64::NAN),
            p95: nearest_rank(sorted, 0.95),
            p99: nearest_rank(sorted, 0.99),
            max: sorted.last().copied().unwrap_or(f64::NAN),
        }
    }
}

/// The nearest-rank `q` quantile of `sorted` (ascending): the smallest time with at least
/// that share of the times at or below it; NaN for none.
pub(crate) fn nearest_rank(sorted: &[f64], q: f64) -> f64 {
    let rank = ((sorted.len() as f64 * q).ceil() as usize).clamp(1, sorted.len().max(1));
    sorted.get(rank - 1).copied().unwrap_or(f64::NAN)
}

#[cfg(test)]
mod tests {
    use super::{Tails, nearest_rank};

    #[test]
    fn tails_of_one_to_a_hundred() {
        let t = Tails::of((1..=100).rev().map(f64::from).collect());
        assert_eq!((t.median, t.p95, t.p99, t.max), (51.0, 95.0, 99.0, 100.0));
        assert!(Tails::of(Vec::new()).median.is_nan());
        let thousand: Vec<f64> = (1..=1000).map(f64::from).collect();
        assert_eq!(nearest_rank(&thousand, 0.999), 999.0);
    }
}
