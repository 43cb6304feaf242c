//! Level files: a RON document holding the graph, world bounds, explosion-grid cell size,
//! material palette and spawn points, and their validation.
//!
//! ```
//! use craterfield_field::{Level, Sdf};
//! let level = Level::from_ron(r#"Level(
//!     name: "pond",
//!     bounds: (min: (0.0, 0.0), max: (512.0, 256.0)),
//!     materials: [(name: "soil", color: (120, 80, 50))],
//!     root: Subtract(
//!         base: HalfPlane(point: (0.0, 100.0), normal: (0.0, 1.0)),
//!         cut: Circle(center: (256.0, 100.0), radius: 40.0),
//!     ),
//! )"#).unwrap();
//! assert!(level.graph().distance(glam::Vec2::new(10.0, 50.0)) < 0.0);
//! ```

use std::collections::BTreeMap;
use std::path::Path;

use glam::Vec2;
use serde::{Deserialize, Serialize};

use super::aabb::Aabb;
use super::error::LevelError;
use super::graph::Graph;
use super::node::{Node, P2};
use super::terrain::{Terrain, TerrainError, TerrainOptions};

/// Largest accepted level file.
pub const MAX_LEVEL_BYTES: usize = 16 * 1024 * 1024;
/// Largest accepted world coordinate magnitude (keeps quantized event coordinates exact).
pub(crate) const MAX_WORLD_COORDINATE: f32 = 65_536.0;

/// The default level, compiled into the library. The crate holds the file, so it builds on
/// its own; the workspace's `levels/default.ron` is a link to it.
pub const DEFAULT_LEVEL_RON: &str =
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/levels/default.ron"));

/// World rectangle of a level.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WorldBounds {
    /// Lower-left corner.
    pub min: P2,
    /// Upper-right corner.
    pub max: P2,
}

/// A palette entry.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialDef {
    /// Display name.
    pub name: String,
    /// sRGB colour.
    pub color: [u8; 3],
}

fn default_cell_size() -> f32 {
    64.0
}

/// A level file as written (see `levels/*.ron`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
#[serde(rename = "Level")]
pub struct LevelFile {
    /// Display name.
    pub name: String,
    /// World rectangle: explosions must be centred inside it.
    pub bounds: WorldBounds,
    /// Explosion-grid cell size in world units.
    #[serde(default = "default_cell_size")]
    pub cell_size: f32,
    /// Material palette; `Material` nodes and fill events index it.
    pub materials: Vec<MaterialDef>,
    /// Spawn points.
    #[serde(default)]
    pub spawns: Vec<P2>,
    /// The terrain graph.
    pub root: Node,
    /// Named nodes that `Ref("name")` refers to. A name given twice is an error (a map
    /// would keep the last definition and silently drop the first).
    #[serde(default, deserialize_with = "unique_names")]
    pub nodes: BTreeMap<String, Node>,
}

/// Reads the `nodes` map, refusing a name defined twice (the parser's error then carries
/// the line and column).
fn unique_names<'de, D>(deserializer: D) -> Result<BTreeMap<String, Node>, D::Error>
where
    D: serde::Deserializer<'de>,
{
    struct Names;
    impl<'de> serde::de::Visitor<'de> for Names {
        type Value = BTreeMap<String, Node>;

        fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
            f.write_str("a map of node names to nodes")
        }

        fn visit_map<A: serde::de::MapAccess<'de>>(
            self,
            mut map: A,
        ) -> Result<Self::Value, A::Error> {
            let mut nodes = BTreeMap::new();
            while let Some((name, node)) = map.next_entry::<String, Node>()? {
                if nodes.contains_key(&name) {
                    return Err(serde::de::Error::custom(format!(
                        "node \"{name}\" is defined twice in `nodes`"
                    )));
                }
                nodes.insert(name, node);
            }
            Ok(nodes)
        }
    }
    deserializer.deserialize_map(Names)
}

/// A validated level with its compiled graph.
#[derive(Clone, Debug)]
pub struct Level {
    file: LevelFile,
    graph: Graph,
}

impl Level {
    /// Parse and validate a level from RON text.
    pub fn from_ron(text: &str) -> Result<Level, LevelError> {
        if text.len() > MAX_LEVEL_BYTES {
            return Err(LevelError::TooLarge {
                size: text.len(),
                limit: MAX_LEVEL_BYTES,
            });
        }
        let file: LevelFile = ron::Options::default()
            .from_str(text)
            .map_err(|e| LevelError::Parse(e.to_string()))?;
        Level::validate(file)
    }

    /// Read, parse and validate a level file.
    pub fn load(path: &Path) -> Result<Level, LevelError> {
        let text =
            craterfield_core::files::read_text(path, MAX_LEVEL_BYTES as u64).map_err(|e| {
                LevelError::Io {
                    path: path.display().to_string(),
                    message: e.to_string(),
                }
            })?;
        Level::from_ron(&text)
    }

    /// The embedded default level.
    pub fn default_level() -> Level {
        // The embedded file is checked by tests; failing here would be a build defect.
        Level::from_ron(DEFAULT_LEVEL_RON).expect("the embedded default level is valid")
    }

