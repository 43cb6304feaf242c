//! [`Marcher`]: the compute pipelines of emitted plans, the camera uniform, the readback
//! target, and the pass that marches every pixel.

use std::time::Duration;
#[cfg(not(target_family = "wasm"))]
use std::time::Instant;

use crate::codegen3d::{MARCH3D_BUDGET, march_inlined_statements, march_wgsl};
use crate::plan3d::{Camera3d, Plan};
use craterfield_gpu::DEFAULT_WAIT;
use craterfield_gpu::PipelineCache;
use craterfield_gpu::Timestamps;
#[cfg(not(target_family = "wasm"))]
use craterfield_gpu::wait_for;
use craterfield_gpu::{Offscreen, READBACK_FORMAT};
use craterfield_wgsl::{EmitError, ShaderBudget};

use super::MarchGpuError;
use super::uniforms::MarchFrame;

/// Compiled plans kept at once (least recently used evicted beyond).
const PIPELINE_CACHE: usize = 16;

/// The shader's workgroup side (`@workgroup_size(8, 8)` in `shaders/march3d.wgsl`).
const WORKGROUP: u32 = 8;

/// The only target format: `rgba8unorm` rounds to nearest when storing, which is the CPU
/// tracer's `floor(clamp(c, 0, 1) * 255 + 0.5)`.
pub(super) const TARGET_FORMAT: wgpu::TextureFormat = READBACK_FORMAT;

/// The GPU raymarcher on the caller's device. See the [module docs](super).
pub struct Marcher {
    device: wgpu::Device,
    queue: wgpu::Queue,
    bind_layout: wgpu::BindGroupLayout,
    pipeline_layout: wgpu::PipelineLayout,
    frame: wgpu::Buffer,
    pipelines: PipelineCache<wgpu::ComputePipeline>,
    readback: Option<Offscreen>,
    timestamps: Option<Timestamps>,
    budget: ShaderBudget,
    wait_limit: Duration,
}

