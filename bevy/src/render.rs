//! The terrain in Bevy's 2D cameras, drawn by the library's own `TerrainRenderer` (refine by
//! default) on Bevy's `RenderDevice` and `RenderQueue`: each camera with a [`TerrainView`]
//! gets a renderer in the render world; at extraction the camera's transform and projection
//! become the library's `Camera` and the terrain's changes since the last frame are uploaded
//! (`prepare`); in the camera's `Core2d` schedule, before the main pass, the renderer's
//! passes are recorded and its last pass draws into the camera's target, which Bevy's
//! sprites and meshes are then drawn over.

use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use bevy::core_pipeline::schedule::{Core2d, Core2dSystems};
use bevy::platform::collections::HashMap;
use bevy::prelude::*;
use bevy::render::camera::{CameraMainPassTextureFormats, extract_cameras};
use bevy::render::renderer::{RenderContext, RenderDevice, RenderQueue, ViewQuery};
use bevy::render::sync_world::RenderEntity;
use bevy::render::view::ViewTarget;
use bevy::render::{Extract, ExtractSchedule, RenderApp};
use craterfield::render2d::gpu::{Culling, TerrainRenderer};
use craterfield::render2d::{Camera as TerrainCamera, Reconstruction, RenderOptions};

use crate::world::Craterfield;

/// Draws the match's terrain into this 2D camera's target, under everything else the camera
/// draws. The terrain's units are Bevy's world units (y up). Cameras with a `TerrainView`
/// render without MSAA (the terrain's edges are antialiased by its own shading; the
/// renderer draws single-sampled).
#[derive(Component, Debug, Clone, PartialEq)]
pub struct TerrainView {
    /// Scale, reconstruction mode, upsampling filter and shading. Refine by default: the
    /// picture of the exact render at the cost of the reduced-scale pipeline.
    pub options: RenderOptions,
    /// Which part of the level the compiled field pipeline covers. By default the whole
    /// level (`Culling::Off`): one compile, however the camera moves. `Culling::View` culls
    /// to the view, a pipeline per set of nodes in view: a camera that scrolls pays a
    /// compile whenever that set changes. A level too large for one shader falls back to
    /// `View` (with a warning).
    pub culling: Culling,
}

impl Default for TerrainView {
    fn default() -> TerrainView {
        TerrainView {
            options: RenderOptions {
                reconstruction: Reconstruction::Refine,
                ..RenderOptions::default()
            },
            culling: Culling::Off,
        }
    }
}

/// CPU time the plugin spent on the terrain per frame, in both worlds' hands (the render
/// world writes, the game reads): `prepare` (uploads and pipeline selection, during
/// extraction) and recording the passes.
#[derive(Resource, Clone, Default)]
pub struct TerrainFrameCosts(Arc<Mutex<FrameCostLog>>);

/// The per-frame costs recorded so far (bounded: the last [`FrameCostLog::CAPACITY`] frames).
#[derive(Debug, Clone, Default)]
pub struct FrameCostLog {
    /// `prepare` per frame and camera.
    pub prepare: Vec<Duration>,
    /// Recording the passes, per frame and camera.
    pub record: Vec<Duration>,
    /// Frames drawn.
    pub frames: u64,
    /// The error of the last frame that could not be prepared, until one is prepared again.
    pub last_error: Option<String>,
    /// The last error recording the passes reported, if any.
    pub last_draw_error: Option<String>,
}

impl FrameCostLog {
    /// Frames kept.
    pub const CAPACITY: usize = 4096;

    fn push(list: &mut Vec<Duration>, d: Duration) {
        if list.len() == Self::CAPACITY {
            list.remove(0);
        }
        list.push(d);
    }
}

impl TerrainFrameCosts {
    /// A copy of the log.
    pub fn snapshot(&self) -> FrameCostLog {
        self.0.lock().map(|g| g.clone()).unwrap_or_default()
    }

    fn with(&self, f: impl FnOnce(&mut FrameCostLog)) {
        if let Ok(mut g) = self.0.lock() {
            f(&mut g);
        }
    }
}

/// One renderer per camera, keyed by the camera's render-world entity.
#[derive(Resource, Default)]
struct TerrainRenderers(HashMap<Entity, ViewRenderer>);

