//! The 3D scene compiler: a scene and a camera to a [`Plan`], run once per camera update,
//! with every optimization of the emitted world switchable for measurement. The object
//! geometry (trees, rocks, huts as primitives with bounds) is `objects`.
//!
//! Emitter-side (decided here, per camera): frustum culling (behind the camera, beyond the
//! far plane, outside the side planes, by bounding sphere), LOD by projected size (an
//! object takes the coarsest simplified form whose surface error stays under half a pixel
//! at the camera's resolution: a tree's six primitives become four, its trunk and its
//! crown's three masses; a rock loses its noise), step tiers from the visible
//! object count, terrain heights baked as literals, the height early-out above the tallest
//! visible object, and the cache key. Shader-side (decided here, executed by both
//! renderers): AABB guards, nearest-row repetition, material IDs, distance-adaptive AO, the
//! terrain-and-bounds shadow, the dot-fract hash, the Lipschitz step from the FBM's slope
//! bound, and analytic terrain normals.
//!
//! The plan depends on the camera only through the visible set and the LOD levels, so the
//! key (a hash of the scene, the visible set with LODs, the step count and the options)
//! names the plan: an unchanged key is an unchanged shader.

mod objects;

use glam::Vec3;
use thiserror::Error;

use crate::plan3d::{
    AoMode, Camera3d, Hash, Lift, March, Material, Node, PaperShading, Plan, Shading, ShadowMode,
    Shape, Sphere, TerrainPlan, WorldShading,
};
use crate::scene::{Lighting, MarchSettings, Scene, SceneError};
use craterfield_wgsl::fnv::Fnv64;
use objects::{Lod, Prepared, guard_for, prepare};

/// The step factor used without the Lipschitz bound: the common hand-tuned heuristic.
pub const HEURISTIC_STEP: f32 = 0.68;

/// One switchable optimization of the emitted world.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Optimization {
    /// Objects outside the view frustum are left out.
    FrustumCull,
    /// Far objects are simplified.
    Lod,
    /// The step budget follows the visible object count.
    StepTiers,
    /// Terrain heights under objects are literals.
    ConstantBaking,
    /// Above the tallest visible object only the terrain is evaluated.
    HeightEarlyOut,
    /// Boxes skip objects far from the sample point.
    AabbGuards,
    /// Only the nearest vineyard row (and its neighbour) is evaluated.
    NearestRow,
    /// The march tracks the nearest object's material.
    MaterialIds,
    /// Fewer AO taps far away, none on flat terrain above the camera.
    AdaptiveAo,
    /// A 4-sample terrain-and-bounds shadow instead of a full soft-shadow march.
    TerrainShadow,
    /// The multiply-add hash instead of the `sin` hash.
    DotFractHash,
    /// The terrain's step factor from its slope bound instead of a heuristic.
    LipschitzStep,
    /// Terrain normals from the noise's gradient instead of differences.
    AnalyticNormal,
}

impl Optimization {
    /// Every optimization.
    pub const ALL: [Optimization; 13] = [
        Optimization::FrustumCull,
        Optimization::Lod,
        Optimization::StepTiers,
        Optimization::ConstantBaking,
        Optimization::HeightEarlyOut,
        Optimization::AabbGuards,
        Optimization::NearestRow,
        Optimization::MaterialIds,
        Optimization::AdaptiveAo,
        Optimization::TerrainShadow,
        Optimization::DotFractHash,
        Optimization::LipschitzStep,
        Optimization::AnalyticNormal,
    ];

    /// The short name (`no-<name>` in the benchmark).
    pub fn name(self) -> &'static str {
        match self {
            Optimization::FrustumCull => "frustum",
            Optimization::Lod => "lod",
            Optimization::StepTiers => "step-tiers",
            Optimization::ConstantBaking => "baking",
            Optimization::HeightEarlyOut => "early-out",
            Optimization::AabbGuards => "guards",
            Optimization::NearestRow => "nearest-row",
            Optimization::MaterialIds => "material-ids",
            Optimization::AdaptiveAo => "adaptive-ao",
            Optimization::TerrainShadow => "terrain-shadow",
            Optimization::DotFractHash => "dot-fract-hash",
            Optimization::LipschitzStep => "lipschitz",
            Optimization::AnalyticNormal => "analytic-normal",
        }
    }
}

/// Step budgets by visible object count: with at most `tiers[i].0` objects visible, the
/// budget is `tiers[i].1 / base` of the scene's step budget.
#[derive(Clone, Debug, PartialEq)]
pub struct StepTiers {
    /// The budget that stands for the scene's full step count.
    pub base: u32,
    /// `(most visible objects, steps)`, by increasing count.
    pub tiers: Vec<(u32, u32)>,
}

