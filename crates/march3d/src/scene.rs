//! 3D scene files: a RON document holding the camera, the lighting model, the march
//! settings, an optional FBM heightfield terrain, the materials and the objects; their
//! validation; and the builtin scenes (`scenes/*.ron`).
//!
//! A scene is what a user writes. The emitter (`march3d::compile`) turns it, for one camera,
//! into a [`Plan`](crate::plan3d::Plan), the form both renderers execute.
//!
//! ```
//! use craterfield_march3d::scene::Scene;
//! let scene = Scene::from_ron(r#"Scene(
//!     name: "ball",
//!     camera: (position: (0.0, 0.0, 0.0), look_at: (0.0, 0.0, 1.0), fov: 30.0),
//!     lighting: Paper((lights: [(position: (0.0, 100.0, 0.0), emission: 200.0)])),
//!     materials: [(name: "red", colour: (0.3, 0.0, 0.0))],
//!     objects: [Shape(shape: Sphere(r: 3.0), at: (0.0, 0.0, 20.0), material: "red")],
//! )"#).unwrap();
//! assert_eq!(scene.objects.len(), 1);
//! ```

use std::path::Path;

use glam::{Mat3, Vec3};
use serde::{Deserialize, Serialize};
use thiserror::Error;

use crate::plan3d::{Camera3d, Fbm, PointLight, PrimKind};

/// Largest accepted scene file.
pub const MAX_SCENE_BYTES: usize = 4 * 1024 * 1024;
/// Most objects a scene may hold.
pub const MAX_OBJECTS: usize = 4096;
/// Largest accepted coordinate magnitude.
pub const MAX_COORDINATE: f32 = 1.0e5;
/// The names of the builtin scenes.
pub const BUILTIN: [&str; 4] = ["scene0", "mandelbulb", "sparse", "forest"];

/// A scene file or value that cannot be used, with where and why.
#[derive(Clone, Debug, PartialEq, Error)]
#[non_exhaustive]
pub enum SceneError {
    /// The file could not be read.
    #[error("cannot read scene {path}: {message}")]
    Io {
        /// The path.
        path: String,
        /// The operating system's message.
        message: String,
    },
    /// The file is larger than [`MAX_SCENE_BYTES`].
    #[error("scene file is {bytes} bytes; at most {MAX_SCENE_BYTES} are accepted")]
    TooLarge {
        /// Its size.
        bytes: usize,
    },
    /// The text is not a scene in RON.
    #[error("scene syntax: {0}")]
    Syntax(String),
    /// A value is out of range.
    #[error("{path}: {message}")]
    Invalid {
        /// Where, e.g. `objects[3].Tree.height`.
        path: String,
        /// What is wrong.
        message: String,
    },
    /// No builtin scene has this name.
    #[error("no builtin scene `{0}` (builtins: scene0, mandelbulb, sparse, forest)")]
    UnknownBuiltin(String),
}

/// A scene as written in its file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// Display name.
    pub name: String,
    /// The default camera.
    pub camera: CameraSpec,
    /// Default image size.
    #[serde(default = "default_size")]
    pub size: (u32, u32),
    /// How hits are lit.
    pub lighting: Lighting,
    /// March settings (each field defaults per lighting model; see [`MarchSpec`]).
    #[serde(default)]
    pub march: MarchSpec,
    /// The heightfield, if any.
    #[serde(default)]
    pub terrain: Option<TerrainSpec>,
    /// Materials, referred to by name.
    pub materials: Vec<MaterialSpec>,
    /// The objects.
    pub objects: Vec<Object>,
}

fn default_size() -> (u32, u32) {
    (1280, 720)
}

/// Where the camera is and what it looks at.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraSpec {
    /// Eye position.
    pub position: Vec3,
    /// A point on the view axis.
    pub look_at: Vec3,
    /// Roughly up.
    #[serde(default = "default_up")]
    pub up: Vec3,
    /// Vertical field of view, degrees.
    pub fov: f32,
}

fn default_up() -> Vec3 {
    Vec3::Y
}

impl CameraSpec {
    /// The camera, or an error naming the degenerate part.
    pub fn camera(&self) -> Result<Camera3d, SceneError> {
        Camera3d::looking(
            self.position,
            self.look_at - self.position,
            self.up,
            self.fov,
        )
        .ok_or_else(|| invalid(
            "camera",
            "needs a finite position, look_at != position, an up not parallel to the view, and 0 < fov < 180",
        ))
    }
}

