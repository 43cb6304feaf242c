//! The foundation of craterfield's crates: what the deterministic field and the 3D tracer
//! share, and the only place of the field's stack where `unsafe` code lives.
//!
//! * [`det`]: float math whose every operation is exactly rounded, and fixed point.
//! * [`backend`]: the CPU instruction sets, their detection at run time, the environment
//!   variable that caps the choice.
//! * [`simd`]: a token type per instruction set, which exists only once the CPU is known to
//!   have it, and the exact lane operations ([`simd::Lanes`]) on it, one file per
//!   architecture. The 3D tracer's fused multiply-add lanes extend these tokens in
//!   `craterfield-march3d`; nothing here fuses, so the field cannot reach an FMA.
//! * [`files`]: bounded reads of files a user or a peer hands over.
//! * [`threads`]: thread counts resolved to what the target can run (one on WebAssembly).

pub mod backend;
pub mod det;
pub mod files;
pub mod simd;
pub mod threads;
