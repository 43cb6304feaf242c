//! The emitted form of a world for one camera: what the emitter (`march3d::compile`) decided
//! and what both renderers execute, the WGSL code generator (`march3d::codegen3d`) as shader
//! text and the CPU sphere tracer (`march3d::cpu`) by interpreting it.
//!
//! This file is the contract between the two renderers: every formula below is what both
//! compute, so that the GPU image and the CPU image differ only by float rounding.
//!
//! # Scene distance `map(p) -> (d, material)`
//! 1. `d = +inf`, `m = SKY`.
//! 2. Terrain (if any): `dt = (p.y - h(p.xz)) * terrain.step_scale`, material
//!    `terrain.material`. `h` is [`Fbm::height`].
//! 3. Early out (if `early_out = Some(top)`) and `p.y > top + EARLY_OUT_MARGIN`: the
//!    objects all lie below `top`, so `d = min(dt, p.y - top)` and the material stays the
//!    terrain's (or `SKY` when `p.y - top` is smaller). No node is evaluated. The margin
//!    keeps that bound well above any hit threshold: right above `top` it would otherwise
//!    read as a surface, and rays skimming over the objects would stop on an invisible
//!    plane.
//! 4. Otherwise each [`Node`] in order: `dn = node_distance(p)`; when `dn < d`:
//!    `d = dn, m = node.material` (strictly less: the first node wins ties).
//! 5. Material IDs (`material_ids = true`) are tracked as above during the march. When
//!    false, the march keeps only `d`, and the material of a hit is found afterwards by
//!    evaluating every node once more at the hit point (the cost the IDs remove).
//!
//! # Node distance
//! * `lift`: [`Lift::None`] uses `p`; [`Lift::Baked`]`(y)` uses `p - (0, y, 0)`;
//!   [`Lift::Ground`]`{x, z}` uses `p - (0, h(x, z), 0)` (the terrain height computed in the
//!   shader: the cost constant baking removes; counts as one SDF evaluation).
//! * `guard = Some(g)`: `q = abs(p - g.centre) - g.half`, `db = length(max(q, 0))`; when
//!   `db > g.margin` the node returns `db` without evaluating its shape (the shape lies
//!   inside the box, so `db` is a lower bound of its distance). Otherwise the shape.
//! * [`Shape::Prim`]: the primitive's formula ([`PrimKind`]) at `rotation * (p - centre)`.
//! * [`Shape::Blend`]: smooth union of the parts, left to right, with the polynomial smooth
//!   minimum `smin(a, b, k) = min(a, b) - h*h*k/4` where `h = max(k - |a - b|, 0) / k`.
//! * [`Shape::Displaced`]: `(prim(p) + amp * (value_noise3(p * freq) - 0.5)) * scale`
//!   where `scale = 1 / (1 + amp * freq * VALUE_NOISE3_SLOPE)` keeps the result a
//!   distance bound.
//! * [`Shape::Rows`]: row `i` (0-based, `count` rows) is the part translated by
//!   `(0, 0, i * spacing)`. With `z = p.z - part.centre.z`, nearest-row repetition
//!   evaluates row `c = clamp(round(z / spacing), 0, count - 1)` and its neighbour `c +
//!   sign(z - c * spacing)` when that is in range (1-2 evaluations); without it, all rows,
//!   `min` over them.
//! * [`Shape::Mandelbulb`]: the power-8 bulb, `w = p - centre`, `m = dot(w, w)`,
//!   `dz = derivative`;
//!   `iterations` times: `dz = 8 * m^3.5 * dz + 1`, `w = (p - centre) + bulb8(w)`,
//!   `m = dot(w, w)`, stop when `m > bailout`; distance `0.25 * ln(m) * sqrt(m) / dz`.
//!   `bulb8` is the trigonometric form `r^8 (sin(b) sin(a), cos(b), sin(b) cos(a))` with
//!   `b = 8 acos(w.y / r)`, `a = 8 atan2(w.x, w.z)`, written without trigonometry.
//!
//! Every node's geometry lies inside its [`Node::bound`] sphere (in world space, after
//! the lift), which the emitter uses for culling, LOD and shadows.
//!
//! # Noise
//! `fract(x) = x - floor(x)`. Lattice hashes of integer points `q` ([`enum@Hash`]):
//! * 2D, `DotFract`: `p3 = fract((q.x, q.y, q.x) * 0.1031); p3 += dot(p3, p3.yzx + 33.33);
//!   fract((p3.x + p3.y) * p3.z)`. 3D: `p3 = fract(q * 0.1031); p3 += dot(p3, p3.zyx +
//!   31.32); fract((p3.x + p3.y) * p3.z)`.
//! * `Sin`: `fract(sin(dot(q, (127.1, 311.7))) * 43758.5453)`, in 3D with `(127.1, 311.7,
//!   74.7)`.
//!
//! 2D value noise with its gradient at `x`: `i = floor(x), f = x - i, u = f*f*(3 - 2f),
//! du = 6 f (1 - f)`; `a, b, c, d` the hashes of `i, i + (1,0), i + (0,1), i + (1,1)`;
//! `k = a - b - c + d`; value `a + (b-a) u.x + (c-a) u.y + k u.x u.y`, gradient
//! `du * ((b-a) + k u.y, (c-a) + k u.x)`. 3D value noise: the same smoothstep weights,
//! trilinear over the 8 corner hashes (value only).
//!
//! [`Fbm::height`]: `q = (x, z) * frequency, J = frequency * I, s = 0, g = 0, w = 1`; per
//! octave: `(v, gn) = noise(q); s += w v; g += w J^T gn; q = lacunarity R q; J =
//! lacunarity R J; w *= gain`, with `R q = (c q.x - s q.y, s q.x + c q.y)` for `c, s` the
//! cosine and sine of `rotation`. Height `base + amplitude * s`, gradient `amplitude * g`.
//!
//! # Normals
//! Terrain hits (material `terrain.material`) with `analytic_normal`:
//! `normalize(-gx, 1, -gz)` from the height's gradient. Other terrain hits: central
//! differences of `map` with step `normal_eps` (6 evaluations). Other hits: forward
//! differences `normalize(map(p + e_i) - map(p))` (3 evaluations besides `map(p)`).
//!
//! # Marching
//! A ray from `o` along unit `dir` starts at `t = 0`; per step `d = map(o + t dir)`; it hits
//! when `d < hit + hit_per_t * t`, and misses when `|o + t dir| > escape`, `t > far` or after
//! `max_steps` steps; otherwise `t += d * step_factor`. With `relax > 1` the step is
//! over-relaxed (Keinert et al. 2014): `step = relax * d * step_factor` while the spheres of
//! consecutive points overlap, falling back to the previous point and plain steps when they
//! do not.
//!
//! World shading with a terrain: a ray that stops without a hit (out of steps, past `far`
//! or escaped) while pointing below the horizon (`dir.y < 0`) or ending below the
//! terrain's top ([`Fbm::top`]) lands on the height field: it is shaded as a terrain hit at
//! `(x, height(x, z), z)` under its end point, at that point's distance. Such a ray can
//! only be looking at the ground; shading it as sky drew sky through grazing hills.
//!
//! Soft shadow (paper shading, [`ShadowMode::Full`]) from `p` towards unit `l`, up to
//! distance `limit` (paper shading: none; the ray runs past the light, as the reference
//! renderer's does): `x = q = p + n * ray_offset, s = ray_offset, res = 1, ph = 1e20` (`s`
//! runs `ray_offset` ahead of the distance from `q`); per step (at most `max_steps`, or
//! `ShadowMode::Full::steps`): `h = map(x)`; if `h < hit`
//! the result is 0; the closest approach between this step's sphere and the previous one,
//! `y = h^2 / (2 ph), d = sqrt(max(h^2 - y^2, 0))`; when `s - y > 0`, `res = min(res, k d /
//! (s - y))`; `ph = h, s += h, x += h l`; stop when `s > limit` or `|x| > escape`.
//!
//! # Counting
//! One *SDF evaluation* is one call of a primitive's distance, of the terrain height, of a
//! bounding sphere, or of one Mandelbulb; a guard's box test is not one.