/// The lighting model.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Lighting {
    /// The reference paper's point lights, Phong, reflections and soft shadows.
    Paper(PaperLighting),
    /// Sun, sky, ambient occlusion and shadows for outdoor worlds.
    World(WorldLighting),
}

/// Parameters of [`Lighting::Paper`]; the defaults are the reference implementation's.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PaperLighting {
    /// Point lights.
    pub lights: Vec<PointLight>,
    /// Phong exponent.
    #[serde(default = "d_shininess")]
    pub shininess: f32,
    /// Specular weight.
    #[serde(default = "d_specular")]
    pub specular: f32,
    /// Ambient term.
    #[serde(default = "d_ambient")]
    pub ambient: f32,
    /// Reflection bounces.
    #[serde(default = "d_bounces")]
    pub bounces: u32,
    /// Multiplier of reflected colour (times the material's reflectivity).
    #[serde(default = "d_reflection_scale")]
    pub reflection_scale: f32,
    /// Soft shadow sharpness; shadows apply only when the scene has more than one object.
    #[serde(default = "d_shadow_k")]
    pub shadow_k: f32,
    /// Fog coefficient of `exp(-fog * t^3)`.
    #[serde(default = "d_paper_fog")]
    pub fog: f32,
    /// Output exponent.
    #[serde(default = "d_gamma")]
    pub gamma: f32,
}

fn d_shininess() -> f32 {
    15.0
}
fn d_specular() -> f32 {
    0.2
}
fn d_ambient() -> f32 {
    0.01
}
fn d_bounces() -> u32 {
    3
}
fn d_reflection_scale() -> f32 {
    0.1
}
fn d_shadow_k() -> f32 {
    3.0
}
fn d_paper_fog() -> f32 {
    7.0e-6
}
fn d_gamma() -> f32 {
    0.4545
}

/// Parameters of [`Lighting::World`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WorldLighting {
    /// Direction towards the sun (any length).
    pub sun: Vec3,
    /// Sun colour.
    #[serde(default = "d_sun_colour")]
    pub sun_colour: Vec3,
    /// Sky colour at the horizon and at the zenith.
    #[serde(default = "d_sky")]
    pub sky: [Vec3; 2],
    /// Fog density.
    #[serde(default = "d_world_fog")]
    pub fog: f32,
    /// Output exponent.
    #[serde(default = "d_gamma")]
    pub gamma: f32,
}

fn d_sun_colour() -> Vec3 {
    Vec3::new(1.3, 1.2, 1.0)
}
fn d_sky() -> [Vec3; 2] {
    [Vec3::new(0.75, 0.82, 0.9), Vec3::new(0.3, 0.5, 0.85)]
}
fn d_world_fog() -> f32 {
    0.006
}

/// March settings; a field left out takes the lighting model's default
/// ([`MarchSpec::resolve`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MarchSpec {
    /// Step budget (the base of the step tiers in worlds).
    pub max_steps: Option<u32>,
    /// Absolute hit threshold.
    pub hit: Option<f32>,
    /// Hit threshold growth per unit distance.
    pub hit_per_t: Option<f32>,
    /// A ray escapes beyond this distance from the origin.
    pub escape: Option<f32>,
    /// A ray escapes beyond this distance along itself.
    pub far: Option<f32>,
    /// Offset of secondary rays from the surface.
    pub ray_offset: Option<f32>,
    /// Step of finite-difference normals.
    pub normal_eps: Option<f32>,
    /// Over-relaxation factor (1 = plain sphere tracing).
    pub relax: Option<f32>,
}

/// March settings with every default filled in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MarchSettings {
    /// See [`MarchSpec::max_steps`].
    pub max_steps: u32,
    /// See [`MarchSpec::hit`].
    pub hit: f32,
    /// See [`MarchSpec::hit_per_t`].
    pub hit_per_t: f32,
    /// See [`MarchSpec::escape`].
    pub escape: f32,
    /// See [`MarchSpec::far`].
    pub far: f32,
    /// See [`MarchSpec::ray_offset`].
    pub ray_offset: f32,
    /// See [`MarchSpec::normal_eps`].
    pub normal_eps: f32,
    /// See [`MarchSpec::relax`].
    pub relax: f32,
}

