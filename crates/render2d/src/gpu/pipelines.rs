//! Bind group layout entries and pipeline constructors shared by the 2D render passes;
//! shader and pipeline validation errors come back as values
//! ([`craterfield_gpu::GpuError::Validation`] in a [`RenderError`]; in a browser from a
//! later call, see [`craterfield_gpu::validated`]).

use super::RenderError;

/// A uniform buffer at `binding`, visible to the vertex, fragment and compute stages.
/// (Not `ShaderStages::all()`: that includes the mesh shader stages, which WebGPU refuses.)
pub(super) fn uniform_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::VERTEX_FRAGMENT | wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

/// A read-only storage buffer of the field at `binding` (fragment and compute stages).
pub(super) fn storage_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    buffer_entry(
        binding,
        wgpu::ShaderStages::FRAGMENT | wgpu::ShaderStages::COMPUTE,
        true,
    )
}

/// A storage buffer at `binding` for `visibility`.
pub(super) fn buffer_entry(
    binding: u32,
    visibility: wgpu::ShaderStages,
    read_only: bool,
) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

/// A filterable 2D float texture at `binding` (fragment and compute stages).
pub(super) fn texture_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT | wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Float { filterable: true },
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        },
        count: None,
    }
}

/// A bind group layout of `entries`.
pub(super) fn layout(
    device: &wgpu::Device,
    label: &str,
    entries: &[wgpu::BindGroupLayoutEntry],
) -> wgpu::BindGroupLayout {
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some(label),
        entries,
    })
}

/// The shader module of `source` and a pipeline layout of `bind_layouts`.
fn module_and_layout(
    device: &wgpu::Device,
    label: &str,
    source: &str,
    bind_layouts: &[&wgpu::BindGroupLayout],
) -> (wgpu::ShaderModule, wgpu::PipelineLayout) {
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(label),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    let layouts: Vec<Option<&wgpu::BindGroupLayout>> =
        bind_layouts.iter().map(|l| Some(*l)).collect();
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(label),
        bind_group_layouts: &layouts,
        immediate_size: 0,
    });
    (module, pipeline_layout)
}

/// `pipeline`, or the validation error the scope caught while it was made.
fn validated<P>(
    scope: wgpu::ErrorScopeGuard,
    label: &str,
    entry: &str,
    pipeline: P,
) -> Result<P, RenderError> {
    Ok(craterfield_gpu::validated(
        scope,
        || format!("{label} ({entry})"),
        pipeline,
    )?)
}

/// A compute pipeline over `bind_layouts`, validation errors as values.
pub(super) fn compute_pipeline(
    device: &wgpu::Device,
    label: &str,
    source: &str,
    entry: &str,
    bind_layouts: &[&wgpu::BindGroupLayout],
) -> Result<wgpu::ComputePipeline, RenderError> {
    let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
    let (module, pipeline_layout) = module_and_layout(device, label, source, bind_layouts);
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some(label),
        layout: Some(&pipeline_layout),
        module: &module,
        entry_point: Some(entry),
        compilation_options: Default::default(),
        cache: None,
    });
    validated(scope, label, entry, pipeline)
}

/// Creates a shader module and a full-screen pipeline, turning validation errors into values.
pub(super) fn fullscreen_pipeline(
    device: &wgpu::Device,
    label: &str,
    source: &str,
    entry: &str,
    bind_layout: &wgpu::BindGroupLayout,
    format: wgpu::TextureFormat,
) -> Result<wgpu::RenderPipeline, RenderError> {
    render_pipeline(
        device,
        label,
        source,
        ("vs_fullscreen", entry),
        &[bind_layout],
        format,
    )
}

/// A render pipeline with vertex and fragment entry points `entries` over `bind_layouts`.
pub(super) fn render_pipeline(
    device: &wgpu::Device,
    label: &str,
    source: &str,
    entries: (&str, &str),
    bind_layouts: &[&wgpu::BindGroupLayout],
    format: wgpu::TextureFormat,
) -> Result<wgpu::RenderPipeline, RenderError> {
    let (vertex_entry, entry) = entries;
    let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
    let (module, pipeline_layout) = module_and_layout(device, label, source, bind_layouts);
    let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(label),
        layout: Some(&pipeline_layout),
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some(vertex_entry),
            compilation_options: Default::default(),
            buffers: &[],
        },
        primitive: wgpu::PrimitiveState::default(),
        depth_stencil: None,
        multisample: wgpu::MultisampleState::default(),
        fragment: Some(wgpu::FragmentState {
            module: &module,
            entry_point: Some(entry),
            compilation_options: Default::default(),
            targets: &[Some(wgpu::ColorTargetState {
                format,
                blend: None,
                write_mask: wgpu::ColorWrites::ALL,
            })],
        }),
        multiview_mask: None,
        cache: None,
    });
    validated(scope, label, entry, pipeline)
}

/// The whole of buffer `b` at `binding`.
pub(super) fn buffer(binding: u32, b: &wgpu::Buffer) -> wgpu::BindGroupEntry<'_> {
    wgpu::BindGroupEntry {
        binding,
        resource: b.as_entire_binding(),
    }
}
