//! [`Tails`]: median, p95, p99 and max of a series of timings, for the `--bench` reports
//! and the side panels.

/// Order statistics of a sample.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Tails {
    /// Number of values.
    pub count: usize,
    /// The median.
    pub median: f64,
    /// The 95th percentile.
    pub p95: f64,
    /// The 99th percentile.
    pub p99: f64,
    /// The largest value.
    pub max: f64,
}

impl Tails {
    /// The tails of `values` (NaNs are dropped); all zero when there are none.
    pub fn of(values: &[f64]) -> Tails {
        let mut v: Vec<f64> = values.iter().copied().filter(|x| !x.is_nan()).collect();
        if v.is_empty() {
            return Tails::default();
        }
        v.sort_by(f64::total_cmp);
        let at = |q: f64| v[((v.len() - 1) as f64 * q).round() as usize];
        Tails {
            count: v.len(),
            median: at(0.5),
            p95: at(0.95),
            p99: at(0.99),
            max: v[v.len() - 1],
        }
    }

    /// `median p95 p99 max` with two decimals, for a report row.
    pub fn row(&self) -> String {
        format!(
            "{:>8.2} {:>8.2} {:>8.2} {:>8.2}",
            self.median, self.p95, self.p99, self.max
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tails_of_a_ramp() {
        let v: Vec<f64> = (1..=100).map(f64::from).collect();
        let t = Tails::of(&v);
        assert_eq!(t.count, 100);
        assert_eq!(t.median, 51.0);
        assert_eq!(t.p95, 95.0);
        assert_eq!(t.p99, 99.0);
        assert_eq!(t.max, 100.0);
        assert_eq!(Tails::of(&[f64::NAN]), Tails::default());
    }
}
