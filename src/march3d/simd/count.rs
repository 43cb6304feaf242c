//! The counting backend: the scalar lane that also counts floating-point operations
//! (filled in with the per-architecture backends).
