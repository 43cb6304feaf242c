//! Helpers shared by the integration tests: the one deterministic pseudo-random generator
//! (SplitMix64, no dependency), scripted inputs, the one GPU test harness (`gpu`), cratered terrains for the renderer tests (`craters`), and the
//! measure of block steps in a rendered shade (`shade_steps`). Each test binary uses part of
//! it.
#![allow(dead_code)]

#[cfg(feature = "gpu")]
pub(crate) mod craters;
#[cfg(feature = "gpu")]
#[cfg(not(target_family = "wasm"))]
pub(crate) mod gpu;
#[cfg(feature = "raster")]
pub(crate) mod shade_steps;

/// `eprintln!` that a browser test shows too: in WebAssembly it writes to the page's console,
/// which wasm-bindgen-test prints (std's output goes nowhere there).
#[macro_export]
macro_rules! say {
    ($($arg:tt)*) => {{
        #[cfg(target_family = "wasm")]
        wasm_bindgen_test::console_log!($($arg)*);
        #[cfg(not(target_family = "wasm"))]
        eprintln!($($arg)*);
    }};
}

use craterfield::field2d::Aabb;
use craterfield::sim::Input;
use craterfield::sim::buttons::{FIRE, JUMP, STICK};

/// One SplitMix64 step: a well-mixed function of `x`.
pub(crate) fn splitmix64(mut x: u64) -> u64 {
    x = x.wrapping_add(0x9e37_79b9_7f4a_7c15);
    x = (x ^ (x >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    x = (x ^ (x >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    x ^ (x >> 31)
}

/// A SplitMix64 stream.
pub(crate) struct Rng(pub u64);

impl Rng {
    /// The next 64 bits.
    pub(crate) fn next(&mut self) -> u64 {
        let z = splitmix64(self.0);
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        z
    }

    /// Uniform-ish in `0..n` (`n > 0`).
    pub(crate) fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }

    /// Uniform in `[0, 1)`, 24 bits.
    pub(crate) fn unit(&mut self) -> f32 {
        (self.next() >> 40) as f32 / (1u64 << 24) as f32
    }

    /// Uniform in `[lo, hi)`.
    pub(crate) fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.unit()
    }

    /// Uniform in `[0, 1)`, 53 bits.
    pub(crate) fn unit_f64(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in `[lo, hi)`, in `f64`.
    pub(crate) fn range_f64(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit_f64()
    }

    /// Uniform in `[-r, r)^2`.
    pub(crate) fn square_point(&mut self, r: f32) -> [f32; 2] {
        [self.range(-r, r), self.range(-r, r)]
    }

    /// Uniform in the box.
    pub(crate) fn point_in(&mut self, b: &Aabb) -> glam::Vec2 {
        glam::Vec2::new(
            b.min.x + (b.max.x - b.min.x) * self.unit(),
            b.min.y + (b.max.y - b.min.y) * self.unit(),
        )
    }
}

/// Player `player`'s input on `frame`: a pure function of its arguments. Aim, throttle,
/// weapon and power hold for segments of 24 frames; fire is pressed on about a quarter of
/// the frames (a new shot every few ticks with the lowered cooldowns), jumps and stick
/// toggles now and then.
pub(crate) fn scripted_input(seed: u64, player: usize, frame: u32) -> Input {
    let segment = splitmix64(seed ^ ((player as u64) << 40) ^ u64::from(frame / 24));
    let tick = splitmix64(segment ^ (u64::from(frame) << 20) ^ 0x5eed);
    // Mostly down and sideways (craters in the ground nearby), sometimes anywhere.
    let base = if segment & 3 == 0 {
        (segment >> 8) as u16
    } else {
        32768u16.wrapping_add((segment >> 8) as u16 / 2)
    };
    let aim = base.wrapping_add((frame % 24) as u16 * 300);
    let throttle: i16 = if (segment >> 24) & 3 == 0 {
        0
    } else {
        ((segment >> 28) % 255) as i16 - 127
    };
    let mut buttons = 0;
    if tick & 3 == 0 {
        buttons |= FIRE;
    }
    if (tick >> 8) & 15 == 0 {
        buttons |= JUMP;
    }
    if (segment >> 36) & 7 == 0 && frame % 24 < 3 {
        buttons |= STICK;
    }
    Input {
        aim,
        buttons,
        drive: throttle as i8,
        power: 96 + ((segment >> 44) % 160) as u8,
        weapon: ((tick >> 16) & 1) as u8,
    }
}