impl Default for StepTiers {
    /// 43, 62, 82 steps of a base 96 for at most 2, 5 and 10 visible objects.
    fn default() -> StepTiers {
        StepTiers {
            base: 96,
            tiers: vec![(2, 43), (5, 62), (10, 82)],
        }
    }
}

impl StepTiers {
    /// The step budget for `visible` objects out of a full budget of `full` steps.
    pub fn steps(&self, visible: usize, full: u32) -> u32 {
        let tier = self
            .tiers
            .iter()
            .find(|(most, _)| visible <= *most as usize)
            .map_or(self.base, |t| t.1);
        let scaled = (full as u64 * tier as u64).div_ceil(self.base.max(1) as u64);
        scaled.clamp(1, full as u64) as u32
    }
}

/// What the emitter does; [`Default`] turns everything on.
#[derive(Clone, Debug, PartialEq)]
pub struct CompileOptions {
    /// Enabled optimizations (see [`Optimization`]).
    pub enabled: Vec<Optimization>,
    /// An object takes its coarsest simplified form whose surface error, projected at the
    /// nearest point of its bounding sphere, covers at most this many pixels.
    pub lod_pixels: f32,
    /// Step budgets.
    pub tiers: StepTiers,
    /// Width over height of the images the plan is for (the frustum's side planes).
    pub aspect: f32,
    /// Height in pixels of the images the plan is for (the size of a pixel for the LOD).
    pub height: u32,
}

impl Default for CompileOptions {
    fn default() -> CompileOptions {
        CompileOptions {
            enabled: Optimization::ALL.to_vec(),
            lod_pixels: 0.5,
            tiers: StepTiers::default(),
            aspect: 16.0 / 9.0,
            height: 720,
        }
    }
}

impl CompileOptions {
    /// Every optimization off: the naive emit the others are measured against.
    pub fn naive() -> CompileOptions {
        CompileOptions {
            enabled: Vec::new(),
            ..CompileOptions::default()
        }
    }

    /// The reference paper's renderer: every object every step, material indices tracked
    /// during the march, the scene's own step budget.
    pub fn paper() -> CompileOptions {
        CompileOptions {
            enabled: vec![Optimization::MaterialIds],
            ..CompileOptions::default()
        }
    }

    /// These options with one optimization switched off.
    pub fn without(&self, o: Optimization) -> CompileOptions {
        let mut r = self.clone();
        r.enabled.retain(|e| *e != o);
        r
    }

    /// Whether an optimization is on.
    pub fn on(&self, o: Optimization) -> bool {
        self.enabled.contains(&o)
    }

    fn bits(&self) -> u32 {
        Optimization::ALL
            .iter()
            .enumerate()
            .filter(|(_, o)| self.on(**o))
            .fold(0, |acc, (i, _)| acc | 1 << i)
    }
}

/// Why a scene cannot be emitted.
#[derive(Clone, Debug, PartialEq, Error)]
#[non_exhaustive]
pub enum CompileError {
    /// The scene is invalid.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// An option is out of range.
    #[error("emit option {what}: {message}")]
    Option {
        /// Which option.
        what: &'static str,
        /// What is wrong.
        message: String,
    },
}

/// Which objects a camera sees, and at which level of detail.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Visibility {
    /// `(object index, level)`: level 0 is full detail, `l > 0` the object's `l`-th
    /// simplified form.
    pub objects: Vec<(u32, u8)>,
}

/// A validated scene with its objects prepared, ready to emit plans for cameras.
#[derive(Clone, Debug)]
pub struct WorldCompiler {
    scene: Scene,
    settings: MarchSettings,
    fingerprint: u64,
    objects: Vec<Prepared>,
    /// Terrain height under each grounded object (0 without terrain).
    ground: Vec<f32>,
}

impl WorldCompiler {
    /// Validates and prepares `scene`.
    pub fn new(scene: &Scene) -> Result<WorldCompiler, CompileError> {
        scene.validate()?;
        let text = ron::to_string(scene).unwrap_or_default();
        let fingerprint = Fnv64::new().bytes(text.as_bytes()).finish();
        let objects: Vec<Prepared> = scene.objects.iter().map(|o| prepare(scene, o)).collect();
        let ground = objects
            .iter()
            .map(|p| match (p.anchor, &scene.terrain) {
                (Some((x, z)), Some(t)) => t.fbm.height(Hash::DotFract, x, z).0,
                _ => 0.0,
            })
            .collect();
        Ok(WorldCompiler {
            settings: scene.march_settings(),
            scene: scene.clone(),
            fingerprint,
            objects,
            ground,
        })
    }