struct ViewRenderer {
    renderer: TerrainRenderer,
    format: wgpu::TextureFormat,
    /// Whether this frame's `prepare` succeeded (the draw is skipped otherwise).
    ready: bool,
    /// The last frame this camera was extracted (stale cameras are dropped).
    frame: u64,
    /// Whether the whole level did not fit one pipeline, so the view is culled instead.
    culling_fallback: bool,
}

#[derive(Resource, Default)]
struct ExtractFrame(u64);

/// Adds the terrain renderer to Bevy's render world (part of `CraterfieldPlugin` when the
/// `render` feature is on and the app renders).
pub(crate) fn build(app: &mut App) {
    let costs = TerrainFrameCosts::default();
    app.insert_resource(costs.clone())
        .add_observer(no_msaa_on_terrain_views);
    let Some(render_app) = app.get_sub_app_mut(RenderApp) else {
        return;
    };
    render_app
        .insert_resource(costs)
        .init_resource::<TerrainRenderers>()
        .init_resource::<ExtractFrame>()
        .add_systems(ExtractSchedule, prepare_terrain.after(extract_cameras))
        .add_systems(Core2d, draw_terrain.in_set(Core2dSystems::Prepass));
}

fn no_msaa_on_terrain_views(add: On<Add, TerrainView>, mut commands: Commands) {
    commands.entity(add.entity).insert(Msaa::Off);
}

/// The library's camera for a Bevy camera: orthographic, unrotated, whole target.
pub fn terrain_camera(
    camera: &Camera,
    transform: &GlobalTransform,
) -> Result<TerrainCamera, String> {
    if camera.viewport.is_some() {
        return Err(
            "cameras with a viewport are not supported (the terrain fills the target)".into(),
        );
    }
    let size = camera
        .physical_viewport_size()
        .ok_or("the camera's target size is not known yet")?;
    let clip_from_view = camera.clip_from_view();
    if clip_from_view.w_axis.w != 1.0 {
        return Err("the camera's projection is not orthographic".into());
    }
    let world_from_clip = transform.to_matrix() * clip_from_view.inverse();
    let center = world_from_clip.project_point3(Vec3::ZERO).truncate();
    let right = world_from_clip.project_point3(Vec3::X).truncate() - center;
    if right.y.abs() > right.x.abs() * 1e-4 {
        return Err("rotated cameras are not supported".into());
    }
    let terrain_camera = TerrainCamera {
        center,
        units_per_pixel: 2.0 * right.x / size.x as f32,
        width: size.x,
        height: size.y,
    };
    terrain_camera.validate().map_err(|e| e.to_string())?;
    Ok(terrain_camera)
}

#[allow(clippy::too_many_arguments)]
fn prepare_terrain(
    craterfield: Extract<Option<Res<Craterfield>>>,
    views: Extract<Query<(&RenderEntity, &Camera, &GlobalTransform, &TerrainView)>>,
    formats: Res<CameraMainPassTextureFormats>,
    device: Res<RenderDevice>,
    queue: Res<RenderQueue>,
    costs: Res<TerrainFrameCosts>,
    mut frame: ResMut<ExtractFrame>,
    mut renderers: ResMut<TerrainRenderers>,
) {
    frame.0 += 1;
    let now = frame.0;
    for view in renderers.0.values_mut() {
        view.ready = false;
    }
    let Some(cf) = craterfield.as_deref() else {
        return;
    };
    for (render_entity, camera, transform, terrain_view) in &views {
        // Inactive, or its target's size not known yet (the first frames of a window).
        if !camera.is_active || camera.physical_viewport_size().is_none() {
            continue;
        }
        let entity = render_entity.id();
        let Some(&format) = formats.get(&entity) else {
            continue;
        };
        let started = Instant::now();
        let result = supported_format(format)
            .and_then(|()| terrain_camera(camera, transform))
            .and_then(|c| {
                let view = view_renderer(
                    &mut renderers.0,
                    entity,
                    format,
                    terrain_view,
                    &device,
                    &queue,
                )?;
                view.frame = now;
                prepare_view(view, cf, &c)?;
                view.ready = true;
                Ok(())
            });
        let took = started.elapsed();
        costs.with(|log| match result {
            Ok(()) => {
                FrameCostLog::push(&mut log.prepare, took);
                log.last_error = None;
            }
            Err(e) => {
                if log.last_error.as_deref() != Some(e.as_str()) {
                    warn!("craterfield: the terrain is not drawn in this camera: {e}");
                }
                log.last_error = Some(e);
            }
        });
    }
    renderers.0.retain(|_, v| v.frame + 2 >= now);
}