impl MarchSettings {
    /// The reference implementation's settings: up to 3000 steps, hit at 5e-6, escape
    /// beyond |p| = 100, secondary rays offset 1e-3, normals with eps 1e-4.
    pub const PAPER: MarchSettings = MarchSettings {
        max_steps: 3000,
        hit: 5.0e-6,
        hit_per_t: 0.0,
        escape: 100.0,
        far: f32::INFINITY,
        ray_offset: 1.0e-3,
        normal_eps: 1.0e-4,
        relax: 1.0,
    };
    /// Outdoor worlds: a base budget of 96 steps and a hit threshold that grows with
    /// distance (a pixel's footprint).
    pub const WORLD: MarchSettings = MarchSettings {
        max_steps: 96,
        hit: 1.0e-3,
        hit_per_t: 1.5e-3,
        escape: 1.0e4,
        far: 160.0,
        ray_offset: 2.0e-2,
        normal_eps: 2.0e-3,
        relax: 1.0,
    };
}

impl MarchSpec {
    /// Fills in the defaults of the lighting model.
    pub fn resolve(&self, lighting: &Lighting) -> MarchSettings {
        let d = match lighting {
            Lighting::Paper(_) => MarchSettings::PAPER,
            Lighting::World(_) => MarchSettings::WORLD,
        };
        MarchSettings {
            max_steps: self.max_steps.unwrap_or(d.max_steps),
            hit: self.hit.unwrap_or(d.hit),
            hit_per_t: self.hit_per_t.unwrap_or(d.hit_per_t),
            escape: self.escape.unwrap_or(d.escape),
            far: self.far.unwrap_or(d.far),
            ray_offset: self.ray_offset.unwrap_or(d.ray_offset),
            normal_eps: self.normal_eps.unwrap_or(d.normal_eps),
            relax: self.relax.unwrap_or(d.relax),
        }
    }
}

/// The heightfield terrain.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TerrainSpec {
    /// The height function.
    pub fbm: Fbm,
    /// Its material's name.
    pub material: String,
}

/// A named material.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialSpec {
    /// The name objects refer to.
    pub name: String,
    /// Linear RGB albedo.
    pub colour: Vec3,
    /// Mirror reflectivity.
    #[serde(default)]
    pub reflectivity: f32,
}

/// An object of the scene. Objects placed by `(x, z)` stand on the terrain (or on y = 0
/// without one).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Object {
    /// One primitive.
    Shape {
        /// The primitive.
        shape: PrimKind,
        /// Its centre; with `on_ground`, `at.y` is the height above the terrain.
        at: Vec3,
        /// Rotation in degrees about x, then y, then z.
        #[serde(default)]
        rotate: Vec3,
        /// Material name.
        material: String,
        /// Whether `at.y` is measured from the terrain.
        #[serde(default)]
        on_ground: bool,
    },
    /// A tree: a trunk and two branches (capsules) and a crown of three blobs, six
    /// primitives.
    Tree {
        /// Where it stands, `(x, z)`.
        at: (f32, f32),
        /// Height.
        height: f32,
        /// Trunk material.
        trunk: String,
        /// Crown material.
        leaves: String,
    },
    /// A rock: an ellipsoid displaced by 3D value noise.
    Rock {
        /// Where it lies, `(x, z)`.
        at: (f32, f32),
        /// Size.
        radius: f32,
        /// Displacement amplitude relative to the radius.
        #[serde(default = "d_roughness")]
        roughness: f32,
        /// Material name.
        material: String,
    },
    /// Vineyard rows along x, repeated along +z.
    VineRows {
        /// Centre of row 0, `(x, z)`.
        at: (f32, f32),
        /// Number of rows.
        rows: u32,
        /// Distance between rows.
        spacing: f32,
        /// Row length.
        length: f32,
        /// Material name.
        material: String,
    },
    /// A hut: walls and a conical roof, blended.
    Hut {
        /// Where it stands, `(x, z)`.
        at: (f32, f32),
        /// Wall half-width.
        size: f32,
        /// Material name.
        material: String,
    },
    /// A power-8 Mandelbulb.
    Mandelbulb {
        /// Centre.
        at: Vec3,
        /// Iterations.
        #[serde(default = "d_iterations")]
        iterations: u32,
        /// Escape radius squared.
        #[serde(default = "d_bailout")]
        bailout: f32,
        /// The distance estimate's starting derivative (1; the reference paper's scene
        /// uses 1.5).
        #[serde(default = "d_derivative")]
        derivative: f32,
        /// Material name.
        material: String,
    },
}

