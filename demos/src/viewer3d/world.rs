//! [`World`]: a loaded scene ready to render: its compiler, the emitter options the panel
//! switches, the camera, and the plan of the current view with its statistics. The plan is
//! emitted again only when the camera, the options or the image's aspect change.

use craterfield::march3d::compile::{CompileOptions, Optimization, WorldCompiler};
use craterfield::march3d::scene::{Lighting, Scene};
use craterfield::march3d::{Camera3d, Plan};

use super::camera::ViewCamera;

/// What the compiler decided for the current view.
#[derive(Clone, Debug, PartialEq)]
pub struct PlanStats {
    /// The plan's cache key (an unchanged key is an unchanged shader).
    pub key: u64,
    /// The march's step budget in this plan (the step tier when tiers are on).
    pub steps: u32,
    /// The scene's full step budget.
    pub full_steps: u32,
    /// Objects in the scene.
    pub objects: usize,
    /// Objects the camera sees (the rest were culled).
    pub visible: usize,
    /// Visible objects drawn in their far, simplified form.
    pub far_lod: usize,
    /// Primitive nodes in the plan.
    pub nodes: usize,
    /// Height above which only the terrain is evaluated, if the plan has one.
    pub early_out: Option<f32>,
}

impl PlanStats {
    /// Objects left out by frustum culling.
    pub fn culled(&self) -> usize {
        self.objects.saturating_sub(self.visible)
    }
}

/// A scene, its compiler, options and camera, and the plan of the current view.
pub(crate) struct World {
    name: String,
    compiler: WorldCompiler,
    options: CompileOptions,
    pub(crate) camera: ViewCamera,
    /// The camera and aspect the plan was emitted for.
    planned_for: Option<(Camera3d, [u32; 2])>,
    plan: Option<(Plan, PlanStats)>,
}

impl World {
    /// Prepares `scene` with the CLI's default preset: the reference renderer's settings for
    /// scenes lit the paper's way, every optimization for worlds.
    pub(crate) fn new(scene: &Scene) -> Result<World, String> {
        let compiler = WorldCompiler::new(scene).map_err(|e| e.to_string())?;
        let options = match scene.lighting {
            Lighting::Paper(_) => CompileOptions::paper(),
            _ => CompileOptions::default(),
        };
        let start = scene.camera.camera().map_err(|e| e.to_string())?;
        let pivot = pivot_depth(&compiler, &start);
        Ok(World {
            name: scene.name.clone(),
            camera: ViewCamera::from_spec(&scene.camera, pivot)?,
            compiler,
            options,
            planned_for: None,
            plan: None,
        })
    }

    /// The scene's name.
    pub(crate) fn name(&self) -> &str {
        &self.name
    }

    /// The emitter options.
    pub(crate) fn options(&self) -> &CompileOptions {
        &self.options
    }

    /// Switches one optimization; the next [`World::plan_for`] emits a new plan.
    pub(crate) fn set_optimization(&mut self, o: Optimization, on: bool) {
        let mut options = self.options.without(o);
        if on {
            // Keep the `ALL` order, so equal sets are equal option values.
            options.enabled = Optimization::ALL
                .into_iter()
                .filter(|e| *e == o || options.on(*e))
                .collect();
        }
        if options != self.options {
            self.options = options;
            self.planned_for = None;
        }
    }

    /// The plan of the last [`World::plan_for`], with its statistics.
    pub(crate) fn current_plan(&self) -> Option<&(Plan, PlanStats)> {
        self.plan.as_ref()
    }

    /// The plan for `camera` and images of `size` (its aspect bounds the frustum, its
    /// height the LOD's pixel), emitted again only when one of them or the options changed.
    pub(crate) fn plan_for(
        &mut self,
        camera: &Camera3d,
        size: [u32; 2],
    ) -> Result<&(Plan, PlanStats), String> {
        if self.planned_for != Some((*camera, size)) || self.plan.is_none() {
            self.plan = None;
            let mut options = self.options.clone();
            options.aspect = size[0] as f32 / size[1].max(1) as f32;
            options.height = size[1].max(1);
            let plan = self
                .compiler
                .emit(camera, &options)
                .map_err(|e| e.to_string())?;
            let stats = self.stats(&plan, camera, &options);
            self.plan = Some((plan, stats));
            self.planned_for = Some((*camera, size));
        }
        self.plan
            .as_ref()
            .ok_or_else(|| "no plan was emitted".to_string())
    }

    fn stats(&self, plan: &Plan, camera: &Camera3d, options: &CompileOptions) -> PlanStats {
        let visibility = self.compiler.visibility(camera, options);
        PlanStats {
            key: plan.key,
            steps: plan.march.max_steps,
            full_steps: self.compiler.scene().march_settings().max_steps,
            objects: self.compiler.scene().objects.len(),
            visible: visibility.objects.len(),
            far_lod: visibility.objects.iter().filter(|o| o.1 > 0).count(),
            nodes: plan.nodes.len(),
            early_out: plan.early_out,
        }
    }
}

/// How far ahead the orbit pivot sits: the median depth of the objects in front of the
/// scene's camera (the reference scenes look at a point one unit ahead, far short of their
/// objects), or zero to use the camera's look-at point.
fn pivot_depth(compiler: &WorldCompiler, camera: &Camera3d) -> f32 {
    let Ok(plan) = compiler.emit(camera, &CompileOptions::naive()) else {
        return 0.0;
    };
    let mut depths: Vec<f32> = plan
        .nodes
        .iter()
        .filter(|n| n.bound.radius.is_finite())
        .map(|n| (n.bound.centre - camera.position).dot(camera.forward))
        .filter(|d| *d > 0.0)
        .collect();
    depths.sort_by(f32::total_cmp);
    depths.get(depths.len() / 2).copied().unwrap_or(0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn toggling_an_optimization_changes_the_plan() {
        let scene = Scene::builtin("forest").unwrap();
        let mut world = World::new(&scene).unwrap();
        let camera = world.camera.camera().unwrap();
        let key = world.plan_for(&camera, [960, 640]).unwrap().0.key;
        world.set_optimization(Optimization::AabbGuards, false);
        assert!(!world.options().on(Optimization::AabbGuards));
        let off = world.plan_for(&camera, [960, 640]).unwrap().0.key;
        assert_ne!(key, off);
        world.set_optimization(Optimization::AabbGuards, true);
        assert_eq!(world.options(), &CompileOptions::default());
        assert_eq!(world.plan_for(&camera, [960, 640]).unwrap().0.key, key);
    }

    #[test]
    fn culling_shows_in_the_stats() {
        let scene = Scene::builtin("forest").unwrap();
        let mut world = World::new(&scene).unwrap();
        let camera = world.camera.camera().unwrap();
        let (_, stats) = world.plan_for(&camera, [1280, 720]).unwrap();
        assert!(stats.visible > 0 && stats.culled() > 0, "{stats:?}");
        assert!(stats.steps <= stats.full_steps);
    }

    #[test]
    fn the_reference_scenes_orbit_their_objects() {
        let scene = Scene::builtin("scene0").unwrap();
        let world = World::new(&scene).unwrap();
        // scene0's objects stand 12 to 20 units ahead; its look-at point is 1 ahead.
        assert!(world.camera.pivot().z > 10.0, "{:?}", world.camera.pivot());
    }
}
