//! The scalar backend: one lane of plain Rust, on every platform. It is also what the
//! `force-scalar` feature leaves.

use super::Lanes;

/// The scalar backend's token.
#[derive(Clone, Copy, Debug, Default)]
pub struct Scalar;

impl Lanes for Scalar {
    const WIDTH: usize = 1;
    type F = f32;
    type M = bool;
    type I = i32;

    #[inline(always)]
    fn splat(self, v: f32) -> f32 {
        v
    }
    #[inline(always)]
    fn load(self, s: &[f32]) -> f32 {
        s[0]
    }
    #[inline(always)]
    fn store(self, v: f32, out: &mut [f32]) {
        out[0] = v;
    }
    #[inline(always)]
    fn add(self, a: f32, b: f32) -> f32 {
        a + b
    }
    #[inline(always)]
    fn sub(self, a: f32, b: f32) -> f32 {
        a - b
    }
    #[inline(always)]
    fn mul(self, a: f32, b: f32) -> f32 {
        a * b
    }
    #[inline(always)]
    fn div(self, a: f32, b: f32) -> f32 {
        a / b
    }
    #[inline(always)]
    fn sqrt(self, a: f32) -> f32 {
        a.sqrt()
    }
    #[inline(always)]
    fn neg(self, a: f32) -> f32 {
        -a
    }
    #[inline(always)]
    fn abs(self, a: f32) -> f32 {
        a.abs()
    }
    #[inline(always)]
    fn floor(self, a: f32) -> f32 {
        a.floor()
    }
    #[inline(always)]
    fn min(self, a: f32, b: f32) -> f32 {
        if a < b { a } else { b }
    }
    #[inline(always)]
    fn max(self, a: f32, b: f32) -> f32 {
        if a > b { a } else { b }
    }
    #[inline(always)]
    fn lt(self, a: f32, b: f32) -> bool {
        a < b
    }
    #[inline(always)]
    fn gt(self, a: f32, b: f32) -> bool {
        a > b
    }
    #[inline(always)]
    fn le(self, a: f32, b: f32) -> bool {
        a <= b
    }
    #[inline(always)]
    fn ge(self, a: f32, b: f32) -> bool {
        a >= b
    }
    #[inline(always)]
    #[allow(clippy::eq_op)]
    fn not_nan(self, a: f32) -> bool {
        a == a
    }
    #[inline(always)]
    fn select(self, m: bool, a: f32, b: f32) -> f32 {
        if m { a } else { b }
    }
    #[inline(always)]
    fn select_i(self, m: bool, a: i32, b: i32) -> i32 {
        if m { a } else { b }
    }
    #[inline(always)]
    fn and(self, a: bool, b: bool) -> bool {
        a & b
    }
    #[inline(always)]
    fn or(self, a: bool, b: bool) -> bool {
        a | b
    }
    #[inline(always)]
    fn xor(self, a: bool, b: bool) -> bool {
        a ^ b
    }
    #[inline(always)]
    fn not(self, a: bool) -> bool {
        !a
    }
    #[inline(always)]
    fn any(self, m: bool) -> bool {
        m
    }
    #[inline(always)]
    fn splat_i(self, v: i32) -> i32 {
        v
    }
    #[inline(always)]
    fn load_i(self, s: &[i32]) -> i32 {
        s[0]
    }
    #[inline(always)]
    fn store_i(self, v: i32, out: &mut [i32]) {
        out[0] = v;
    }
    #[inline(always)]
    fn to_i32(self, v: f32) -> i32 {
        v as i32
    }
    #[inline(always)]
    fn to_f32(self, v: i32) -> f32 {
        v as f32
    }
    #[inline(always)]
    fn add_i(self, a: i32, b: i32) -> i32 {
        a.wrapping_add(b)
    }
    #[inline(always)]
    fn mul_i(self, a: i32, b: i32) -> i32 {
        a.wrapping_mul(b)
    }
    #[inline(always)]
    fn xor_i(self, a: i32, b: i32) -> i32 {
        a ^ b
    }
    #[inline(always)]
    fn shr_i(self, a: i32, n: u32) -> i32 {
        ((a as u32) >> n) as i32
    }
    #[inline(always)]
    fn lt_i(self, a: i32, b: i32) -> bool {
        a < b
    }
    #[inline(always)]
    fn gt_i(self, a: i32, b: i32) -> bool {
        a > b
    }
    #[inline(always)]
    fn mask_bits(self, m: bool) -> f32 {
        f32::from_bits(if m { u32::MAX } else { 0 })
    }
    #[inline(always)]
    fn bits_mask(self, f: f32) -> bool {
        f.to_bits() != 0
    }
    #[inline(always)]
    fn int_bits(self, i: i32) -> f32 {
        f32::from_bits(i as u32)
    }
    #[inline(always)]
    fn bits_int(self, f: f32) -> i32 {
        f.to_bits() as i32
    }
}