fn d_roughness() -> f32 {
    0.18
}
fn d_iterations() -> u32 {
    4
}
fn d_bailout() -> f32 {
    256.0
}
fn d_derivative() -> f32 {
    1.0
}

fn invalid(path: impl Into<String>, message: impl Into<String>) -> SceneError {
    SceneError::Invalid {
        path: path.into(),
        message: message.into(),
    }
}

impl Scene {
    /// Parses and validates RON text.
    pub fn from_ron(text: &str) -> Result<Scene, SceneError> {
        if text.len() > MAX_SCENE_BYTES {
            return Err(SceneError::TooLarge { bytes: text.len() });
        }
        let scene: Scene = ron::Options::default()
            .from_str(text)
            .map_err(|e| SceneError::Syntax(e.to_string()))?;
        scene.validate()?;
        Ok(scene)
    }

    /// Reads, parses and validates a file.
    pub fn load(path: &Path) -> Result<Scene, SceneError> {
        let text =
            craterfield_core::files::read_text(path, MAX_SCENE_BYTES as u64).map_err(|e| {
                SceneError::Io {
                    path: path.display().to_string(),
                    message: e.to_string(),
                }
            })?;
        Scene::from_ron(&text)
    }

    /// A builtin scene by name ([`BUILTIN`]).
    pub fn builtin(name: &str) -> Result<Scene, SceneError> {
        let text = match name {
            "scene0" => include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/scene0.ron")),
            "mandelbulb" => include_str!(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/scenes/mandelbulb.ron"
            )),
            "sparse" => include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/sparse.ron")),
            "forest" => include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/forest.ron")),
            other => return Err(SceneError::UnknownBuiltin(other.to_string())),
        };
        Scene::from_ron(text)
    }

    /// A builtin name, or else a path to a RON file.
    pub fn named_or_file(name: &str) -> Result<Scene, SceneError> {
        if BUILTIN.contains(&name) {
            Scene::builtin(name)
        } else {
            Scene::load(Path::new(name))
        }
    }

    /// The index of a material by name.
    pub fn material_index(&self, name: &str) -> Option<u32> {
        self.materials
            .iter()
            .position(|m| m.name == name)
            .map(|i| i as u32)
    }

    /// The scene's march settings with defaults filled in.
    pub fn march_settings(&self) -> MarchSettings {
        self.march.resolve(&self.lighting)
    }

    /// Checks every value; the error names the first bad one.
    pub fn validate(&self) -> Result<(), SceneError> {
        self.camera.camera()?;
        let (w, h) = self.size;
        if w == 0 || h == 0 || w > 16384 || h > 16384 {
            return Err(invalid("size", format!("{w}x{h} is not in 1..=16384")));
        }
        self.validate_lighting()?;
        validate_march(&self.march_settings())?;
        if let Some(t) = &self.terrain {
            validate_fbm(&t.fbm)?;
            self.check_material("terrain.material", &t.material)?;
        }
        if self.materials.is_empty() || self.materials.len() > 256 {
            return Err(invalid("materials", "needs 1..=256 materials"));
        }
        for (i, m) in self.materials.iter().enumerate() {
            let path = format!("materials[{i}]");
            if self.materials[..i].iter().any(|o| o.name == m.name) {
                return Err(invalid(
                    path,
                    format!("a second material named `{}`", m.name),
                ));
            }
            check_vec(&format!("{path}.colour"), m.colour, 0.0, 16.0)?;
            check_range(&format!("{path}.reflectivity"), m.reflectivity, 0.0, 1.0)?;
        }
        if self.objects.len() > MAX_OBJECTS {
            return Err(invalid(
                "objects",
                format!("{} objects; at most {MAX_OBJECTS}", self.objects.len()),
            ));
        }
        for (i, o) in self.objects.iter().enumerate() {
            self.validate_object(&format!("objects[{i}]"), o)?;
        }
        Ok(())
    }

    fn check_material(&self, path: &str, name: &str) -> Result<(), SceneError> {
        match self.material_index(name) {
            Some(_) => Ok(()),
            None => Err(invalid(path, format!("no material named `{name}`"))),
        }
    }

    fn validate_lighting(&self) -> Result<(), SceneError> {
        match &self.lighting {
            Lighting::Paper(p) => {
                if p.lights.is_empty() || p.lights.len() > 16 {
                    return Err(invalid("lighting.lights", "needs 1..=16 lights"));
                }
                for (i, l) in p.lights.iter().enumerate() {
                    let path = format!("lighting.lights[{i}]");
                    check_vec(
                        &format!("{path}.position"),
                        l.position,
                        -MAX_COORDINATE,
                        MAX_COORDINATE,
                    )?;
                    check_range(&format!("{path}.emission"), l.emission, 0.0, 1.0e6)?;
                }
                check_range("lighting.shininess", p.shininess, 0.0, 4096.0)?;
                check_range("lighting.specular", p.specular, 0.0, 100.0)?;
                check_range("lighting.ambient", p.ambient, 0.0, 100.0)?;
                check_range("lighting.reflection_scale", p.reflection_scale, 0.0, 1.0)?;
                check_range("lighting.shadow_k", p.shadow_k, 1.0e-3, 1.0e3)?;
                check_range("lighting.fog", p.fog, 0.0, 1.0)?;
                check_range("lighting.gamma", p.gamma, 0.05, 10.0)?;
                if p.bounces > 8 {
                    return Err(invalid("lighting.bounces", "at most 8"));
                }
            }
            Lighting::World(w) => {
                check_vec("lighting.sun", w.sun, -1.0e3, 1.0e3)?;
                if w.sun.length() < 1.0e-6 {
                    return Err(invalid("lighting.sun", "must not be zero"));
                }
                check_vec("lighting.sun_colour", w.sun_colour, 0.0, 100.0)?;
                check_vec("lighting.sky[0]", w.sky[0], 0.0, 100.0)?;
                check_vec("lighting.sky[1]", w.sky[1], 0.0, 100.0)?;
                check_range("lighting.fog", w.fog, 0.0, 10.0)?;
                check_range("lighting.gamma", w.gamma, 0.05, 10.0)?;
            }
        }
        Ok(())
    }

    fn validate_object(&self, path: &str, o: &Object) -> Result<(), SceneError> {
        let c = MAX_COORDINATE;
        match o {
            Object::Shape {
                shape,
                at,
                rotate,
                material,
                ..
            } => {
                check_vec(&format!("{path}.Shape.at"), *at, -c, c)?;
                check_vec(&format!("{path}.Shape.rotate"), *rotate, -3600.0, 3600.0)?;
                validate_prim(&format!("{path}.Shape.shape"), shape)?;
                self.check_material(&format!("{path}.Shape.material"), material)
            }
            Object::Tree {
                at,
                height,
                trunk,
                leaves,
            } => {
                check_xz(&format!("{path}.Tree.at"), *at)?;
                check_range(&format!("{path}.Tree.height"), *height, 0.1, 1000.0)?;
                self.check_material(&format!("{path}.Tree.trunk"), trunk)?;
                self.check_material(&format!("{path}.Tree.leaves"), leaves)
            }
            Object::Rock {
                at,
                radius,
                roughness,
                material,
            } => {
                check_xz(&format!("{path}.Rock.at"), *at)?;
                check_range(&format!("{path}.Rock.radius"), *radius, 0.01, 1000.0)?;
                check_range(&format!("{path}.Rock.roughness"), *roughness, 0.0, 1.0)?;
                self.check_material(&format!("{path}.Rock.material"), material)
            }
            Object::VineRows {
                at,
                rows,
                spacing,
                length,
                material,
            } => {
                check_xz(&format!("{path}.VineRows.at"), *at)?;
                if !(1..=64).contains(rows) {
                    return Err(invalid(format!("{path}.VineRows.rows"), "must be 1..=64"));
                }
                check_range(&format!("{path}.VineRows.spacing"), *spacing, 1.5, 100.0)?;
                check_range(&format!("{path}.VineRows.length"), *length, 0.5, 1000.0)?;
                self.check_material(&format!("{path}.VineRows.material"), material)
            }
            Object::Hut { at, size, material } => {
                check_xz(&format!("{path}.Hut.at"), *at)?;
                check_range(&format!("{path}.Hut.size"), *size, 0.1, 100.0)?;
                self.check_material(&format!("{path}.Hut.material"), material)
            }
            Object::Mandelbulb {
                at,
                iterations,
                bailout,
                derivative,
                material,
            } => {
                check_vec(&format!("{path}.Mandelbulb.at"), *at, -c, c)?;
                check_range(
                    &format!("{path}.Mandelbulb.derivative"),
                    *derivative,
                    0.1,
                    100.0,
                )?;
                if !(1..=16).contains(iterations) {
                    return Err(invalid(
                        format!("{path}.Mandelbulb.iterations"),
                        "must be 1..=16",
                    ));
                }
                check_range(&format!("{path}.Mandelbulb.bailout"), *bailout, 4.0, 1.0e6)?;
                self.check_material(&format!("{path}.Mandelbulb.material"), material)
            }
        }
    }
}