impl Marcher {
    /// A raymarcher on `device` and `queue` (the caller's; the marcher keeps clones).
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue) -> Result<Marcher, MarchGpuError> {
        let bind_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("craterfield march3d"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::COMPUTE,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: false,
                        min_binding_size: wgpu::BufferSize::new(
                            std::mem::size_of::<MarchFrame>() as u64
                        ),
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 1,
                    visibility: wgpu::ShaderStages::COMPUTE,
                    ty: wgpu::BindingType::StorageTexture {
                        access: wgpu::StorageTextureAccess::WriteOnly,
                        format: TARGET_FORMAT,
                        view_dimension: wgpu::TextureViewDimension::D2,
                    },
                    count: None,
                },
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("craterfield march3d"),
            bind_group_layouts: &[Some(&bind_layout)],
            immediate_size: 0,
        });
        let frame = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("craterfield march3d frame"),
            size: std::mem::size_of::<MarchFrame>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        Ok(Marcher {
            device: device.clone(),
            queue: queue.clone(),
            bind_layout,
            pipeline_layout,
            frame,
            pipelines: PipelineCache::new(PIPELINE_CACHE),
            readback: None,
            timestamps: Timestamps::new(device, queue, 1),
            budget: MARCH3D_BUDGET,
            wait_limit: DEFAULT_WAIT,
        })
    }

    /// The largest shader handed to the driver (default [`MARCH3D_BUDGET`]): a plan past it
    /// is [`MarchGpuError::TooLarge`] before any pipeline is created.
    pub fn shader_budget(&self) -> ShaderBudget {
        self.budget
    }

    /// Replaces the [`shader_budget`](Self::shader_budget). Plans already compiled stay
    /// cached.
    pub fn set_shader_budget(&mut self, budget: ShaderBudget) {
        self.budget = budget;
    }

    /// How long a render waits for the GPU before giving up with
    /// [`craterfield_gpu::GpuError::Timeout`] (default [`DEFAULT_WAIT`]).
    pub fn wait_limit(&self) -> Duration {
        self.wait_limit
    }

    /// Replaces the [`wait_limit`](Self::wait_limit).
    pub fn set_wait_limit(&mut self, limit: Duration) {
        self.wait_limit = limit;
    }

    /// Pipeline cache counters: `(hits, misses)`.
    pub fn cache_counters(&self) -> (u64, u64) {
        (self.pipelines.hits(), self.pipelines.misses())
    }

    /// Whether [`render_timed`](Self::render_timed) reports GPU time from timestamp queries
    /// (`true`) or wall-clock time around the submitted pass (`false`).
    pub fn gpu_timestamps(&self) -> bool {
        self.timestamps.is_some()
    }

    /// Records the pass that renders `plan` seen by `camera` into `target` (a view of a 2D
    /// `Rgba8Unorm` texture with `STORAGE_BINDING` usage, the whole image) on the caller's
    /// encoder. The camera uniform is written through the queue, so one marcher renders one
    /// frame per submission.
    pub fn encode(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        plan: &Plan,
        camera: &Camera3d,
        target: &wgpu::TextureView,
    ) -> Result<(), MarchGpuError> {
        self.encode_timed(encoder, plan, camera, target, None)
    }

    /// [`encode`](Self::encode) writing timestamps at the beginning (`index`) and end
    /// (`index + 1`) of the pass into `query_set`, so the caller can read the pass's GPU
    /// time (see [`Timestamps`]).
    pub fn encode_timed(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        plan: &Plan,
        camera: &Camera3d,
        target: &wgpu::TextureView,
        timestamps: Option<(&wgpu::QuerySet, u32)>,
    ) -> Result<(), MarchGpuError> {
        let texture = target.texture();
        if texture.format() != TARGET_FORMAT
            || !texture
                .usage()
                .contains(wgpu::TextureUsages::STORAGE_BINDING)
        {
            return Err(MarchGpuError::Target {
                format: texture.format(),
                usage: texture.usage(),
            });
        }
        self.prepare(plan, camera, texture.width(), texture.height())?;
        self.encode_pass(
            encoder,
            plan.key,
            target,
            texture.width(),
            texture.height(),
            timestamps,
        );
        Ok(())
    }

    /// [`Self::new`] once the device has validated what it made: the constructor for a
    /// browser, where that answer comes from the page's event loop.
    pub async fn new_async(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
    ) -> Result<Marcher, MarchGpuError> {
        let marcher = Marcher::new(device, queue)?;
        craterfield_gpu::settle().await?;
        Ok(marcher)
    }

    /// [`Self::render_to_rgba`] for every target: awaits the validation of the plan's
    /// pipeline (compiled on a miss) and the readback instead of blocking.
    pub async fn render_to_rgba_async(
        &mut self,
        plan: &Plan,
        camera: &Camera3d,
        width: u32,
        height: u32,
    ) -> Result<Vec<u8>, MarchGpuError> {
        self.prepare(plan, camera, width, height)?;
        craterfield_gpu::settle().await?;
        let target = self.readback_target(width, height)?;
        let mut encoder = self
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("craterfield march3d"),
            });
        self.encode_pass(&mut encoder, plan.key, target.view(), width, height, None);
        target.encode_copy(&mut encoder);
        self.queue.submit([encoder.finish()]);
        let pixels = target.read_async(&self.device).await;
        self.readback = Some(target);
        Ok(pixels?.into_raw())
    }

    /// The readback target, made anew when the size changed.
    fn readback_target(&mut self, width: u32, height: u32) -> Result<Offscreen, MarchGpuError> {
        match self.readback.take() {
            Some(target) if target.size() == (width, height) => Ok(target),
            _ => Ok(Offscreen::storage(&self.device, width, height)?),
        }
    }

    /// Renders `plan` seen by `camera` at `width x height` and reads back the pixels: RGBA,
    /// 4 bytes per pixel, rows top to bottom. Native targets only (see
    /// [`Self::render_to_rgba_async`]).
    #[cfg(not(target_family = "wasm"))]
    pub fn render_to_rgba(
        &mut self,
        plan: &Plan,
        camera: &Camera3d,
        width: u32,
        height: u32,
    ) -> Result<Vec<u8>, MarchGpuError> {
        self.render_timed(plan, camera, width, height)
            .map(|(pixels, _)| pixels)
    }

    /// Like [`render_to_rgba`](Self::render_to_rgba), with the frame's time in
    /// milliseconds: GPU time of the pass from timestamp queries when the device has them
    /// ([`gpu_timestamps`](Self::gpu_timestamps)), otherwise wall-clock time from submitting
    /// the pass to its completion. Compiling a new plan's pipeline is not timed. Each wait
    /// for the GPU is bounded by the [`wait_limit`](Self::wait_limit). Native targets only.
    #[cfg(not(target_family = "wasm"))]
    pub fn render_timed(
        &mut self,
        plan: &Plan,
        camera: &Camera3d,
        width: u32,
        height: u32,
    ) -> Result<(Vec<u8>, f64), MarchGpuError> {
        self.prepare(plan, camera, width, height)?;
        let target = self.readback_target(width, height)?;
        self.readback = Some(target);
        let Some(target) = self.readback.as_ref() else {
            unreachable!("the readback target was just set");
        };
        let mut encoder = self
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("craterfield march3d"),
            });
        let stamps = self.timestamps.as_ref().and_then(|ts| ts.pair(0));
        self.encode_pass(&mut encoder, plan.key, target.view(), width, height, stamps);
        // Every submission is waited for with the marcher's limit before a read maps its
        // buffer; by then the GPU has finished and the read's own wait returns at once.
        if let Some(ts) = &self.timestamps {
            ts.encode_resolve(&mut encoder);
            target.encode_copy(&mut encoder);
            let index = self.queue.submit([encoder.finish()]);
            wait_for(&self.device, Some(index), self.wait_limit, "march pass")?;
            let pixels = target.read(&self.device)?.into_raw();
            let ms = ts.read_ms(&self.device)?.first().copied().unwrap_or(0.0);
            return Ok((pixels, ms));
        }
        // No timestamp queries: the wall-clock time of the pass alone, then the copy.
        let started = Instant::now();
        let index = self.queue.submit([encoder.finish()]);
        wait_for(&self.device, Some(index), self.wait_limit, "march pass")?;
        let ms = started.elapsed().as_secs_f64() * 1e3;
        let mut copy = self
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("craterfield march3d readback"),
            });
        target.encode_copy(&mut copy);
        let index = self.queue.submit([copy.finish()]);
        wait_for(&self.device, Some(index), self.wait_limit, "readback copy")?;
        Ok((target.read(&self.device)?.into_raw(), ms))
    }

    /// Checks the size and camera, compiles (or finds) the plan's pipeline and writes the
    /// camera uniform.
    fn prepare(
        &mut self,
        plan: &Plan,
        camera: &Camera3d,
        width: u32,
        height: u32,
    ) -> Result<(), MarchGpuError> {
        // In a browser: a pipeline made earlier that the device has since refused.
        craterfield_gpu::pending_errors()?;
        // The CPU tracer's limits too: the same image sizes on both renderers.
        let limit = self
            .device
            .limits()
            .max_texture_dimension_2d
            .min(crate::cpu::MAX_SIDE);
        let pixels = u64::from(width) * u64::from(height);
        if width == 0
            || height == 0
            || width > limit
            || height > limit
            || pixels > crate::cpu::MAX_PIXELS
        {
            return Err(MarchGpuError::Size {
                width,
                height,
                limit,
            });
        }
        let finite = [camera.position, camera.forward, camera.right, camera.up]
            .iter()
            .all(|v| v.is_finite());
        if !(finite && camera.tan_half_fov.is_finite() && camera.tan_half_fov > 0.0) {
            return Err(MarchGpuError::Camera);
        }
        let (device, layout, budget) = (&self.device, &self.pipeline_layout, &self.budget);
        self.pipelines
            .get_or_try_insert_with(plan.key, || compile(device, layout, plan, budget))?;
        let frame = MarchFrame::new(camera, width, height);
        self.queue
            .write_buffer(&self.frame, 0, bytemuck::bytes_of(&frame));
        Ok(())
    }

    /// Records the compute pass over `target` with the pipeline of `key` (already
    /// prepared), with timestamps around it when `timed`.
    fn encode_pass(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        key: u64,
        target: &wgpu::TextureView,
        width: u32,
        height: u32,
        timestamps: Option<(&wgpu::QuerySet, u32)>,
    ) {
        let Some(pipeline) = self.pipelines.peek(key) else {
            unreachable!("prepare compiled the pipeline of this key");
        };
        let bind = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("craterfield march3d"),
            layout: &self.bind_layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: self.frame.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(target),
                },
            ],
        });
        let timestamp_writes =
            timestamps.map(|(query_set, first)| wgpu::ComputePassTimestampWrites {
                query_set,
                beginning_of_pass_write_index: Some(first),
                end_of_pass_write_index: Some(first + 1),
            });
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("craterfield march3d"),
            timestamp_writes,
        });
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, &bind, &[]);
        pass.dispatch_workgroups(width.div_ceil(WORKGROUP), height.div_ceil(WORKGROUP), 1);
    }
}

