//! The emitted WGSL on a real GPU (whatever adapter wgpu finds; Mesa's lavapipe in CI):
//! `base_sample` at thousands of points near the surfaces of every example level and of the
//! every-variant graph agrees with `Graph::sample` on the CPU, and so does the default level
//! culled to a 1080p view, inside that view.

mod common;
mod emit_support;

use common::Rng;
use common::gpu::TestResult;
use craterfield::emit::TerrainEmitter;
use craterfield::field2d::{Aabb, Graph, Sample, Sdf};
use craterfield::gpu::GpuContext;
use emit_support::{every_variant_bounds, every_variant_graph, example_levels, prospero_graph};
use glam::Vec2;
use wgpu::util::DeviceExt;

/// Points compared per graph.
const POINTS: usize = 3000;
/// Points are taken where the CPU distance is below this (near the surfaces).
const NEAR: f32 = 24.0;
/// Offset of the neighbours that tell whether the CPU gradient is well defined at a point.
const PROBE: f32 = 4e-3;

const ENTRY: &str = "
@group(0) @binding(0) var<storage, read> points: array<vec2<f32>>;
@group(0) @binding(1) var<storage, read_write> results: array<vec4<f32>>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if (i < arrayLength(&points)) {
        results[i] = base_sample(points[i]);
    }
}
";

/// `base_sample` of `emitted` at every point, computed on the GPU.
fn gpu_samples(gpu: &GpuContext, name: &str, emitted: &str, points: &[Vec2]) -> Vec<[f32; 4]> {
    let device = &gpu.device;
    let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(name),
        source: wgpu::ShaderSource::Wgsl(format!("{emitted}\n{ENTRY}").into()),
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some(name),
        layout: None,
        module: &module,
        entry_point: Some("main"),
        compilation_options: Default::default(),
        cache: None,
    });
    let input: Vec<u8> = points
        .iter()
        .flat_map(|p| [p.x.to_le_bytes(), p.y.to_le_bytes()])
        .flatten()
        .collect();
    let points_buf = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("points"),
        contents: &input,
        usage: wgpu::BufferUsages::STORAGE,
    });
    let size = (points.len() * 16) as u64;
    let results = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("results"),
        size,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let readback = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback"),
        size,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(name),
        layout: &pipeline.get_bind_group_layout(0),
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: points_buf.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: results.as_entire_binding(),
            },
        ],
    });
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
    {
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor::default());
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &bind_group, &[]);
        pass.dispatch_workgroups(points.len().div_ceil(64) as u32, 1, 1);
    }
    encoder.copy_buffer_to_buffer(&results, 0, &readback, 0, size);
    gpu.queue.submit([encoder.finish()]);
    if let Some(error) = pollster::block_on(scope.pop()) {
        panic!("{name}: the GPU rejected the emitted shader: {error}");
    }
    readback.slice(..).map_async(wgpu::MapMode::Read, |r| {
        r.expect("mapping the readback buffer");
    });
    device
        .poll(wgpu::PollType::wait_indefinitely())
        .expect("waiting for the GPU");
    let view = readback.slice(..).get_mapped_range().expect("mapped range");
    view.chunks_exact(16)
        .map(|c| {
            let f = |i: usize| f32::from_le_bytes([c[i], c[i + 1], c[i + 2], c[i + 3]]);
            [f(0), f(4), f(8), f(12)]
        })
        .collect()
}

/// `POINTS` points in `region` where the CPU distance is within `NEAR` of a surface.
fn points_near_surfaces(graph: &Graph, region: &Aabb, seed: u64) -> Vec<Vec2> {
    let mut rng = Rng(seed);
    let mut out = Vec::with_capacity(POINTS);
    for _ in 0..POINTS * 400 {
        let p = rng.point_in(region);
        if graph.distance(p).abs() < NEAR {
            out.push(p);
            if out.len() == POINTS {
                break;
            }
        }
    }
    assert!(
        out.len() >= POINTS / 2,
        "only {} points near surfaces",
        out.len()
    );
    out
}

/// True where the CPU gradient and material do not change within `PROBE` of `p`: the point
/// is not on a kink (a min/max switch, a medial axis) where an ulp of difference in a
/// comparison legitimately picks the other operand's gradient and material.
fn well_defined(graph: &Graph, p: Vec2, s: &Sample) -> bool {
    [
        Vec2::new(PROBE, 0.0),
        Vec2::new(-PROBE, 0.0),
        Vec2::new(0.0, PROBE),
        Vec2::new(0.0, -PROBE),
    ]
    .iter()
    .all(|&o| {
        let n = graph.sample(p + o);
        n.material == s.material && (n.gradient - s.gradient).length() < 5e-3
    })
}