fn check_range(path: &str, v: f32, lo: f32, hi: f32) -> Result<(), SceneError> {
    if v.is_finite() && v >= lo && v <= hi {
        Ok(())
    } else {
        Err(invalid(path, format!("must be in [{lo}, {hi}], got {v}")))
    }
}

fn check_vec(path: &str, v: Vec3, lo: f32, hi: f32) -> Result<(), SceneError> {
    for (axis, x) in ["x", "y", "z"].iter().zip(v.to_array()) {
        check_range(&format!("{path}.{axis}"), x, lo, hi)?;
    }
    Ok(())
}

fn check_xz(path: &str, (x, z): (f32, f32)) -> Result<(), SceneError> {
    check_range(&format!("{path}.x"), x, -MAX_COORDINATE, MAX_COORDINATE)?;
    check_range(&format!("{path}.z"), z, -MAX_COORDINATE, MAX_COORDINATE)
}

fn check_positive(path: &str, v: f32) -> Result<(), SceneError> {
    check_range(path, v, 1.0e-6, MAX_COORDINATE)
}

fn validate_prim(path: &str, p: &PrimKind) -> Result<(), SceneError> {
    let c = MAX_COORDINATE;
    match *p {
        PrimKind::Sphere { r } => check_positive(&format!("{path}.r"), r),
        PrimKind::Box { half } => check_vec(&format!("{path}.half"), half, 1.0e-6, c),
        PrimKind::RoundBox { half, r } => {
            check_vec(&format!("{path}.half"), half, 1.0e-6, c)?;
            check_range(&format!("{path}.r"), r, 0.0, half.min_element())
        }
        PrimKind::Capsule { a, b, r } => {
            check_vec(&format!("{path}.a"), a, -c, c)?;
            check_vec(&format!("{path}.b"), b, -c, c)?;
            check_positive(&format!("{path}.r"), r)
        }
        PrimKind::Torus { major, minor } => {
            check_positive(&format!("{path}.major"), major)?;
            check_positive(&format!("{path}.minor"), minor)
        }
        PrimKind::Cylinder { r, h } => {
            check_positive(&format!("{path}.r"), r)?;
            check_positive(&format!("{path}.h"), h)
        }
        PrimKind::CappedCone { h, r1, r2 } => {
            check_positive(&format!("{path}.h"), h)?;
            check_range(&format!("{path}.r1"), r1, 0.0, c)?;
            check_range(&format!("{path}.r2"), r2, 0.0, c)?;
            if r1 + r2 <= 0.0 {
                return Err(invalid(path, "r1 + r2 must be positive"));
            }
            Ok(())
        }
        PrimKind::Octahedron { s } => check_positive(&format!("{path}.s"), s),
        PrimKind::Ellipsoid { r } => check_vec(&format!("{path}.r"), r, 1.0e-6, c),
        PrimKind::Plane { normal, offset } => {
            check_vec(&format!("{path}.normal"), normal, -1.0e3, 1.0e3)?;
            if normal.length() < 1.0e-6 {
                return Err(invalid(format!("{path}.normal"), "must not be zero"));
            }
            check_range(&format!("{path}.offset"), offset, -c, c)
        }
    }
}