    /// The scene.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The objects `camera` sees and their levels of detail.
    pub fn visibility(&self, camera: &Camera3d, opts: &CompileOptions) -> Visibility {
        let objects = self
            .objects
            .iter()
            .enumerate()
            .filter_map(|(i, p)| {
                let bound = self.world_bound(i, p);
                if opts.on(Optimization::FrustumCull)
                    && !in_frustum(camera, &bound, opts, &self.settings)
                {
                    return None;
                }
                let level = if opts.on(Optimization::Lod) {
                    lod_level(camera, &bound, &p.lods, opts)
                } else {
                    0
                };
                Some((i as u32, level))
            })
            .collect();
        Visibility { objects }
    }

    fn world_bound(&self, i: usize, p: &Prepared) -> Sphere {
        Sphere {
            centre: p.bound.centre + Vec3::Y * self.ground[i],
            radius: p.bound.radius,
        }
    }

    /// The plan for `camera`.
    pub fn emit(&self, camera: &Camera3d, opts: &CompileOptions) -> Result<Plan, CompileError> {
        check_options(opts)?;
        let vis = self.visibility(camera, opts);
        let steps = if opts.on(Optimization::StepTiers) {
            opts.tiers.steps(vis.objects.len(), self.settings.max_steps)
        } else {
            self.settings.max_steps
        };
        let nodes: Vec<Node> = vis
            .objects
            .iter()
            .flat_map(|&(i, lod)| self.object_nodes(i as usize, lod, opts))
            .collect();
        let terrain = self.terrain_plan(opts);
        let early_out = match (&terrain, opts.on(Optimization::HeightEarlyOut)) {
            (Some(_), true) if !nodes.is_empty() => Some(
                nodes
                    .iter()
                    .map(|n| n.bound.centre.y + n.bound.radius)
                    .fold(f32::NEG_INFINITY, f32::max),
            ),
            _ => None,
        };
        let key = self.key(&vis, steps, opts);
        Ok(Plan {
            key,
            march: self.march(steps, opts),
            terrain,
            early_out,
            nodes,
            materials: self.materials(),
            shading: self.shading(opts),
            material_ids: opts.on(Optimization::MaterialIds),
            hash: if opts.on(Optimization::DotFractHash) {
                Hash::DotFract
            } else {
                Hash::Sin
            },
        })
    }

    fn key(&self, vis: &Visibility, steps: u32, opts: &CompileOptions) -> u64 {
        let mut h = Fnv64::new();
        h.u64(self.fingerprint).u32(steps).u32(opts.bits());
        for &(i, lod) in &vis.objects {
            h.u32(i).u32(lod as u32);
        }
        h.finish()
    }

    fn object_nodes(&self, i: usize, lod: u8, opts: &CompileOptions) -> Vec<Node> {
        let p = &self.objects[i];
        let parts = match lod {
            0 => &p.full,
            l => &p.lods[l as usize - 1].parts,
        };
        let lift = match p.anchor {
            None => Lift::None,
            Some((x, z))
                if self.scene.terrain.is_some() && !opts.on(Optimization::ConstantBaking) =>
            {
                Lift::Ground { x, z }
            }
            Some(_) => Lift::Baked(self.ground[i]),
        };
        parts
            .nodes
            .iter()
            .map(|n| {
                let mut n = n.clone();
                if opts.on(Optimization::AabbGuards) && n.cost > 1 {
                    n.guard = guard_for(&n.bound);
                }
                if let Shape::Rows { nearest, .. } = &mut n.shape {
                    *nearest = opts.on(Optimization::NearestRow);
                    if *nearest {
                        n.cost = 2;
                    }
                }
                n.bound.centre.y += self.ground[i];
                if let Lift::Ground { .. } = lift {
                    n.cost += 1;
                }
                n.lift = lift;
                n
            })
            .collect()
    }

    fn terrain_plan(&self, opts: &CompileOptions) -> Option<TerrainPlan> {
        let t = self.scene.terrain.as_ref()?;
        Some(TerrainPlan {
            fbm: t.fbm,
            material: self.scene.material_index(&t.material).unwrap_or(0),
            step_scale: if opts.on(Optimization::LipschitzStep) {
                t.fbm.step_scale()
            } else {
                1.0
            },
            analytic_normal: opts.on(Optimization::AnalyticNormal),
        })
    }