mod check;

use glam::{Mat3, Vec3};
use serde::{Deserialize, Serialize};

pub use check::PlanError;

/// Most octaves of a terrain's FBM.
pub const MAX_OCTAVES: u32 = 12;

/// Most reflection bounces of the paper shading.
pub const MAX_BOUNCES: u32 = 64;

/// Most iterations of a Mandelbulb node.
pub const MAX_MANDELBULB_ITERATIONS: u32 = 64;

/// How far above the tallest object the height early-out starts (see the module doc).
pub const EARLY_OUT_MARGIN: f32 = 0.5;

/// The material index of the background.
pub const SKY: u32 = u32::MAX;

/// A steepest-slope bound of [`value_noise3`](Fbm) over unit frequency, used by
/// [`Shape::Displaced`]: the gradient of the trilinear smoothstep value noise is at most
/// `1.5 * sqrt(3)` (each partial is at most 1.5).
pub const VALUE_NOISE3_SLOPE: f32 = 2.598_076;

/// A world ready to render for one camera.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Plan {
    /// The cache key of the emitted program: visible set, LOD levels, step count and the
    /// options that change the code (see `march3d::compile`).
    pub key: u64,
    /// The march.
    pub march: March,
    /// The heightfield terrain, if the world has one.
    pub terrain: Option<TerrainPlan>,
    /// The top of the tallest object (height early-out, see the module doc).
    pub early_out: Option<f32>,
    /// The objects that survived culling, at their LOD.
    pub nodes: Vec<Node>,
    /// Materials by index.
    pub materials: Vec<Material>,
    /// How hits become colours.
    pub shading: Shading,
    /// Whether the march tracks the nearest node's material (see the module doc).
    pub material_ids: bool,
    /// Which hash the noise uses.
    pub hash: Hash,
}

