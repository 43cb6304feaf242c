//! WGSL text helpers shared by every emitter: exact number literals and module-scope names.
//!
//! Literals round-trip bit for bit: an `f32` is printed as the shortest decimal that parses
//! back to the same bits (Rust's float formatting guarantees that), with the `f` suffix so
//! WGSL reads it as `f32` directly instead of rounding through an abstract float. WGSL has no
//! literal for infinities or NaN, and a constant expression that produces one is an error, so
//! those are built at run time from their bits ([`f32_expr`] and [`NONFINITE_HELPER`]).

use glam::Vec2;
use thiserror::Error;

/// Prefix of every module-scope name an emitter defines, so emitted text never clashes with
/// the hand-written WGSL it is concatenated with.
pub const PREFIX: &str = "em_";

/// Module-scope code that turns bits into an `f32` at run time. A private variable is read so
/// that no compiler folds the value as a constant expression (where infinities are errors).
pub const NONFINITE_HELPER: &str = "var<private> em_zero_bits: u32 = 0u;\n\
fn em_f32_bits(bits: u32) -> f32 {\n    return bitcast<f32>(bits | em_zero_bits);\n}\n";

/// Name of the function defined by [`NONFINITE_HELPER`].
pub const NONFINITE_FN: &str = "em_f32_bits";

/// Errors of the WGSL text helpers.
#[derive(Debug, Error, PartialEq)]
#[non_exhaustive]
pub enum WgslError {
    /// A name that is not a plain ASCII WGSL identifier.
    #[error(
        "`{0}` is not a valid WGSL identifier (ASCII letters, digits and `_`, not starting with a digit or `__`)"
    )]
    BadIdentifier(String),
    /// A value that has no WGSL literal.
    #[error("{0} has no WGSL literal (infinities and NaN must be built at run time)")]
    NonFinite(f32),
}

/// The exact WGSL literal of a finite `f32`, e.g. `1.5f`, `-0.0f`, `1e-7f`,
/// `3.4028234663852886e38f`.
pub fn f32_literal(v: f32) -> Result<String, WgslError> {
    if !v.is_finite() {
        return Err(WgslError::NonFinite(v));
    }
    // `{:?}` is the shortest round-tripping decimal, in scientific form for very large and
    // very small magnitudes; every form it prints ("1.5", "1e-7") is a WGSL decimal float
    // literal once suffixed. A browser's WGSL compiler (Tint) reads a literal as a double and
    // refuses one beyond the range of `f32`, which the shortest decimal of `f32::MAX`
    // (3.4028235e38) is: such a value is printed with the digits of its exact double.
    let shortest = format!("{v:?}");
    let beyond_range = shortest
        .parse::<f64>()
        .is_ok_and(|d| d.abs() > f64::from(f32::MAX));
    Ok(if beyond_range {
        format!("{:?}f", f64::from(v))
    } else {
        format!("{shortest}f")
    })
}

/// An `f32` as a WGSL expression: its literal when finite, otherwise a call to
/// [`NONFINITE_FN`] with its bits (the module must then include [`NONFINITE_HELPER`]).
pub fn f32_expr(v: f32) -> String {
    f32_literal(v).unwrap_or_else(|_| format!("{NONFINITE_FN}({}u)", v.to_bits()))
}

/// `vec2<f32>(x, y)` with exact components.
pub fn vec2_expr(v: Vec2) -> String {
    format!("vec2<f32>({}, {})", f32_expr(v.x), f32_expr(v.y))
}

/// An `i32` literal (`i32::MIN` has none: its magnitude does not fit, so it is converted from
/// an abstract integer).
pub fn i32_literal(v: i32) -> String {
    if v == i32::MIN {
        "i32(-2147483648)".to_string()
    } else {
        format!("{v}i")
    }
}

/// A `u32` literal in hexadecimal.
pub fn u32_literal(v: u32) -> String {
    format!("0x{v:x}u")
}

/// True for a plain ASCII WGSL identifier: `[A-Za-z_][A-Za-z0-9_]*`, not `_` alone and not
/// starting with `__` (reserved). Keywords are not checked: prefixed names cannot be one.
pub fn is_identifier(s: &str) -> bool {
    let mut chars = s.chars();
    let Some(first) = chars.next() else {
        return false;
    };
    let valid_start = first.is_ascii_alphabetic() || first == '_';
    valid_start
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
        && s != "_"
        && !s.starts_with("__")
}

/// The module-scope name `em_<name>`, checked to be a valid identifier.
pub fn module_name(name: &str) -> Result<String, WgslError> {
    let full = format!("{PREFIX}{name}");
    if is_identifier(&full) {
        Ok(full)
    } else {
        Err(WgslError::BadIdentifier(full))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn literals_have_the_expected_shapes() {
        assert_eq!(f32_literal(1.5).unwrap(), "1.5f");
        assert_eq!(f32_literal(-0.0).unwrap(), "-0.0f");
        assert_eq!(f32_literal(0.0).unwrap(), "0.0f");
        assert_eq!(f32_literal(1e-7).unwrap(), "1e-7f");
        // Within f32's range as a double (a browser's compiler refuses 3.4028235e38).
        assert_eq!(f32_literal(f32::MAX).unwrap(), "3.4028234663852886e38f");
        assert_eq!(f32_literal(-f32::MAX).unwrap(), "-3.4028234663852886e38f");
        assert_eq!(f32_literal(3.4028233e38).unwrap(), "3.4028233e38f");
        for v in [f32::MAX, -f32::MAX, f32::MIN_POSITIVE, 1e-45, 3.4028233e38] {
            let text = f32_literal(v).unwrap();
            let digits = text.trim_end_matches('f');
            assert_eq!(
                digits.parse::<f32>().unwrap().to_bits(),
                v.to_bits(),
                "{text}"
            );
            assert!(
                digits.parse::<f64>().unwrap().abs() <= f64::from(f32::MAX),
                "{text}"
            );
        }
        assert_eq!(
            f32_literal(f32::INFINITY),
            Err(WgslError::NonFinite(f32::INFINITY))
        );
        assert_eq!(f32_expr(f32::INFINITY), "em_f32_bits(2139095040u)");
        assert_eq!(i32_literal(-1_073_741_824), "-1073741824i");
        assert_eq!(i32_literal(i32::MIN), "i32(-2147483648)");
        assert_eq!(u32_literal(0x8da6_b343), "0x8da6b343u");
    }

    #[test]
    fn identifiers_are_checked() {
        assert!(is_identifier("em_c12"));
        assert!(is_identifier("_x"));
        assert!(!is_identifier("_"));
        assert!(!is_identifier("__x"));
        assert!(!is_identifier("1x"));
        assert!(!is_identifier("a-b"));
        assert!(!is_identifier(""));
        assert_eq!(module_name("poly3_v").unwrap(), "em_poly3_v");
        assert!(matches!(
            module_name("a b"),
            Err(WgslError::BadIdentifier(_))
        ));
    }
}