    fn march(&self, steps: u32, opts: &CompileOptions) -> March {
        let s = &self.settings;
        // Without the bound, a world with terrain steps by the heuristic factor everywhere.
        let step_factor = if self.scene.terrain.is_some() && !opts.on(Optimization::LipschitzStep) {
            HEURISTIC_STEP
        } else {
            1.0
        };
        March {
            max_steps: steps,
            hit: s.hit,
            hit_per_t: s.hit_per_t,
            far: s.far,
            escape: s.escape,
            step_factor,
            ray_offset: s.ray_offset,
            normal_eps: s.normal_eps,
            relax: s.relax,
        }
    }

    fn materials(&self) -> Vec<Material> {
        self.scene
            .materials
            .iter()
            .map(|m| Material {
                colour: m.colour,
                reflectivity: m.reflectivity,
            })
            .collect()
    }

    fn shading(&self, opts: &CompileOptions) -> Shading {
        match &self.scene.lighting {
            Lighting::Paper(p) => Shading::Paper(PaperShading {
                lights: p.lights.clone(),
                shininess: p.shininess,
                specular: p.specular,
                ambient: p.ambient,
                bounces: p.bounces,
                reflection_scale: p.reflection_scale,
                // The reference renderer casts shadows only in scenes of several objects.
                shadow_k: (self.scene.objects.len() > 1).then_some(p.shadow_k),
                fog: p.fog,
                gamma: p.gamma,
            }),
            Lighting::World(w) => Shading::World(WorldShading {
                sun: w.sun.normalize(),
                sun_colour: w.sun_colour,
                sky: w.sky,
                ao: if opts.on(Optimization::AdaptiveAo) {
                    AoMode::Adaptive {
                        near: 5,
                        far: 3,
                        near_distance: 10.0,
                    }
                } else {
                    AoMode::Fixed(5)
                },
                shadow: if opts.on(Optimization::TerrainShadow) {
                    ShadowMode::TerrainAndBounds {
                        steps: 4,
                        spacing: 1.0,
                    }
                } else {
                    ShadowMode::Full {
                        steps: self.settings.max_steps,
                        k: 8.0,
                    }
                },
                fog: w.fog,
                gamma: w.gamma,
            }),
        }
    }
}

/// The plan of `scene` for `camera` (see [`WorldCompiler`], which keeps the prepared
/// objects between camera updates).
pub fn emit(scene: &Scene, camera: &Camera3d, opts: &CompileOptions) -> Result<Plan, CompileError> {
    WorldCompiler::new(scene)?.emit(camera, opts)
}

fn check_options(opts: &CompileOptions) -> Result<(), CompileError> {
    let bad = |what, message: &str| {
        Err(CompileError::Option {
            what,
            message: message.to_string(),
        })
    };
    if opts.lod_pixels.is_nan() || opts.lod_pixels < 0.0 {
        return bad("lod_pixels", "must be a non-negative number");
    }
    if opts.height == 0 {
        return bad("height", "must be at least one pixel");
    }
    if !(opts.aspect > 0.0 && opts.aspect.is_finite()) {
        return bad("aspect", "must be positive and finite");
    }
    if opts.tiers.base == 0 || opts.tiers.tiers.iter().any(|t| t.1 == 0) {
        return bad("tiers", "step counts must be positive");
    }
    Ok(())
}

/// The level of detail of an object with bounding sphere `bound` and simplified forms
/// `lods`: the coarsest form whose error, over the size of a pixel at the bound's nearest
/// point, is at most `opts.lod_pixels` (0, full detail, when none is, or when the eye is
/// inside the bound).
fn lod_level(camera: &Camera3d, bound: &Sphere, lods: &[Lod], opts: &CompileOptions) -> u8 {
    let near = (bound.centre - camera.position).length() - bound.radius;
    if near.is_nan() || near <= 0.0 {
        return 0;
    }
    let pixel = 2.0 * near * camera.tan_half_fov / opts.height as f32;
    let allowed = opts.lod_pixels * pixel;
    lods.iter()
        .rposition(|l| l.error <= allowed)
        .map_or(0, |i| i as u8 + 1)
}

