//! Polynomial `exp`, `log`, `sin`, `cos` over any [`Pack`](super::simd::Pack).
