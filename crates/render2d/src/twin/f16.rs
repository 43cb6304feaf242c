//! IEEE-754 half precision (`f16`) conversions: the reduced-scale textures of the GPU
//! renderer are `Rgba16Float`, so the twin rounds every stored value the same way (round to
//! nearest, ties to even; overflow to infinity; subnormals kept).

/// Largest finite `f16` (`0x7BFF`).
pub const F16_MAX: f32 = 65504.0;

/// Smallest magnitude that rounds to infinity: halfway between [`F16_MAX`] and `2^16`.
const OVERFLOW: f32 = 65520.0;

/// Smallest normal `f16`, `2^-14`.
const MIN_NORMAL: f32 = 1.0 / 16384.0;

/// The `f16` bit pattern nearest to `x` (ties to even). NaN gives a quiet NaN.
pub fn f16_bits(x: f32) -> u16 {
    let bits = x.to_bits();
    let sign = ((bits >> 16) & 0x8000) as u16;
    let magnitude = x.abs();
    if magnitude.is_nan() {
        return sign | 0x7E00;
    }
    if magnitude >= OVERFLOW {
        return sign | 0x7C00;
    }
    if magnitude < MIN_NORMAL {
        // Subnormal: a multiple of 2^-24. Scaling by a power of two is exact, and rounding
        // to 1024 lands on the smallest normal's encoding (0x0400), which is correct.
        let quanta = (magnitude * 16_777_216.0).round_ties_even() as u16;
        return sign | quanta;
    }
    // Normal: drop the 13 low mantissa bits, ties to even; a carry moves into the exponent.
    let abs = bits & 0x7FFF_FFFF;
    let lsb = (abs >> 13) & 1;
    let rounded = (abs + 0x0FFF + lsb) & !0x1FFF;
    let exponent = (rounded >> 23) as i32 - 127 + 15;
    let mantissa = (rounded >> 13) & 0x3FF;
    sign | ((exponent as u16) << 10) | mantissa as u16
}

/// The value of the `f16` bit pattern `h` (exact: every `f16` is an `f32`).
pub fn f16_to_f32(h: u16) -> f32 {
    let sign = if h & 0x8000 != 0 { -1.0 } else { 1.0 };
    let exponent = u32::from((h >> 10) & 0x1F);
    let mantissa = u32::from(h & 0x3FF);
    match exponent {
        0 => sign * mantissa as f32 / 16_777_216.0,
        31 if mantissa == 0 => sign * f32::INFINITY,
        31 => f32::NAN,
        _ => {
            let bits = (u32::from(h & 0x8000) << 16) | ((exponent + 112) << 23) | (mantissa << 13);
            f32::from_bits(bits)
        }
    }
}

/// `x` rounded to the nearest `f16` and back, as a texture of that format stores it.
pub fn round_f16(x: f32) -> f32 {
    f16_to_f32(f16_bits(x))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn known_bit_patterns() {
        let cases: [(f32, u16); 16] = [
            (0.0, 0x0000),
            (-0.0, 0x8000),
            (1.0, 0x3C00),
            (-2.0, 0xC000),
            (0.1, 0x2E66),
            (1.0 / 3.0, 0x3555),
            (F16_MAX, 0x7BFF),
            (65519.0, 0x7BFF),
            (OVERFLOW, 0x7C00),
            (f32::INFINITY, 0x7C00),
            (f32::NEG_INFINITY, 0xFC00),
            (MIN_NORMAL, 0x0400),
            (1.0 / 16_777_216.0, 0x0001),
            // Half a quantum ties to even (zero); one and a half to two quanta.
            (0.5 / 16_777_216.0, 0x0000),
            (1.5 / 16_777_216.0, 0x0002),
            (-32.0, 0xD000),
        ];
        for (x, bits) in cases {
            assert_eq!(f16_bits(x), bits, "{x}");
        }
        assert!(f16_to_f32(f16_bits(f32::NAN)).is_nan());
    }

    #[test]
    fn ties_go_to_even_and_values_round_trip() {
        // 2049 lies halfway between 2048 and 2050 (spacing 2 above 2048).
        assert_eq!(round_f16(2049.0), 2048.0);
        assert_eq!(round_f16(2051.0), 2052.0);
        assert_eq!(round_f16(1.0 + 1.0 / 2048.0), 1.0);
        assert_eq!(round_f16(1.0 + 3.0 / 2048.0), 1.0 + 2.0 / 1024.0);
        assert_eq!(round_f16(0.1), 0.099_975_586);
        // A carry out of the mantissa moves into the exponent.
        assert_eq!(round_f16(2047.9), 2048.0);
        for h in (0u16..0x7C00).step_by(7).chain([0x7BFF, 0x03FF, 0x0400]) {
            let x = f16_to_f32(h);
            assert_eq!(f16_bits(x), h, "{h:#06x}");
            assert_eq!(f16_bits(-x), h | 0x8000, "-{h:#06x}");
        }
    }
}