fn validate_march(m: &MarchSettings) -> Result<(), SceneError> {
    if !(1..=100_000).contains(&m.max_steps) {
        return Err(invalid("march.max_steps", "must be 1..=100000"));
    }
    check_range("march.hit", m.hit, 1.0e-9, 1.0)?;
    check_range("march.hit_per_t", m.hit_per_t, 0.0, 0.1)?;
    check_range("march.escape", m.escape, 1.0e-3, 1.0e7)?;
    if m.far.is_nan() || m.far <= 0.0 {
        return Err(invalid("march.far", "must be positive (infinity allowed)"));
    }
    check_range("march.ray_offset", m.ray_offset, 0.0, 1.0)?;
    check_range("march.normal_eps", m.normal_eps, 1.0e-7, 1.0)?;
    check_range("march.relax", m.relax, 1.0, 2.0)
}

fn validate_fbm(f: &Fbm) -> Result<(), SceneError> {
    check_range("terrain.fbm.base", f.base, -1.0e4, 1.0e4)?;
    check_range("terrain.fbm.amplitude", f.amplitude, 0.0, 1.0e4)?;
    check_range("terrain.fbm.frequency", f.frequency, 1.0e-6, 1.0e3)?;
    check_range("terrain.fbm.lacunarity", f.lacunarity, 1.0, 8.0)?;
    check_range("terrain.fbm.gain", f.gain, 0.0, 1.0)?;
    check_range("terrain.fbm.rotation", f.rotation, -7.0, 7.0)?;
    if !(1..=12).contains(&f.octaves) {
        return Err(invalid("terrain.fbm.octaves", "must be 1..=12"));
    }
    Ok(())
}