/// How rays step.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct March {
    /// At most this many steps per ray.
    pub max_steps: u32,
    /// A ray hits when `d < hit + hit_per_t * t`.
    pub hit: f32,
    /// The part of the hit threshold that grows with the distance travelled.
    pub hit_per_t: f32,
    /// A ray misses when `t > far`.
    pub far: f32,
    /// A ray escapes when `|p| > escape` (distance of the point from the origin of the world).
    pub escape: f32,
    /// Each step advances `t += d * step_factor` (a Lipschitz bound of the field, or 1).
    pub step_factor: f32,
    /// Secondary rays start this far from the surface along the normal.
    pub ray_offset: f32,
    /// Forward-difference step of object normals.
    pub normal_eps: f32,
    /// Over-relaxation factor of enhanced sphere tracing (1 = plain sphere tracing).
    pub relax: f32,
}

/// The heightfield terrain `y = h(x, z)`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TerrainPlan {
    /// The height function.
    pub fbm: Fbm,
    /// Its material.
    pub material: u32,
    /// `1 / sqrt(1 + max|grad h|^2)`: multiplies `p.y - h` into a distance bound.
    pub step_scale: f32,
    /// Terrain normals from the analytic gradient (one call) instead of central
    /// differences of the scene (six calls).
    pub analytic_normal: bool,
}

/// Fractal value noise: `h(x, z) = base + amplitude * sum_o gain^o * n(R^o (x, z) *
/// frequency * lacunarity^o)` over `octaves` octaves, with `n` the 2D value noise in
/// `[0, 1)` of smoothstep-interpolated lattice hashes and `R` the rotation by
/// `rotation` radians (to break the lattice's alignment from octave to octave).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Fbm {
    /// Height at noise 0.
    pub base: f32,
    /// Height of the first octave.
    pub amplitude: f32,
    /// Lattice cells per world unit of the first octave.
    pub frequency: f32,
    /// Frequency ratio between octaves.
    pub lacunarity: f32,
    /// Amplitude ratio between octaves.
    pub gain: f32,
    /// Number of octaves (1..=12).
    pub octaves: u32,
    /// Rotation between octaves, radians.
    pub rotation: f32,
}