/// Uploads and selects the pipeline for one camera; a level too large for one pipeline
/// falls back from `Culling::Off` to culling to the view, once.
fn prepare_view(
    view: &mut ViewRenderer,
    cf: &Craterfield,
    camera: &TerrainCamera,
) -> Result<(), String> {
    let (terrain, palette) = (cf.world().terrain(), cf.palette());
    match view.renderer.prepare(terrain, palette, camera) {
        Ok(_) => Ok(()),
        Err(e) if view.renderer.culling() == Culling::Off => {
            warn!(
                "craterfield: the whole level does not fit one pipeline ({e}): culling to the view"
            );
            view.renderer.set_culling(Culling::View);
            view.culling_fallback = true;
            view.renderer
                .prepare(terrain, palette, camera)
                .map(|_| ())
                .map_err(|e| e.to_string())
        }
        Err(e) => Err(e.to_string()),
    }
}

/// The renderer writes sRGB-encoded colours, or linear ones into an sRGB format that encodes
/// them; a floating-point (HDR) target would want linear values it cannot be told of.
fn supported_format(format: wgpu::TextureFormat) -> Result<(), String> {
    use wgpu::TextureFormat::{Rgba16Float, Rgba32Float};
    if matches!(format, Rgba16Float | Rgba32Float) {
        Err(format!(
            "HDR cameras ({format:?}) are not supported: the terrain is drawn in sRGB"
        ))
    } else {
        Ok(())
    }
}

/// The camera's renderer, made (or remade, for another format) on demand, its options
/// following the component.
fn view_renderer<'a>(
    renderers: &'a mut HashMap<Entity, ViewRenderer>,
    entity: Entity,
    format: wgpu::TextureFormat,
    view: &TerrainView,
    device: &RenderDevice,
    queue: &RenderQueue,
) -> Result<&'a mut ViewRenderer, String> {
    if renderers.get(&entity).is_none_or(|r| r.format != format) {
        let renderer =
            TerrainRenderer::new(device.wgpu_device(), queue, format, view.options.clone())
                .map_err(|e| e.to_string())?;
        renderers.insert(
            entity,
            ViewRenderer {
                renderer,
                format,
                ready: false,
                frame: 0,
                culling_fallback: false,
            },
        );
    }
    let r = renderers.get_mut(&entity).ok_or("no renderer")?;
    if r.renderer.options() != &view.options {
        r.renderer.set_options(view.options.clone());
    }
    if r.renderer.culling() != view.culling && !r.culling_fallback {
        r.renderer.set_culling(view.culling);
    }
    Ok(r)
}

/// Records the renderer's passes, then its last pass into the camera's main texture: the
/// first draw of the frame into it, so it clears it to the camera's clear colour first.
fn draw_terrain(
    view: ViewQuery<&ViewTarget>,
    renderers: Res<TerrainRenderers>,
    costs: Res<TerrainFrameCosts>,
    mut ctx: RenderContext,
) {
    let Some(r) = renderers.0.get(&view.entity()).filter(|r| r.ready) else {
        return;
    };
    let target = view.into_inner();
    let started = Instant::now();
    let encoder = ctx.command_encoder();
    let mut result = r.renderer.encode_prepasses(encoder);
    if result.is_ok() {
        let attachments = [Some(target.get_color_attachment())];
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("craterfield terrain"),
            color_attachments: &attachments,
            depth_stencil_attachment: None,
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        result = r.renderer.draw(&mut pass);
    }
    let took = started.elapsed();
    costs.with(|log| match result {
        Ok(()) => {
            FrameCostLog::push(&mut log.record, took);
            log.frames += 1;
        }
        Err(e) => {
            let e = e.to_string();
            if log.last_draw_error.as_deref() != Some(e.as_str()) {
                warn!("craterfield: drawing the terrain failed: {e}");
            }
            log.last_draw_error = Some(e);
        }
    });
}