/// The rotation matrix of Euler angles in degrees, applied about x, then y, then z.
pub fn rotation_degrees(angles: Vec3) -> Mat3 {
    let r = angles * (std::f32::consts::PI / 180.0);
    Mat3::from_rotation_z(r.z) * Mat3::from_rotation_y(r.y) * Mat3::from_rotation_x(r.x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builtins_parse_and_validate() {
        for name in BUILTIN {
            let s = Scene::builtin(name).unwrap();
            assert!(!s.objects.is_empty(), "{name}");
        }
        assert!(matches!(
            Scene::builtin("nope"),
            Err(SceneError::UnknownBuiltin(_))
        ));
    }

    /// A misspelt field in any part of a scene (camera, light, object, shape) is an error
    /// naming it and its line, never a silent default.
    #[test]
    fn unknown_fields_are_errors_that_name_the_line() {
        let scene0 = include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/scene0.ron"));
        for (from, to, field, line) in [
            ("fov: 30.0", "fov: 30.0, roll: 1.0", "roll", 5),
            (
                "emission: 200.0",
                "emission: 200.0, colour: 1.0",
                "colour",
                8,
            ),
            (
                "material: \"red\")",
                "material: \"red\", scale: 2.0)",
                "scale",
                31,
            ),
            (
                "Sphere(r: 3.0)",
                "Sphere(r: 3.0, radius: 1.0)",
                "radius",
                31,
            ),
        ] {
            let text = scene0.replacen(from, to, 1);
            assert_ne!(text, scene0, "{from}");
            let err = Scene::from_ron(&text).unwrap_err().to_string();
            assert!(
                err.contains(field) && err.contains(&format!("{line}:")),
                "{field}: {err}"
            );
        }
    }

    #[test]
    fn bad_values_name_their_place() {
        let text = include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/scene0.ron"))
            .replace("r: 3.0", "r: -3.0");
        let err = Scene::from_ron(&text).unwrap_err().to_string();
        assert!(err.contains("objects[") && err.contains(".r"), "{err}");
        let text = include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/scene0.ron"))
            .replace("material: \"red\"", "material: \"nope\"");
        let err = Scene::from_ron(&text).unwrap_err().to_string();
        assert!(err.contains("no material named `nope`"), "{err}");
        let text = include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/scene0.ron"))
            .replace("fov: 30.0", "fov: NaN");
        assert!(Scene::from_ron(&text).is_err());
        assert!(matches!(
            Scene::from_ron("Scene("),
            Err(SceneError::Syntax(_))
        ));
    }

    #[test]
    fn paper_defaults_are_the_reference_settings() {
        let s = Scene::builtin("scene0").unwrap();
        assert_eq!(s.march_settings(), MarchSettings::PAPER);
        let Lighting::Paper(p) = &s.lighting else {
            panic!("scene0 uses paper lighting")
        };
        assert_eq!(
            (p.shininess, p.specular, p.ambient, p.bounces),
            (15.0, 0.2, 0.01, 3)
        );
    }
}