/// The lattice hash of the noise.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Hash {
    /// `fract((p3.x + p3.y) * p3.z)` after `p3 = fract(p * 0.1031); p3 += dot(p3, p3.yzx +
    /// 33.33)`: multiplies and adds only.
    DotFract,
    /// The conventional `fract(sin(dot(p, (127.1, 311.7, 74.7))) * 43758.5453)`.
    Sin,
}

/// One object of the emitted world.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Node {
    /// Material index.
    pub material: u32,
    /// Where the node's local y = 0 is.
    pub lift: Lift,
    /// The box test that skips the shape far from it.
    pub guard: Option<Guard>,
    /// The geometry.
    pub shape: Shape,
    /// A sphere (world space) containing the geometry.
    pub bound: Sphere,
    /// Primitive evaluations one call of this node costs (for the statistics and the
    /// emitter's cost model).
    pub cost: u32,
}

/// Vertical placement of a node.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Lift {
    /// Coordinates are world coordinates.
    None,
    /// The terrain height at the anchor, baked as a literal.
    Baked(f32),
    /// The terrain height at `(x, z)`, computed when the node is evaluated.
    Ground {
        /// Anchor x.
        x: f32,
        /// Anchor z.
        z: f32,
    },
}

/// An axis-aligned box around a node's geometry (node-local coordinates, after the lift).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Guard {
    /// Box centre.
    pub centre: Vec3,
    /// Half extents.
    pub half: Vec3,
    /// Within this distance of the box, the shape itself is evaluated.
    pub margin: f32,
}

/// A sphere.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Sphere {
    /// Centre.
    pub centre: Vec3,
    /// Radius.
    pub radius: f32,
}

/// The geometry of a node (node-local coordinates).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Shape {
    /// One primitive.
    Prim(Prim),
    /// Smooth union of primitives (a tree).
    Blend {
        /// Blend radius.
        k: f32,
        /// The parts.
        parts: Vec<Prim>,
    },
    /// A primitive with 3D value-noise displacement (a rock).
    Displaced {
        /// The base shape.
        prim: Prim,
        /// Displacement amplitude.
        amp: f32,
        /// Noise frequency.
        freq: f32,
    },
    /// `count` copies of `part` spaced `spacing` apart along +z (vineyard rows).
    Rows {
        /// Row 0.
        part: Prim,
        /// Distance between rows.
        spacing: f32,
        /// Number of rows (>= 1).
        count: u32,
        /// Evaluate only the nearest row and its neighbour.
        nearest: bool,
    },
    /// A power-8 Mandelbulb.
    Mandelbulb {
        /// Centre.
        centre: Vec3,
        /// Iterations (at most).
        iterations: u32,
        /// Escape when `|w|^2 > bailout`.
        bailout: f32,
        /// The running derivative's start value: 1 in the textbook estimate; the reference
        /// renderer starts at 1.5, which makes its estimate smaller (more conservative) and
        /// so changes its soft shadows.
        derivative: f32,
    },
}

/// A primitive placed in node-local space: `p_local = rotation * (p - centre)`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Prim {
    /// Where the primitive's origin is.
    pub centre: Vec3,
    /// World-to-primitive rotation, if any (the inverse of the object's rotation).
    pub rotation: Option<Mat3>,
    /// The primitive in its own frame.
    pub kind: PrimKind,
}

