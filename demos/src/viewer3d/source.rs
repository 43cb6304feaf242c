//! [`SceneSource`]: where the viewer's scene comes from (a builtin scene or a RON file),
//! and loading it into a validated scene or a message the panel shows.

use std::path::PathBuf;

use craterfield::march3d::scene::{BUILTIN, Scene};

use crate::common::RunArgs;

/// The scene the viewer shows.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum SceneSource {
    /// A builtin scene by name (one of the library's `scene::BUILTIN`, as the CLI offers).
    Builtin(String),
    /// A RON scene file.
    File(PathBuf),
}

impl SceneSource {
    /// The builtin scene opened when the command line names no file: the world whose
    /// culling, LOD and step tiers the panel's statistics are about.
    pub const DEFAULT_BUILTIN: &'static str = "forest";

    /// The command line's file, or the default builtin. Like the CLI, a builtin's name
    /// that is not an existing file opens the builtin.
    pub fn from_args(args: &RunArgs) -> SceneSource {
        match &args.file {
            Some(path) if !path.exists() && is_builtin(&path.to_string_lossy()) => {
                SceneSource::Builtin(path.to_string_lossy().into_owned())
            }
            Some(path) => SceneSource::File(path.clone()),
            None => SceneSource::Builtin(SceneSource::DEFAULT_BUILTIN.to_string()),
        }
    }

    /// Every builtin scene, in the CLI's order.
    pub fn builtins() -> impl Iterator<Item = SceneSource> {
        BUILTIN
            .iter()
            .map(|name| SceneSource::Builtin((*name).to_string()))
    }

    /// The name the scene picker shows.
    pub fn label(&self) -> String {
        match self {
            SceneSource::Builtin(name) => name.clone(),
            SceneSource::File(path) => path.display().to_string(),
        }
    }

    /// Reads and validates the scene; the error says which source failed and why.
    pub fn load(&self) -> Result<Scene, String> {
        match self {
            SceneSource::Builtin(name) => {
                Scene::builtin(name).map_err(|e| format!("builtin scene {name}: {e}"))
            }
            SceneSource::File(path) => {
                Scene::load(path).map_err(|e| format!("scene file {}: {e}", path.display()))
            }
        }
    }
}

fn is_builtin(name: &str) -> bool {
    BUILTIN.contains(&name)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_command_line_picks_the_source() {
        let mut args = RunArgs::default();
        assert_eq!(
            SceneSource::from_args(&args),
            SceneSource::Builtin("forest".into())
        );
        args.file = Some(PathBuf::from("mandelbulb"));
        assert_eq!(
            SceneSource::from_args(&args),
            SceneSource::Builtin("mandelbulb".into())
        );
        args.file = Some(PathBuf::from("no/such/scene.ron"));
        assert!(matches!(
            SceneSource::from_args(&args),
            SceneSource::File(_)
        ));
    }

    #[test]
    fn every_builtin_loads_and_a_missing_file_says_so() {
        for source in SceneSource::builtins() {
            assert!(source.load().is_ok(), "{}", source.label());
        }
        let missing = SceneSource::File(PathBuf::from("no/such/scene.ron"));
        let message = missing.load().unwrap_err();
        assert!(message.contains("no/such/scene.ron"), "{message}");
    }
}
