//! Fixed-point storage of world coordinates: 1/256 world unit in an `i32`, exact in `f32`.
//!
//! Events are stored in fixed point so that a replay (or a network peer) reproduces the exact
//! same numbers. Every valid fixed-point value has magnitude at most `2^24 - 1`, so
//! `v as f32 / 256.0` is exact: converting back to `f32` never rounds.

use thiserror::Error;

/// One world unit in fixed point.
pub const FIXED_ONE: i32 = 256;

/// The largest valid fixed-point magnitude, `2^24 - 1` (just under 65536 world units).
pub const FIXED_MAX: i32 = (1 << 24) - 1;

/// Why a float could not be converted to fixed point.
#[derive(Clone, Copy, Debug, PartialEq, Error)]
#[non_exhaustive]
pub enum QuantError {
    /// The value is NaN or infinite.
    #[error("value {value} is not finite")]
    NotFinite {
        /// The offending value.
        value: f32,
    },
    /// The value's magnitude exceeds [`FIXED_MAX`] / 256 world units.
    #[error("value {value} is out of the fixed-point range (|v| <= {max} world units)")]
    OutOfRange {
        /// The offending value.
        value: f32,
        /// The largest representable magnitude, in world units.
        max: f32,
    },
}

/// Whether `v` is a valid fixed-point value (`|v| <= FIXED_MAX`).
#[inline]
pub fn in_range(v: i32) -> bool {
    (-FIXED_MAX..=FIXED_MAX).contains(&v)
}

/// Converts fixed point to world units. Exact for every valid value (`|v| <= FIXED_MAX`).
#[inline]
pub fn to_f32(v: i32) -> f32 {
    v as f32 / FIXED_ONE as f32
}

/// Converts world units to fixed point, rounding to nearest (ties away from zero).
///
/// Rejects NaN, infinities and values whose rounded magnitude exceeds [`FIXED_MAX`].
pub fn from_f32(x: f32) -> Result<i32, QuantError> {
    if !x.is_finite() {
        return Err(QuantError::NotFinite { value: x });
    }
    // Multiplying by a power of two is exact (no overflow: |x| < 2^128 / 256 is checked below).
    let scaled = (x * FIXED_ONE as f32).round();
    if scaled.abs() > FIXED_MAX as f32 {
        return Err(QuantError::OutOfRange {
            value: x,
            max: to_f32(FIXED_MAX),
        });
    }
    // |scaled| <= 2^24 - 1 and integral: the conversion is exact.
    Ok(scaled as i32)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trips_and_rounds_to_nearest() {
        assert_eq!(from_f32(1.0), Ok(256));
        assert_eq!(from_f32(-2.5), Ok(-640));
        assert_eq!(from_f32(0.001), Ok(0));
        assert_eq!(from_f32(1.0 / 512.0), Ok(1));
        assert_eq!(from_f32(0.9 / 256.0), Ok(1));
        for v in [-FIXED_MAX, -1, 0, 1, 12345, FIXED_MAX] {
            assert_eq!(from_f32(to_f32(v)), Ok(v));
        }
        assert_eq!(to_f32(FIXED_MAX) * 256.0, FIXED_MAX as f32);
    }

    #[test]
    fn rejects_bad_values_naming_them() {
        let e = from_f32(f32::NAN).unwrap_err();
        assert!(e.to_string().contains("NaN"), "{e}");
        let e = from_f32(f32::INFINITY).unwrap_err();
        assert!(e.to_string().contains("inf"), "{e}");
        let e = from_f32(70000.0).unwrap_err();
        assert!(e.to_string().contains("70000"), "{e}");
        assert!(from_f32(65535.99).is_ok());
        assert!(from_f32(65536.0).is_err());
        assert!(from_f32(-1e30).is_err());
    }
}
