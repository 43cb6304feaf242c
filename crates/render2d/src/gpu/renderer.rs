//! [`TerrainRenderer`]: pipelines, textures and the three passes.

use crate::camera::Camera;
use crate::emit::{ShaderBudget, TerrainEmitter};
use crate::lattice::Lattice;
use crate::options::{Reconstruction, RenderOptions, Upsample};
use crate::twin::slope_bound;
use craterfield_field::Aabb;
use craterfield_field::Graph;
use craterfield_field::Sdf;
use craterfield_field::Terrain;
use craterfield_gpu::PipelineCache;
use glam::Vec2;

use super::grid_mirror::{GridMirror, UploadStats, buffer_with};
use super::pipelines::{fullscreen_pipeline, layout, storage_entry, texture_entry, uniform_entry};
use super::refine_mode::{RefineDevice, RefineMode};
use super::refine_passes::{RefineBinds, RefineFieldPipelines, RefineLayouts};
use super::shaders;
use super::uniforms::{FrameUniform, MAX_PALETTE, PaletteUniform};
use super::{Culling, RenderError};
use crate::twin::RefineStats;

/// Format of the reduced-scale textures: distance, gradient and material (passes 1-2), or
/// the four pair values (pass 2, mode planes). Filterable and renderable everywhere.
const LOWRES_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

/// Compiled field pipelines kept per visible set of the level (LRU beyond this).
const PIPELINE_CACHE: usize = 16;

/// What [`TerrainRenderer::prepare`] did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PrepareStats {
    /// Uploads of the explosion grid.
    pub upload: UploadStats,
    /// Whether the field pipeline came from the cache.
    pub pipeline_hit: bool,
    /// Cache key of the visible set.
    pub pipeline_key: u64,
    /// Graph nodes kept and culled for this view.
    pub kept_nodes: usize,
    /// Graph nodes culled away.
    pub culled_nodes: usize,
}

struct FieldPipelines {
    sdf: wgpu::RenderPipeline,
    direct: wgpu::RenderPipeline,
    /// Compiled only when the renderer draws mode refine.
    refine: Option<RefineFieldPipelines>,
}

struct Layouts {
    field: wgpu::BindGroupLayout,
    reconstruct: wgpu::BindGroupLayout,
    upsample: wgpu::BindGroupLayout,
    refine: RefineLayouts,
}

struct LowResTargets {
    texels: wgpu::TextureView,
    padded: wgpu::TextureView,
    pairs: wgpu::TextureView,
    dims: (u32, u32),
}

struct BindGroups {
    field: wgpu::BindGroup,
    reconstruct: wgpu::BindGroup,
    upsample: wgpu::BindGroup,
    refine: Option<RefineBinds>,
}

struct Prepared {
    key: u64,
    lattice: Lattice,
    camera: Camera,
}

/// The GPU terrain renderer. See the [module docs](super).
pub struct TerrainRenderer {
    device: wgpu::Device,
    queue: wgpu::Queue,
    target_format: wgpu::TextureFormat,
    options: RenderOptions,
    frame: wgpu::Buffer,
    palette: wgpu::Buffer,
    mirror: GridMirror,
    emitter: Option<TerrainEmitter>,
    field_pipelines: PipelineCache<FieldPipelines>,
    layouts: Layouts,
    divergence: wgpu::RenderPipeline,
    pairs: wgpu::RenderPipeline,
    upsample: [wgpu::RenderPipeline; 4],
    sampler: wgpu::Sampler,
    lowres: Option<LowResTargets>,
    bind: Option<BindGroups>,
    prepared: Option<Prepared>,
    refine: RefineMode,
    culling: Culling,
}

impl Layouts {
    fn new(device: &wgpu::Device) -> Layouts {
        let mut field = vec![uniform_entry(0)];
        field.extend((1..=4).map(storage_entry));
        field.push(uniform_entry(6));
        Layouts {
            field: layout(device, "craterfield field", &field),
            reconstruct: layout(
                device,
                "craterfield reconstruct",
                &[uniform_entry(0), texture_entry(1)],
            ),
            upsample: layout(
                device,
                "craterfield upsample",
                &[
                    uniform_entry(0),
                    texture_entry(1),
                    texture_entry(2),
                    wgpu::BindGroupLayoutEntry {
                        binding: 3,
                        visibility: wgpu::ShaderStages::FRAGMENT,
                        ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                        count: None,
                    },
                    uniform_entry(4),
                ],
            ),
            refine: RefineLayouts::new(device),
        }
    }
}