/// Whether a bounding sphere can touch the view: in front of the eye (dot with the view
/// direction), before the far plane, and inside the four side planes.
fn in_frustum(camera: &Camera3d, s: &Sphere, opts: &CompileOptions, m: &MarchSettings) -> bool {
    if !s.radius.is_finite() {
        return true;
    }
    let rel = s.centre - camera.position;
    let depth = rel.dot(camera.forward);
    if depth < -s.radius || depth - s.radius > m.far.min(m.escape) {
        return false;
    }
    let ty = camera.tan_half_fov;
    let tx = ty * opts.aspect;
    // Inward plane normals of the side planes through the eye.
    let planes = [
        (camera.forward * tx + camera.right).normalize(),
        (camera.forward * tx - camera.right).normalize(),
        (camera.forward * ty + camera.up).normalize(),
        (camera.forward * ty - camera.up).normalize(),
    ];
    planes.iter().all(|n| rel.dot(*n) >= -s.radius)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn forest() -> (WorldCompiler, Camera3d) {
        let scene = Scene::builtin("forest").unwrap();
        let cam = scene.camera.camera().unwrap();
        (WorldCompiler::new(&scene).unwrap(), cam)
    }

    #[test]
    fn tiers_follow_the_visible_count() {
        let t = StepTiers::default();
        assert_eq!(t.steps(0, 96), 43);
        assert_eq!(t.steps(2, 96), 43);
        assert_eq!(t.steps(5, 96), 62);
        assert_eq!(t.steps(10, 96), 82);
        assert_eq!(t.steps(11, 96), 96);
        assert_eq!(t.steps(1, 3000), 1344);
    }

    #[test]
    fn culling_drops_what_is_behind_and_keeps_what_is_ahead() {
        let (e, cam) = forest();
        let all = e.visibility(&cam, &CompileOptions::naive()).objects.len();
        let seen = e.visibility(&cam, &CompileOptions::default()).objects.len();
        assert_eq!(all, e.scene().objects.len());
        assert!(seen < all && seen > 0, "{seen} of {all}");
        // Turned around, the objects in front before are behind now.
        let back = Camera3d::looking(cam.position, -cam.forward, Vec3::Y, 50.0).unwrap();
        let behind = e.visibility(&back, &CompileOptions::default());
        let front = e.visibility(&cam, &CompileOptions::default());
        let both = front
            .objects
            .iter()
            .filter(|o| behind.objects.iter().any(|b| b.0 == o.0))
            .count();
        assert!(both < front.objects.len() / 2, "{both}");
    }

    #[test]
    fn the_key_changes_with_the_visible_set_only() {
        let (e, cam) = forest();
        let o = CompileOptions::default();
        let a = e.emit(&cam, &o).unwrap();
        let nudged = Camera3d::looking(
            cam.position + Vec3::new(0.0, 0.0, 0.01),
            cam.forward,
            Vec3::Y,
            50.0,
        )
        .unwrap();
        let b = e.emit(&nudged, &o).unwrap();
        assert_eq!(a.key, b.key);
        assert_eq!(a, b);
        let turned =
            Camera3d::looking(cam.position, Vec3::new(1.0, 0.0, 0.3), Vec3::Y, 50.0).unwrap();
        let c = e.emit(&turned, &o).unwrap();
        assert_ne!(a.key, c.key);
        let d = e.emit(&cam, &o.without(Optimization::AabbGuards)).unwrap();
        assert_ne!(a.key, d.key);
    }

    #[test]
    fn naive_and_optimized_plans_differ_as_documented() {
        let (e, cam) = forest();
        let naive = e.emit(&cam, &CompileOptions::naive()).unwrap();
        let all = e.emit(&cam, &CompileOptions::default()).unwrap();
        assert!(naive.nodes.iter().all(|n| n.guard.is_none()));
        assert!(all.nodes.iter().any(|n| n.guard.is_some()));
        assert!(
            naive
                .nodes
                .iter()
                .any(|n| matches!(n.lift, Lift::Ground { .. }))
        );
        assert!(
            all.nodes
                .iter()
                .all(|n| !matches!(n.lift, Lift::Ground { .. }))
        );
        assert_eq!(naive.march.step_factor, HEURISTIC_STEP);
        assert!(all.terrain.unwrap().step_scale > HEURISTIC_STEP);
        assert!(all.early_out.is_some() && naive.early_out.is_none());
        assert_eq!(naive.march.max_steps, 96);
    }

    #[test]
    fn the_paper_plan_keeps_every_object_and_the_reference_settings() {
        let scene = Scene::builtin("scene0").unwrap();
        let cam = scene.camera.camera().unwrap();
        let plan = emit(&scene, &cam, &CompileOptions::paper()).unwrap();
        assert_eq!(plan.nodes.len(), 6);
        assert_eq!(plan.march.max_steps, 3000);
        assert_eq!(plan.march.hit, 5.0e-6);
        assert!(plan.material_ids);
        let Shading::Paper(p) = &plan.shading else {
            panic!("paper shading")
        };
        assert_eq!(p.shadow_k, Some(3.0));
    }
}
