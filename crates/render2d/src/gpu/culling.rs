//! [`Culling`]: which part of the level the field pipeline is compiled for.

use craterfield_field::Aabb;

/// Which part of the level the renderer's field pipeline covers. Each distinct part is its
/// own pipeline, compiled on its first frame (kept in an LRU of 16): a view that moves
/// changes the part, and the frame that meets a new one pays a pipeline compile.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[non_exhaustive]
pub enum Culling {
    /// Only what can reach the view: the cheapest shader per frame; a moving view compiles
    /// a pipeline whenever the set of nodes near it changes.
    #[default]
    View,
    /// The whole level, one pipeline: no compile after the first frame, wherever the view
    /// goes, for a shader that evaluates every node. A level past the shader budget cannot
    /// be drawn this way (`prepare` says so). For a scrolling game view this is what keeps
    /// the worst frame short: on lavapipe, the artillery example's p99 frame went from
    /// 779 ms (a compile whenever the view's set of nodes changed) to 103 ms.
    Off,
}

impl Culling {
    /// The rectangle the pipeline is compiled for, given the view's (`None`: the whole level).
    pub(crate) fn rect(self, view: Aabb) -> Option<Aabb> {
        match self {
            Culling::View => Some(view),
            Culling::Off => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec2;

    #[test]
    fn off_covers_the_whole_level() {
        let view = Aabb::new(Vec2::new(100.0, -50.0), Vec2::new(1300.0, 700.0));
        assert_eq!(Culling::View.rect(view), Some(view));
        assert_eq!(Culling::Off.rect(view), None);
    }
}
