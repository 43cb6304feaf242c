//! The interface every 2D field exposes to queries, physics and renderers.

use glam::Vec2;

use super::sample::{MaterialId, Sample};

/// A 2D signed distance field.
///
/// Implementations are deterministic: the same point gives the same bits on every platform,
/// and `sample(p).distance` is bit-identical to `distance(p)`.
pub trait Sdf {
    /// Signed distance at `p` (negative inside).
    fn distance(&self, p: Vec2) -> f32;
    /// Distance, gradient and material at `p`, in one pass.
    fn sample(&self, p: Vec2) -> Sample;
    /// Distance and material without the gradient (cheaper where only colour is needed).
    fn distance_material(&self, p: Vec2) -> (f32, MaterialId) {
        let s = self.sample(p);
        (s.distance, s.material)
    }
    /// An upper bound on `|distance(a) - distance(b)| / |a - b|` (1 for exact fields).
    fn lipschitz(&self) -> f32;
    /// The field as a tape program, if it has one: a [`crate::Terrain`] over such
    /// a field evaluates it with the tape evaluators (region-specialized, SIMD batches)
    /// instead of calling [`Sdf::distance`] and [`Sdf::sample`] point by point. The
    /// program must compute exactly what those methods compute.
    fn program(&self) -> Option<std::sync::Arc<crate::tape::Program>> {
        None
    }
    /// How far the ray from `p` along the unit `dir` is proven to keep the field at or
    /// above `above` (`> 0`), without evaluating it point by point: ray casts and sweeps
    /// skip such stretches. The default proves nothing and is never asked again.
    fn clear_run(&self, p: Vec2, dir: Vec2, above: f32) -> ClearRun {
        let _ = (p, dir, above);
        ClearRun::NOTHING
    }
}

/// A stretch of a ray that a field proves clear ([`Sdf::clear_run`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClearRun {
    /// The field is at least the threshold at every point `p + dir * s`, `0 <= s <= clear`.
    pub clear: f32,
    /// How much farther, past `clear`, asking again proves nothing new: the caller steps
    /// on by other means until then (`0`: ask at the next point; infinite: never again).
    pub retry_after: f32,
}

impl ClearRun {
    /// Nothing proven, and nothing to gain by asking again.
    pub const NOTHING: ClearRun = ClearRun {
        clear: 0.0,
        retry_after: f32::INFINITY,
    };
}

impl<T: Sdf + ?Sized> Sdf for &T {
    fn distance(&self, p: Vec2) -> f32 {
        (**self).distance(p)
    }
    fn sample(&self, p: Vec2) -> Sample {
        (**self).sample(p)
    }
    fn distance_material(&self, p: Vec2) -> (f32, MaterialId) {
        (**self).distance_material(p)
    }
    fn lipschitz(&self) -> f32 {
        (**self).lipschitz()
    }
    fn program(&self) -> Option<std::sync::Arc<crate::tape::Program>> {
        (**self).program()
    }
    fn clear_run(&self, p: Vec2, dir: Vec2, above: f32) -> ClearRun {
        (**self).clear_run(p, dir, above)
    }
}