    /// Validate a parsed level file and compile its graph.
    pub fn validate(file: LevelFile) -> Result<Level, LevelError> {
        let invalid = |path: &str, reason: String| LevelError::Invalid {
            path: path.into(),
            reason,
        };
        if file.name.trim().is_empty() || file.name.len() > 256 {
            return Err(invalid(
                "name",
                format!("must be 1..=256 characters, got {}", file.name.len()),
            ));
        }
        let b = file.bounds;
        for (i, v) in [b.min[0], b.min[1], b.max[0], b.max[1]]
            .into_iter()
            .enumerate()
        {
            let field = [
                "bounds.min.x",
                "bounds.min.y",
                "bounds.max.x",
                "bounds.max.y",
            ][i];
            if !v.is_finite() || v.abs() > MAX_WORLD_COORDINATE {
                return Err(invalid(
                    field,
                    format!("must be a finite number within ±{MAX_WORLD_COORDINATE}, got {v}"),
                ));
            }
        }
        for (axis, lo, hi) in [("x", b.min[0], b.max[0]), ("y", b.min[1], b.max[1])] {
            if (hi - lo)
                .partial_cmp(&16.0)
                .is_none_or(|o| o == std::cmp::Ordering::Less)
            {
                return Err(invalid(
                    "bounds",
                    format!(
                        "the world must be at least 16 units wide on {axis}, got {lo} ..= {hi}"
                    ),
                ));
            }
        }
        let cs = file.cell_size;
        if !(4.0..=4096.0).contains(&cs) {
            return Err(invalid(
                "cell_size",
                format!("must be in 4 ..= 4096 world units, got {cs}"),
            ));
        }
        if file.materials.is_empty() || file.materials.len() > 256 {
            return Err(invalid(
                "materials",
                format!("needs 1 ..= 256 entries, got {}", file.materials.len()),
            ));
        }
        for (i, m) in file.materials.iter().enumerate() {
            if m.name.trim().is_empty() {
                return Err(invalid(
                    &format!("materials[{i}].name"),
                    "must not be empty".into(),
                ));
            }
        }
        if file.spawns.len() > 1024 {
            return Err(invalid(
                "spawns",
                format!(
                    "{} spawn points exceed the limit of 1024",
                    file.spawns.len()
                ),
            ));
        }
        let world = Aabb::new(Vec2::from(b.min), Vec2::from(b.max));
        for (i, s) in file.spawns.iter().enumerate() {
            if !world.contains(Vec2::from(*s)) {
                return Err(invalid(
                    &format!("spawns[{i}]"),
                    format!("({}, {}) lies outside the world bounds", s[0], s[1]),
                ));
            }
        }
        check_materials(&file.root, "root", file.materials.len())?;
        for (name, node) in &file.nodes {
            check_materials(node, &format!("nodes[\"{name}\"]"), file.materials.len())?;
        }
        let graph = Graph::compile(&file.root, &file.nodes)?;
        let level = Level { file, graph };
        // The explosion grid this level asks for must be buildable (cell count, memory).
        level
            .terrain()
            .map_err(|e| invalid("cell_size", e.to_string()))?;
        Ok(level)
    }

    /// The level as written.
    pub fn file(&self) -> &LevelFile {
        &self.file
    }

    /// The compiled terrain graph.
    pub fn graph(&self) -> &Graph {
        &self.graph
    }

    /// Display name.
    pub fn name(&self) -> &str {
        &self.file.name
    }

    /// World rectangle.
    pub fn bounds(&self) -> Aabb {
        Aabb::new(
            Vec2::from(self.file.bounds.min),
            Vec2::from(self.file.bounds.max),
        )
    }

    /// Material palette.
    pub fn materials(&self) -> &[MaterialDef] {
        &self.file.materials
    }

    /// Terrain options for this level: its grid cell size and palette size, defaults
    /// otherwise.
    pub fn terrain_options(&self) -> TerrainOptions {
        TerrainOptions {
            cell_size: self.file.cell_size,
            material_count: self.file.materials.len() as u16,
            ..TerrainOptions::default()
        }
    }

    /// A terrain over this level's graph and bounds, with [`Level::terrain_options`].
    pub fn terrain(&self) -> Result<Terrain<Graph>, TerrainError> {
        let b = self.bounds();
        Terrain::new(self.graph.clone(), b.min, b.max, self.terrain_options())
    }

    /// Spawn points.
    pub fn spawns(&self) -> impl Iterator<Item = Vec2> + '_ {
        self.file.spawns.iter().map(|s| Vec2::from(*s))
    }
}

/// Every `Material` id must index the palette.
fn check_materials(node: &Node, path: &str, count: usize) -> Result<(), LevelError> {
    let here = format!("{path}.{}", node.kind());
    match node {
        Node::Material { id, .. } if *id as usize >= count => {
            return Err(LevelError::Invalid {
                path: format!("{here}.id"),
                reason: format!("material {id} is not in the palette of {count} materials"),
            });
        }
        _ => {}
    }
    for (label, child) in node.children() {
        check_materials(child, &format!("{here}{label}"), count)?;
    }
    Ok(())
}