fn upsample_index(options: &RenderOptions) -> usize {
    match (options.reconstruction, options.upsample) {
        (Reconstruction::Planes, _) => 3,
        (_, Upsample::Bilinear) => 0,
        (_, Upsample::BSpline) => 1,
        (_, Upsample::CatmullRom) => 2,
    }
}

impl TerrainRenderer {
    /// A renderer drawing into textures of `target_format` with `options`, on the game's
    /// `device`. In a browser the validation of its pipelines is still pending when this
    /// returns (a failure comes back from a later `prepare`): await [`Self::new_async`]
    /// there to have it checked first.
    pub fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        target_format: wgpu::TextureFormat,
        options: RenderOptions,
    ) -> Result<TerrainRenderer, RenderError> {
        let features = target_format.guaranteed_format_features(device.features());
        let renderable = features
            .allowed_usages
            .contains(wgpu::TextureUsages::RENDER_ATTACHMENT);
        if !(renderable
            && target_format.has_color_aspect()
            && !target_format.is_depth_stencil_format())
        {
            return Err(RenderError::TargetFormat(target_format));
        }
        let layouts = Layouts::new(device);
        let reconstruct = shaders::reconstruct_module();
        let divergence = fullscreen_pipeline(
            device,
            "craterfield reconstruct",
            &reconstruct,
            "fs_divergence",
            &layouts.reconstruct,
            LOWRES_FORMAT,
        )?;
        let pairs = fullscreen_pipeline(
            device,
            "craterfield reconstruct",
            &reconstruct,
            "fs_pairs",
            &layouts.reconstruct,
            LOWRES_FORMAT,
        )?;
        let upsample_src = shaders::upsample_module();
        let make = |entry: &str| {
            fullscreen_pipeline(
                device,
                "craterfield upsample",
                &upsample_src,
                entry,
                &layouts.upsample,
                target_format,
            )
        };
        let upsample = [
            make("fs_bilinear")?,
            make("fs_bspline")?,
            make("fs_catmull_rom")?,
            make("fs_planes")?,
        ];
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("craterfield linear clamp"),
            address_mode_u: wgpu::AddressMode::ClampToEdge,
            address_mode_v: wgpu::AddressMode::ClampToEdge,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        let frame = buffer_with(
            device,
            "craterfield frame",
            bytemuck::bytes_of(&FrameUniform::default()),
            wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        );
        let palette = buffer_with(
            device,
            "craterfield palette",
            bytemuck::bytes_of(&PaletteUniform::new(&[])),
            wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        );
        Ok(TerrainRenderer {
            device: device.clone(),
            queue: queue.clone(),
            target_format,
            options,
            frame,
            palette,
            mirror: GridMirror::new(device),
            emitter: None,
            field_pipelines: PipelineCache::new(PIPELINE_CACHE),
            layouts,
            divergence,
            pairs,
            upsample,
            sampler,
            lowres: None,
            bind: None,
            prepared: None,
            refine: RefineMode::new(device),
            culling: Culling::default(),
        })
    }

    /// [`Self::new`], returning once the device has validated the renderer's pipelines:
    /// the constructor for a browser, where that answer comes from the page's event loop.
    /// (Pipelines compiled later, for a level's field or a mode, are checked at the
    /// `prepare` after the answer comes.)
    pub async fn new_async(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        target_format: wgpu::TextureFormat,
        options: RenderOptions,
    ) -> Result<TerrainRenderer, RenderError> {
        let renderer = TerrainRenderer::new(device, queue, target_format, options)?;
        craterfield_gpu::settle().await?;
        Ok(renderer)
    }

    /// The options in use.
    pub fn options(&self) -> &RenderOptions {
        &self.options
    }

    /// Changes scale, mode, filter or shading; takes effect at the next `prepare`.
    pub fn set_options(&mut self, options: RenderOptions) {
        if options.scale != self.options.scale {
            self.lowres = None;
        }
        self.bind = None;
        self.options = options;
        self.prepared = None;
    }

    /// Which part of the level the field pipeline covers (by default only what reaches the
    /// view); takes effect at the next `prepare`.
    pub fn set_culling(&mut self, culling: Culling) {
        self.culling = culling;
    }

    /// The culling in use.
    pub fn culling(&self) -> Culling {
        self.culling
    }

    /// Field pipeline cache counters: `(hits, misses)`.
    pub fn cache_counters(&self) -> (u64, u64) {
        (self.field_pipelines.hits(), self.field_pipelines.misses())
    }

    /// Uploads what changed in `terrain`, the camera and the palette, and selects (compiling
    /// on a miss) the field pipeline for the part of the level in view.
    pub fn prepare(
        &mut self,
        terrain: &Terrain<Graph>,
        palette: &[[u8; 3]],
        camera: &Camera,
    ) -> Result<PrepareStats, RenderError> {
        // In a browser: a pipeline made earlier that the device has since refused.
        craterfield_gpu::pending_errors()?;
        let lattice = Lattice::new(camera, self.options.scale)?;
        let refine = self.options.reconstruction == Reconstruction::Refine;
        if refine {
            RefineMode::check_limits(&self.device)?;
        }
        // The level graph's content fingerprint: whether the emitter and the cell proofs
        // are current.
        let fingerprint = crate::emit::graph_fingerprint(terrain.base());
        let mut stats = PrepareStats {
            upload: self.mirror.sync(&self.device, &self.queue, terrain)?,
            ..PrepareStats::default()
        };
        if stats.upload.reallocated {
            self.bind = None;
        }
        self.ensure_lowres(camera, &lattice)?;
        if refine {
            let gpu = RefineDevice {
                device: &self.device,
                queue: &self.queue,
                layouts: &self.layouts.refine,
                format: self.target_format,
            };
            if self.refine.ensure(gpu, terrain, fingerprint, camera)? {
                self.bind = None;
            }
        }
        self.write_palette(palette);
        let key = self.select_pipeline(terrain, fingerprint, &lattice, &mut stats)?;
        let dims = self.lowres.as_ref().map_or((1, 1), |t| t.dims);
        let uniform = FrameUniform {
            palette_len: palette.len().min(MAX_PALETTE) as u32,
            slope: slope_bound(terrain.lipschitz()),
            texture_dims: [dims.0, dims.1],
            ..FrameUniform::new(
                camera,
                &lattice,
                &self.options.shade,
                self.target_format.is_srgb(),
            )
            .with_grid(&GridMirror::frame(terrain))
        };
        self.queue
            .write_buffer(&self.frame, 0, bytemuck::bytes_of(&uniform));
        if self.bind.is_none() {
            self.bind = Some(self.bind_groups()?);
        }
        self.prepared = Some(Prepared {
            key,
            lattice,
            camera: *camera,
        });
        Ok(stats)
    }

    fn select_pipeline(
        &mut self,
        terrain: &Terrain<Graph>,
        fingerprint: u64,
        lattice: &Lattice,
        stats: &mut PrepareStats,
    ) -> Result<u64, RenderError> {
        let current = self
            .emitter
            .take()
            .filter(|e| e.fingerprint() == fingerprint);
        let emitter: &TerrainEmitter = self
            .emitter
            .insert(current.unwrap_or_else(|| TerrainEmitter::new(terrain.base())));
        let plan = emitter.plan(
            self.culling.rect(lattice_rect(lattice)),
            terrain.options().band,
        );
        stats.pipeline_key = plan.key;
        stats.kept_nodes = plan.kept;
        stats.culled_nodes = plan.culled;
        let (device, layouts, format) = (&self.device, &self.layouts, self.target_format);
        let refine = self.options.reconstruction == Reconstruction::Refine;
        let lacks_refine = self
            .field_pipelines
            .peek(plan.key)
            .is_some_and(|p| refine && p.refine.is_none());
        if lacks_refine {
            // Compiled for another mode: compile again with the refine passes.
            self.field_pipelines.clear();
        }
        let (_, hit) = self.field_pipelines.get_or_try_insert_with(plan.key, || {
            let base = emitter.emit_within(&plan, &ShaderBudget::default())?;
            let sdf = fullscreen_pipeline(
                device,
                "craterfield sdf pass",
                &shaders::sdf_module(&base),
                "fs_sdf",
                &layouts.field,
                LOWRES_FORMAT,
            )?;
            let direct = fullscreen_pipeline(
                device,
                "craterfield direct",
                &shaders::direct_module(&base),
                "fs_direct",
                &layouts.field,
                format,
            )?;
            let refine = if refine {
                Some(RefineFieldPipelines::new(
                    device,
                    &layouts.field,
                    &layouts.refine,
                    &base,
                )?)
            } else {
                None
            };
            Ok::<_, RenderError>(FieldPipelines {
                sdf,
                direct,
                refine,
            })
        })?;
        stats.pipeline_hit = hit;
        Ok(plan.key)
    }

    /// What mode refine did in the last frame submitted (waits for the device): blocks
    /// proven and evaluated, pixels evaluated exactly, and field evaluations (texels,
    /// corner samples, exact pixels). Native targets only (see [`Self::refine_stats_async`]).
    #[cfg(not(target_family = "wasm"))]
    pub fn refine_stats(&self) -> Result<RefineStats, RenderError> {
        pollster::block_on(self.refine_stats_async())
    }

    /// [`Self::refine_stats`] for every target, awaiting the readback.
    pub async fn refine_stats_async(&self) -> Result<RefineStats, RenderError> {
        let (prepared, _, _) = self.ready()?;
        if self.options.reconstruction != Reconstruction::Refine {
            return Err(RenderError::NotPrepared);
        }
        let (l, c) = (&prepared.lattice, &prepared.camera);
        self.refine.stats(&self.device, &self.queue, l, c).await
    }

    fn write_palette(&mut self, palette: &[[u8; 3]]) {
        let uniform = PaletteUniform::new(palette);
        self.queue
            .write_buffer(&self.palette, 0, bytemuck::bytes_of(&uniform));
    }

    /// Allocates the reduced-scale textures for the largest lattice this image size needs.
    fn ensure_lowres(&mut self, camera: &Camera, lattice: &Lattice) -> Result<(), RenderError> {
        let (w, h) = Lattice::max_dims(camera.width, camera.height, self.options.scale);
        let (w, h) = (w.max(lattice.cols), h.max(lattice.rows));
        let fits = self
            .lowres
            .as_ref()
            .is_some_and(|t| t.dims.0 >= w && t.dims.1 >= h);
        if fits {
            return Ok(());
        }
        craterfield_gpu::check_texture(
            &self.device,
            "reduced-scale textures (texels per side)",
            w,
            h,
        )?;
        let make = |label: &str| {
            self.device
                .create_texture(&wgpu::TextureDescriptor {
                    label: Some(label),
                    size: wgpu::Extent3d {
                        width: w,
                        height: h,
                        depth_or_array_layers: 1,
                    },
                    mip_level_count: 1,
                    sample_count: 1,
                    dimension: wgpu::TextureDimension::D2,
                    format: LOWRES_FORMAT,
                    usage: wgpu::TextureUsages::RENDER_ATTACHMENT
                        | wgpu::TextureUsages::TEXTURE_BINDING,
                    view_formats: &[],
                })
                .create_view(&wgpu::TextureViewDescriptor::default())
        };
        self.lowres = Some(LowResTargets {
            texels: make("craterfield texels"),
            padded: make("craterfield padded texels"),
            pairs: make("craterfield pairs"),
            dims: (w, h),
        });
        self.bind = None;
        Ok(())
    }

    fn bind_groups(&self) -> Result<BindGroups, RenderError> {
        let lowres = self.lowres.as_ref().ok_or(RenderError::NotPrepared)?;
        let buffers = self.mirror.buffers();
        let mut field: Vec<wgpu::BindGroupEntry> = vec![wgpu::BindGroupEntry {
            binding: 0,
            resource: self.frame.as_entire_binding(),
        }];
        field.extend(
            buffers
                .iter()
                .enumerate()
                .map(|(i, b)| wgpu::BindGroupEntry {
                    binding: i as u32 + 1,
                    resource: b.as_entire_binding(),
                }),
        );
        field.push(wgpu::BindGroupEntry {
            binding: 6,
            resource: self.palette.as_entire_binding(),
        });
        let field = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("craterfield field"),
            layout: &self.layouts.field,
            entries: &field,
        });
        let reconstruct = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("craterfield reconstruct"),
            layout: &self.layouts.reconstruct,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: self.frame.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(&lowres.texels),
                },
            ],
        });
        let source = match self.options.reconstruction {
            Reconstruction::Divergence => &lowres.padded,
            _ => &lowres.texels,
        };
        let upsample = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("craterfield upsample"),
            layout: &self.layouts.upsample,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: self.frame.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(source),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: wgpu::BindingResource::TextureView(&lowres.pairs),
                },
                wgpu::BindGroupEntry {
                    binding: 3,
                    resource: wgpu::BindingResource::Sampler(&self.sampler),
                },
                wgpu::BindGroupEntry {
                    binding: 4,
                    resource: self.palette.as_entire_binding(),
                },
            ],
        });
        let refine = if self.options.reconstruction == Reconstruction::Refine {
            let refine = &self.layouts.refine;
            let (frame, palette) = (&self.frame, &self.palette);
            self.refine
                .binds(&self.device, refine, frame, palette, &lowres.texels)
        } else {
            None
        };
        Ok(BindGroups {
            field,
            reconstruct,
            upsample,
            refine,
        })
    }

    /// Records passes 1 and 2 (into the renderer's own textures). Call before [`Self::draw`]
    /// when drawing into a render pass of your own.
    pub fn encode_prepasses(&self, encoder: &mut wgpu::CommandEncoder) -> Result<(), RenderError> {
        self.encode_prepasses_timed(encoder, None)
    }

    fn encode_prepasses_timed(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        pass1_writes: Option<wgpu::RenderPassTimestampWrites<'_>>,
    ) -> Result<(), RenderError> {
        let (prepared, bind, lowres) = self.ready()?;
        let pipelines = self
            .field_pipelines
            .peek(prepared.key)
            .ok_or(RenderError::NotPrepared)?;
        let l = &prepared.lattice;
        lowres_pass(
            encoder,
            "craterfield sdf pass",
            &lowres.texels,
            &pipelines.sdf,
            &bind.field,
            l,
            pass1_writes,
        );
        if self.options.reconstruction == Reconstruction::Refine {
            let own = pipelines.refine.as_ref();
            return self
                .refine
                .encode(encoder, own, bind.refine.as_ref(), &bind.field);
        }
        let second = match self.options.reconstruction {
            Reconstruction::Off | Reconstruction::Refine => None,
            Reconstruction::Divergence => Some((&self.divergence, &lowres.padded)),
            Reconstruction::Planes => Some((&self.pairs, &lowres.pairs)),
        };
        if let Some((pipeline, target)) = second {
            lowres_pass(
                encoder,
                "craterfield reconstruct",
                target,
                pipeline,
                &bind.reconstruct,
                l,
                None,
            );
        }
        Ok(())
    }

    /// Records pass 3 into the caller's render pass, whose target must be the camera's size
    /// and this renderer's format.
    pub fn draw(&self, pass: &mut wgpu::RenderPass<'_>) -> Result<(), RenderError> {
        let (prepared, bind, _) = self.ready()?;
        let c = &prepared.camera;
        pass.set_viewport(0.0, 0.0, c.width as f32, c.height as f32, 0.0, 1.0);
        if self.options.reconstruction == Reconstruction::Refine {
            return self.refine.draw(pass, bind.refine.as_ref());
        }
        pass.set_pipeline(&self.upsample[upsample_index(&self.options)]);
        pass.set_bind_group(0, &bind.upsample, &[]);
        pass.draw(0..3, 0..1);
        Ok(())
    }

    /// Records all three passes, drawing the frame into `target` (the camera's size).
    pub fn render(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        target: &wgpu::TextureView,
    ) -> Result<(), RenderError> {
        self.render_timed(encoder, target, None)
    }

    /// [`Self::render`] writing a timestamp before pass 1 (`index`) and after pass 3
    /// (`index + 1`) into `query_set`.
    pub fn render_timed(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        target: &wgpu::TextureView,
        timestamps: Option<(&wgpu::QuerySet, u32)>,
    ) -> Result<(), RenderError> {
        let start = timestamps.map(|(set, i)| wgpu::RenderPassTimestampWrites {
            query_set: set,
            beginning_of_pass_write_index: Some(i),
            end_of_pass_write_index: None,
        });
        self.encode_prepasses_timed(encoder, start)?;
        let end = timestamps.map(|(set, i)| wgpu::RenderPassTimestampWrites {
            query_set: set,
            beginning_of_pass_write_index: None,
            end_of_pass_write_index: Some(i + 1),
        });
        let mut pass = begin_pass(encoder, "craterfield upsample", target, end);
        self.draw(&mut pass)
    }

    /// [`Self::render`] writing four timestamps into `query_set` from `index`: the
    /// beginning and end of pass 1 (`index`, `index + 1`) and of pass 3 (`index + 2`,
    /// `index + 3`). Pass 2 (the reconstruction, or mode refine's classification and exact
    /// passes) lies between the second and the third. Read them with
    /// [`Timestamps::read_marks_ms`](craterfield_gpu::Timestamps::read_marks_ms) (two pairs).
    pub fn render_timed_passes(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        target: &wgpu::TextureView,
        query_set: &wgpu::QuerySet,
        index: u32,
    ) -> Result<(), RenderError> {
        let writes = |at: u32| wgpu::RenderPassTimestampWrites {
            query_set,
            beginning_of_pass_write_index: Some(at),
            end_of_pass_write_index: Some(at + 1),
        };
        self.encode_prepasses_timed(encoder, Some(writes(index)))?;
        let mut pass = begin_pass(
            encoder,
            "craterfield upsample",
            target,
            Some(writes(index + 2)),
        );
        self.draw(&mut pass)
    }

    /// Full-resolution direct evaluation of the same field into `target` (the baseline the
    /// reduced-scale pipeline is measured against), with optional timestamps as in
    /// [`Self::render_timed`].
    pub fn render_direct(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        target: &wgpu::TextureView,
        timestamps: Option<(&wgpu::QuerySet, u32)>,
    ) -> Result<(), RenderError> {
        let (prepared, bind, _) = self.ready()?;
        let pipelines = self
            .field_pipelines
            .peek(prepared.key)
            .ok_or(RenderError::NotPrepared)?;
        let writes = timestamps.map(|(set, i)| wgpu::RenderPassTimestampWrites {
            query_set: set,
            beginning_of_pass_write_index: Some(i),
            end_of_pass_write_index: Some(i + 1),
        });
        let mut pass = begin_pass(encoder, "craterfield direct", target, writes);
        let c = &prepared.camera;
        pass.set_viewport(0.0, 0.0, c.width as f32, c.height as f32, 0.0, 1.0);
        pass.set_pipeline(&pipelines.direct);
        pass.set_bind_group(0, &bind.field, &[]);
        pass.draw(0..3, 0..1);
        Ok(())
    }

    fn ready(&self) -> Result<(&Prepared, &BindGroups, &LowResTargets), RenderError> {
        match (&self.prepared, &self.bind, &self.lowres) {
            (Some(p), Some(b), Some(l)) => Ok((p, b, l)),
            _ => Err(RenderError::NotPrepared),
        }
    }

    /// The device this renderer draws with.
    pub fn device(&self) -> &wgpu::Device {
        &self.device
    }

    /// The queue this renderer uploads with.
    pub fn queue(&self) -> &wgpu::Queue {
        &self.queue
    }

    /// The render target format.
    pub fn target_format(&self) -> wgpu::TextureFormat {
        self.target_format
    }
}