/// Primitives in their own frame (formulas of Quilez's distance functions).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum PrimKind {
    /// `|p| - r`.
    Sphere {
        /// Radius.
        r: f32,
    },
    /// `q = |p| - half; |max(q, 0)| + min(max(q.x, q.y, q.z), 0)`.
    Box {
        /// Half extents.
        half: Vec3,
    },
    /// A box with edges rounded by `r` (`half` includes the rounding).
    RoundBox {
        /// Half extents.
        half: Vec3,
        /// Rounding radius.
        r: f32,
    },
    /// Segment from `a` to `b`, radius `r`.
    Capsule {
        /// One end.
        a: Vec3,
        /// The other end.
        b: Vec3,
        /// Radius.
        r: f32,
    },
    /// Torus in the xz plane: `|(|p.xz| - major, p.y)| - minor`.
    Torus {
        /// Ring radius.
        major: f32,
        /// Tube radius.
        minor: f32,
    },
    /// Capped cylinder along y: radius `r`, half height `h`.
    Cylinder {
        /// Radius.
        r: f32,
        /// Half height.
        h: f32,
    },
    /// Capped cone along y from `-h` (radius `r1`) to `+h` (radius `r2`).
    CappedCone {
        /// Half height.
        h: f32,
        /// Bottom radius.
        r1: f32,
        /// Top radius.
        r2: f32,
    },
    /// Exact octahedron `|x| + |y| + |z| = s`.
    Octahedron {
        /// Size.
        s: f32,
    },
    /// Ellipsoid with radii `r` (Quilez's bound `k0 * (k0 - 1) / k1`).
    Ellipsoid {
        /// Radii.
        r: Vec3,
    },
    /// Half-space below the plane `dot(p, normal) = offset` (`normal` unit length).
    Plane {
        /// Unit normal.
        normal: Vec3,
        /// Offset along the normal.
        offset: f32,
    },
}

/// A surface's look.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Material {
    /// Linear RGB albedo.
    pub colour: Vec3,
    /// Mirror reflectivity (paper shading).
    pub reflectivity: f32,
}

/// How a hit becomes a colour.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Shading {
    /// The reference paper's model (see [`PaperShading`]).
    Paper(PaperShading),
    /// Outdoor worlds (see [`WorldShading`]).
    World(WorldShading),
}

/// The reference paper's shading: for each point light at distance `r`, intensity
/// `emission / r`; `colour * (ambient + sum diffuse * shadow * intensity) + specular *
/// sum pow(max(dot(reflect(-l, n), -dir), 0), shininess) * shadow * intensity`; times the
/// fog `exp(-fog * t^3)`; plus reflections (`reflectivity * reflection_scale` times the
/// colour traced along the mirror direction, up to `bounces` bounces); then each channel
/// clamped to [0, 1] and raised to `gamma`. Misses are black. Bytes are `floor(c * 255)`,
/// the reference's truncation (world shading rounds).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PaperShading {
    /// Point lights.
    pub lights: Vec<PointLight>,
    /// Phong exponent.
    pub shininess: f32,
    /// Specular weight.
    pub specular: f32,
    /// Ambient term.
    pub ambient: f32,
    /// Reflection bounces.
    pub bounces: u32,
    /// Multiplier of reflected colour (times the material's reflectivity).
    pub reflection_scale: f32,
    /// Soft shadows `min(k * d / t)` along the light ray (`None`: no shadows).
    pub shadow_k: Option<f32>,
    /// Fog coefficient of `exp(-fog * t^3)`.
    pub fog: f32,
    /// Output exponent.
    pub gamma: f32,
}

/// A point light.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PointLight {
    /// Position.
    pub position: Vec3,
    /// Emission (falls off as 1/distance).
    pub emission: f32,
}

/// Outdoor shading: sun, sky, ambient occlusion, shadows, distance fog.
///
/// A miss is `mix(sky[0], sky[1], clamp(dir.y, 0, 1))`. A hit at distance `t` with normal
/// `n` and albedo `c`: `diff = max(dot(n, sun), 0)`; `sh` the shadow (1 lit, 0 shadowed;
/// [`ShadowMode`]); `occ` the occlusion of `N` taps ([`AoMode`]): `ao = 0, sca = 1`, for
/// `i < N`: `h = 0.01 + 0.12 i / max(N - 1, 1)`, `ao += (h - map(p + h n)) sca`, `sca *=
/// 0.95`; `occ = clamp(1 - 3 ao, 0, 1)` (1 when `N = 0`). Colour `c * (sun_colour * diff *
/// sh + 0.6 * mix(sky[0], sky[1], 0.5 + 0.5 n.y) * occ)`, then fog `mix(colour, sky[0], 1 -
/// exp(-fog t))`. Misses and hits are then clamped to [0, 1] and raised to `gamma`.
///
/// [`ShadowMode::TerrainAndBounds`]: from `o = p + n * ray_offset`, shadowed when one of
/// the samples `o + sun * s_i` lies below the terrain, or when the sun ray meets a node's
/// bound ahead: `oc = centre - o, b = dot(oc, sun), c = dot(oc, oc) - r^2`, `b > 0 && b * b
/// > c`. [`ShadowMode::Full`]: `sh` is the soft shadow (module doc) from `p` along `sun`
/// with limit `far`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WorldShading {
    /// Unit direction towards the sun.
    pub sun: Vec3,
    /// Sun colour.
    pub sun_colour: Vec3,
    /// Sky colour at the horizon and at the zenith (misses and ambient light).
    pub sky: [Vec3; 2],
    /// Ambient occlusion taps.
    pub ao: AoMode,
    /// Sun shadows.
    pub shadow: ShadowMode,
    /// Fog density of `exp(-fog * t)` towards the horizon colour.
    pub fog: f32,
    /// Output exponent.
    pub gamma: f32,
}