/// Compare GPU and CPU at `points`; returns (worst distance error, points whose gradient and
/// material were compared).
fn compare(name: &str, graph: &Graph, points: &[Vec2], gpu: &[[f32; 4]]) -> (f32, usize) {
    let mut worst = 0.0f32;
    let mut compared = 0;
    for (p, g) in points.iter().zip(gpu) {
        let s = graph.sample(*p);
        let err = (g[0] - s.distance).abs();
        assert!(
            err <= 1e-3 * (1.0 + s.distance.abs()),
            "{name} at {p}: GPU distance {} CPU {}",
            g[0],
            s.distance
        );
        worst = worst.max(err);
        if !well_defined(graph, *p, &s) {
            continue;
        }
        let grad = Vec2::new(g[1], g[2]);
        assert!(
            (grad - s.gradient).length() <= 1e-2,
            "{name} at {p}: GPU gradient {grad} CPU {}",
            s.gradient
        );
        assert_eq!(g[3], f32::from(s.material), "{name} at {p}: material");
        compared += 1;
    }
    assert!(
        compared * 10 >= points.len() * 8,
        "{name}: only {compared} of {} points have a well-defined gradient",
        points.len()
    );
    (worst, compared)
}

fn check(gpu: &GpuContext, name: &str, graph: &Graph, region: &Aabb, view: Option<Aabb>) {
    let emitter = TerrainEmitter::new(graph);
    let plan = emitter.plan(view, 32.0);
    let wgsl = emitter.emit(&plan);
    let points = points_near_surfaces(graph, region, emitter.fingerprint());
    let results = gpu_samples(gpu, name, &wgsl, &points);
    let (worst, compared) = compare(name, graph, &points, &results);
    println!(
        "{name}: {} points ({} kept / {} culled nodes), worst distance error {worst:.2e}, \
         gradient and material compared at {compared}",
        points.len(),
        plan.kept,
        plan.culled
    );
}

fn emitted_levels_match_the_cpu_on_the_gpu(gpu: &GpuContext) -> TestResult {
    for (name, graph, bounds) in example_levels() {
        check(gpu, &name, &graph, &bounds, None);
    }
    Ok(())
}

fn the_every_variant_graph_matches_the_cpu_on_the_gpu(gpu: &GpuContext) -> TestResult {
    let bounds = every_variant_bounds();
    check(gpu, "every variant", &every_variant_graph(), &bounds, None);
    Ok(())
}

fn the_culled_default_level_matches_the_cpu_inside_its_view(gpu: &GpuContext) -> TestResult {
    let (_, graph, _) = example_levels().remove(0);
    let view = Aabb::new(Vec2::ZERO, Vec2::new(1920.0, 1080.0));
    check(
        gpu,
        "default, culled to 1920x1080",
        &graph,
        &view,
        Some(view),
    );
    Ok(())
}

fn the_prospero_expression_runs_on_the_gpu(gpu: &GpuContext) -> TestResult {
    let Some(graph) = prospero_graph() else {
        println!("prospero.vm not found: only the level graphs ran");
        return Ok(());
    };
    let region = Aabb::new(Vec2::splat(-1.0), Vec2::splat(1.0));
    let emitter = TerrainEmitter::new(&graph);
    let wgsl = emitter.emit(&emitter.plan(None, 32.0));
    let mut rng = Rng(3);
    let points: Vec<Vec2> = (0..512).map(|_| rng.point_in(&region)).collect();
    let started = std::time::Instant::now();
    let results = gpu_samples(gpu, "prospero", &wgsl, &points);
    println!(
        "prospero: {} points in {:.2?} (pipeline creation included)",
        points.len(),
        started.elapsed()
    );
    for (p, g) in points.iter().zip(&results) {
        let s = graph.sample(*p);
        assert!(
            (g[0] - s.distance).abs() <= 1e-3 * (1.0 + s.distance.abs()),
            "prospero at {p}: GPU {} CPU {}",
            g[0],
            s.distance
        );
    }
    Ok(())
}

fn main() {
    common::gpu::run(&[
        (
            "emitted_levels_match_the_cpu_on_the_gpu",
            emitted_levels_match_the_cpu_on_the_gpu,
        ),
        (
            "the_every_variant_graph_matches_the_cpu_on_the_gpu",
            the_every_variant_graph_matches_the_cpu_on_the_gpu,
        ),
        (
            "the_culled_default_level_matches_the_cpu_inside_its_view",
            the_culled_default_level_matches_the_cpu_inside_its_view,
        ),
        (
            "the_prospero_expression_runs_on_the_gpu",
            the_prospero_expression_runs_on_the_gpu,
        ),
    ]);
}