/// The world rectangle the lattice's texels cover.
fn lattice_rect(l: &Lattice) -> Aabb {
    let a = l.texel_center(0, 0);
    let b = l.texel_center(l.cols.saturating_sub(1), l.rows.saturating_sub(1));
    Aabb::new(Vec2::new(a.x, b.y), Vec2::new(b.x, a.y))
}

fn begin_pass<'e>(
    encoder: &'e mut wgpu::CommandEncoder,
    label: &str,
    target: &wgpu::TextureView,
    timestamps: Option<wgpu::RenderPassTimestampWrites<'e>>,
) -> wgpu::RenderPass<'e> {
    encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some(label),
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view: target,
            depth_slice: None,
            resolve_target: None,
            ops: wgpu::Operations {
                load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                store: wgpu::StoreOp::Store,
            },
        })],
        depth_stencil_attachment: None,
        timestamp_writes: timestamps,
        occlusion_query_set: None,
        multiview_mask: None,
    })
}

fn lowres_pass(
    encoder: &mut wgpu::CommandEncoder,
    label: &str,
    target: &wgpu::TextureView,
    pipeline: &wgpu::RenderPipeline,
    bind: &wgpu::BindGroup,
    lattice: &Lattice,
    writes: Option<wgpu::RenderPassTimestampWrites<'_>>,
) {
    let mut pass = begin_pass(encoder, label, target, writes);
    pass.set_viewport(0.0, 0.0, lattice.cols as f32, lattice.rows as f32, 0.0, 1.0);
    pass.set_pipeline(pipeline);
    pass.set_bind_group(0, bind, &[]);
    pass.draw(0..3, 0..1);
}