/// Ambient occlusion taps along the normal.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum AoMode {
    /// Always this many taps.
    Fixed(u32),
    /// `near` taps closer than `near_distance`, `far` taps beyond; none on flat terrain
    /// (normal.y > 0.9) above the camera.
    Adaptive {
        /// Taps near the camera.
        near: u32,
        /// Taps far from the camera.
        far: u32,
        /// The distance between near and far.
        near_distance: f32,
    },
}

/// Sun shadows.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum ShadowMode {
    /// Soft shadow march of the full scene, at most `steps` steps, softness `k`.
    Full {
        /// Steps.
        steps: u32,
        /// Softness.
        k: f32,
    },
    /// `steps` samples of the terrain height along the sun ray at distances
    /// `spacing * (1, 3, 7, 15, ...)`, plus an exact ray test against each node's bound.
    TerrainAndBounds {
        /// Samples.
        steps: u32,
        /// Distance unit of the samples.
        spacing: f32,
    },
}

impl Prim {
    /// The primitive at `centre`, unrotated.
    pub fn at(centre: Vec3, kind: PrimKind) -> Prim {
        Prim {
            centre,
            rotation: None,
            kind,
        }
    }
}

/// The camera of a frame: pixel `(i, j)` of a `W x H` image looks along
/// `normalize(forward + x * right + y * up)` with `x = (2 (i + 0.5) / W - 1) * (W / H) *
/// tan_half_fov` and `y = (1 - 2 (j + 0.5) / H) * tan_half_fov` (the reference paper's
/// rays).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Camera3d {
    /// Eye position.
    pub position: Vec3,
    /// Unit view direction.
    pub forward: Vec3,
    /// Unit screen-right direction.
    pub right: Vec3,
    /// Unit screen-up direction.
    pub up: Vec3,
    /// `tan(fov_y / 2)`.
    pub tan_half_fov: f32,
}

impl Camera3d {
    /// A camera at `position` looking along `forward` with `up` roughly up and a vertical
    /// field of view of `fov_deg` degrees; `None` when the vectors are degenerate (zero,
    /// parallel, not finite) or the angle is not in (0, 180).
    pub fn looking(position: Vec3, forward: Vec3, up: Vec3, fov_deg: f32) -> Option<Camera3d> {
        if !(position.is_finite() && fov_deg > 0.0 && fov_deg < 180.0) {
            return None;
        }
        let forward = forward.try_normalize()?;
        let right = up.cross(forward).try_normalize()?;
        let up = forward.cross(right);
        Some(Camera3d {
            position,
            forward,
            right,
            up,
            tan_half_fov: (fov_deg.to_radians() * 0.5).tan(),
        })
    }

    /// The unit direction of pixel `(i, j)` of a `width x height` image.
    pub fn ray(&self, i: u32, j: u32, width: u32, height: u32) -> Vec3 {
        let aspect = width as f32 / height as f32;
        let x = (2.0 * (i as f32 + 0.5) / width as f32 - 1.0) * aspect * self.tan_half_fov;
        let y = (1.0 - 2.0 * (j as f32 + 0.5) / height as f32) * self.tan_half_fov;
        (self.forward + self.right * x + self.up * y).normalize()
    }
}
