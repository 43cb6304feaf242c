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
    /// The field as a tape program, if it has one: a [`crate::field2d::Terrain`] over such
    /// a field evaluates it with the tape evaluators (region-specialized, SIMD batches)
    /// instead of calling [`Sdf::distance`] and [`Sdf::sample`] point by point. The
    /// program must compute exactly what those methods compute.
    fn program(&self) -> Option<std::sync::Arc<crate::field2d::tape::Program>> {
        None
    }
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
    fn program(&self) -> Option<std::sync::Arc<crate::field2d::tape::Program>> {
        (**self).program()
    }
}
