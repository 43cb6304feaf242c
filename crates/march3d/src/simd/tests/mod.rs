//! One conformance suite for every lane backend this machine has: each operation applied
//! lane by lane to awkward inputs and compared with plain `f32` arithmetic, the polynomial
//! math compared with double precision over dense ranges, and the counting backend's
//! tallies.

//!
//! The inputs and the runner every part shares are here; the operation suite is in `lanes`,
//! the math in `math`, the counting backend's tallies in `counting`.

mod counting;
mod lanes;
mod math;

use super::count::Counting;
use super::{Pack, PackKernel, Pair};
#[cfg(all(target_arch = "aarch64", not(feature = "force-scalar")))]
use craterfield_core::simd::Neon;
#[cfg(all(target_arch = "x86_64", not(feature = "force-scalar")))]
use craterfield_core::simd::{Avx2, Avx512};
use craterfield_core::simd::{Lanes, Scalar};

/// Floats that break careless lane code: signed zeros, infinities, NaN, subnormals, the
/// extremes, halfway cases for rounding, and ordinary values.
fn float_inputs() -> Vec<f32> {
    let mut v = vec![
        0.0,
        -0.0,
        1.0,
        -1.0,
        0.5,
        -0.5,
        1.5,
        2.5,
        -2.5,
        0.3,
        -0.3,
        3.75,
        -7.25,
        1e-3,
        123.456,
        -98765.43,
        1e20,
        -3e30,
        f32::MAX,
        f32::MIN,
        f32::MIN_POSITIVE,
        -f32::MIN_POSITIVE,
        1e-40,
        -1e-42,
        f32::from_bits(1),
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::NAN,
        8_388_607.5,
        16_777_217.0,
        2_147_483_520.0,
        -2_147_483_648.0,
        std::f32::consts::PI,
        -std::f32::consts::E,
    ];
    v.push(f32::from_bits(0x7fc0_1234));
    v
}

/// 32-bit integers for the integer lanes.
fn int_inputs() -> Vec<i32> {
    vec![
        0,
        1,
        -1,
        2,
        7,
        -8,
        255,
        0x3f80_0000,
        0x7f80_0000,
        0x007f_ffff,
        i32::MAX,
        i32::MIN,
        i32::MIN + 1,
        123_456_789,
        -987_654_321,
        0x5555_5555,
    ]
}

/// Lanes of the widest pack, a [`Pair`] of AVX-512 registers: every column is padded to
/// a multiple of it.
pub(super) const WIDEST: usize = 32;

/// `v` padded with zeros to a multiple of every backend's width.
fn pad<T: Copy + Default>(mut v: Vec<T>) -> Vec<T> {
    while !v.len().is_multiple_of(WIDEST) {
        v.push(T::default());
    }
    v
}

/// Every pair `(a, b)` of `xs`, as two padded columns.
fn pairs<T: Copy + Default>(xs: &[T]) -> (Vec<T>, Vec<T>) {
    let (a, b) = xs
        .iter()
        .flat_map(|&a| xs.iter().map(move |&b| (a, b)))
        .unzip();
    (pad(a), pad(b))
}

/// Every triple of `xs`, as three padded columns.
fn triples(xs: &[f32]) -> (Vec<f32>, Vec<f32>, Vec<f32>) {
    let mut cols = (Vec::new(), Vec::new(), Vec::new());
    for &a in xs {
        for &b in xs {
            for &c in xs {
                cols.0.push(a);
                cols.1.push(b);
                cols.2.push(c);
            }
        }
    }
    (pad(cols.0), pad(cols.1), pad(cols.2))
}

/// Runs `k` on every backend this machine has, and on a [`Pair`] of each but the counting
/// one: (name, width, output).
fn on_every_backend<K: PackKernel + Clone>(k: K) -> Vec<(&'static str, usize, K::Output)> {
    // Without a vector backend compiled in (feature `force-scalar`) nothing is pushed.
    #[allow(unused_mut)]
    let mut out = vec![
        ("scalar", Scalar::WIDTH, Pack::call(Scalar, k.clone())),
        ("scalar pair", 2, Pack::call(Pair(Scalar), k.clone())),
        ("counting", Counting::WIDTH, Counting.call(k.clone())),
    ];
    #[cfg(all(target_arch = "x86_64", not(feature = "force-scalar")))]
    if let Some(p) = craterfield_core::simd::Avx2::new() {
        out.push(("avx2", Avx2::WIDTH, Pack::call(p, k.clone())));
        out.push(("avx2 pair", 2 * Avx2::WIDTH, Pack::call(Pair(p), k.clone())));
    }
    #[cfg(all(target_arch = "x86_64", not(feature = "force-scalar")))]
    if let Some(p) = craterfield_core::simd::Avx512::new() {
        out.push(("avx512", Avx512::WIDTH, Pack::call(p, k.clone())));
        out.push(("avx512 pair", WIDEST, Pack::call(Pair(p), k.clone())));
    }
    #[cfg(all(target_arch = "aarch64", not(feature = "force-scalar")))]
    if let Some(p) = craterfield_core::simd::Neon::new() {
        out.push(("neon", Neon::WIDTH, Pack::call(p, k.clone())));
        out.push(("neon pair", 2 * Neon::WIDTH, Pack::call(Pair(p), k.clone())));
    }
    out
}