/// `plan`'s emitted module ([`march_wgsl`]), refused with [`MarchGpuError::TooLarge`] when it
/// is past `budget`: what [`Marcher`] hands the driver goes through this. It needs no
/// device, so a plan can be checked before asking for one.
pub fn march_wgsl_within(plan: &Plan, budget: &ShaderBudget) -> Result<String, MarchGpuError> {
    let source = march_wgsl(plan)?;
    budget
        .check_inlined(march_inlined_statements(plan, &source))
        .and_then(|()| budget.check_text(&source))
        .map_err(|e| match e {
            EmitError::TooLarge { what, size, limit } => MarchGpuError::TooLarge {
                key: plan.key,
                what,
                size,
                limit,
            },
        })?;
    Ok(source)
}

/// The compute pipeline of `plan`'s emitted module (within `budget`), with the device's
/// validation errors as values.
fn compile(
    device: &wgpu::Device,
    layout: &wgpu::PipelineLayout,
    plan: &Plan,
    budget: &ShaderBudget,
) -> Result<wgpu::ComputePipeline, MarchGpuError> {
    let source = march_wgsl_within(plan, budget)?;
    let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("craterfield march3d"),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("craterfield march3d"),
        layout: Some(layout),
        module: &module,
        entry_point: Some("main"),
        compilation_options: Default::default(),
        cache: None,
    });
    craterfield_gpu::validated(
        scope,
        || format!("march3d plan {:#018x}", plan.key),
        pipeline,
    )
    .map_err(|e| match e {
        craterfield_gpu::GpuError::Validation { message, .. } => MarchGpuError::Validation {
            key: plan.key,
            message,
        },
        other => other.into(),
    })
}
