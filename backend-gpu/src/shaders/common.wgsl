// Shared by every pipeline: the structs (twins of `layout.rs`), the
// counter-based RNG and scrambled Sobol points (twins of
// prismatic_core::{rng, sobol}), float helpers and optics (twins of
// prismatic_core::{math, optics, geometry::basis}).
// Constants (WORKGROUP_SIZE, WHITE_BAND, tolerances, RNG dimensions) come
// from the prelude that `shaders.rs` writes from the Rust constants.

// Twin of prismatic_gpu::layout::Params.
struct Params {
    seed: u32,
    chunk_start: u32,
    chunk_len: u32,
    slots: u32,
    band_count: u32,
    max_depth: u32,
    wavelengths: u32,
    object_count: u32,
    light_count: u32,
    light_cdf: u32,
    estimator: u32,
    window: u32,
    width: u32,
    height: u32,
    pixel_offset: u32,
    pixel_count: u32,
    stored: u32,
    grid_mask: u32,
    capacity: u32,
    point_capacity: u32,
    gather_first: u32,
    gather_span: u32,
    sum_shift: i32,
    flux_shift: i32,
    flux: f32,
    radius: f32,
    inv_cell: f32,
    exposure: f32,
    ambient: vec3<f32>,
    light_tracing: u32,
    background: vec3<f32>,
    splat_scale: f32,
    cam_origin: vec3<f32>,
    photon_sequence: u32,
    cam_right: vec3<f32>,
    view_seed: u32,
    cam_down: vec3<f32>,
    view_pass: u32,
    cam_corner: vec3<f32>,
    view_paths: u32,
    cam_forward: vec3<f32>,
    colour_by_wavelength: u32,
    white_balance: vec3<f32>,
    env_strength: f32,
    env_first: u32,
    env_width: u32,
    env_height: u32,
    env_turn: f32,
    caustic_photons: u32,
    indirect_flux: f32,
    rough_records: u32,
    rough_gathers: u32,
}

// Twin of prismatic_core::photon::Photon (band in the low 16 bits of
// `band_bounces`, bounces in the high 16: the Rust struct's two u16s).
struct Photon {
    position: vec3<f32>,
    flux: f32,
    direction_oct: u32,
    lambda_nm: f32,
    emission: u32,
    band_bounces: u32,
}

// Twin of prismatic_gpu::layout::GpuObject.
struct GpuObject {
    kind: u32,
    first: u32,
    count: u32,
    second: u32,
    a: vec3<f32>,
    ra: f32,
    n: vec3<f32>,
    rb: f32,
}

// Twin of prismatic_gpu::layout::GpuSurface.
struct GpuSurface {
    kind: u32,
    flags: u32,
    ior_first: u32,
    curve_first: u32,
    albedo: vec3<f32>,
    white_ior: f32,
    checker_albedo: vec3<f32>,
    checker_size: f32,
    checker_offset: vec3<f32>,
    curve_len: u32,
    absorption: vec3<f32>,
    absorption_first: u32,
    texture_first: u32,
    texture_width: u32,
    texture_height: u32,
    uv_first: u32,
    emission: vec3<f32>,
    film_first: u32,
}

// Twin of prismatic_gpu::layout::GpuLight.
struct GpuLight {
    kind: u32,
    shadows: u32,
    proj_kind: u32,
    proj_count: u32,
    position: vec3<f32>,
    power: f32,
    axis: vec3<f32>,
    cos_max: f32,
    tangent: vec3<f32>,
    radius: f32,
    bitangent: vec3<f32>,
    proj_scale: f32,
    proj_first: u32,
    proj_cdf: u32,
    sun: u32,
    spectrum_len: u32,
    reflected_r: vec3<f32>,
    spectrum_first: u32,
    reflected_g: vec3<f32>,
    cos_inner: f32,
    reflected_b: vec3<f32>,
    aimed: u32,
    aim: vec2<f32>,
    _pad1: vec2<u32>,
    mean_toward: vec3<f32>,
    range: f32,
}

// Twin of prismatic_gpu::layout::GpuBand.
struct GpuBand {
    weight: vec3<f32>,
    lambda_nm: f32,
    lo_nm: f32,
    hi_nm: f32,
    max_weight: f32,
    _pad: f32,
}

// Twin of prismatic_gpu::layout::VisiblePoint (sums and flux are i64
// fixed-point sums, see fixed.wgsl).
struct VisiblePoint {
    position: vec3<f32>,
    total: u32,
    normal: vec3<f32>,
    radius: f32,
    weight: vec3<f32>,
    found: u32,
    sums: array<vec2<u32>, 3>,
    flux: vec2<u32>,
    pixel: u32,
    ratio: f32,
    level: u32,
    widest: u32,
    albedo: vec3<f32>,
    rough: u32,
    toward: vec3<f32>,
    triangle: u32,
}

// Twin of prismatic_gpu::layout::RunStats.
struct RunStats {
    counts: array<vec2<u32>, TALLY_COUNTS>,
    flux: array<f32, TALLY_FLUXES>,
    min_ratio: atomic<u32>,
    max_ratio: atomic<u32>,
}

// Twin of prismatic_gpu::layout::Tally.
struct Tally {
    counts: array<u32, TALLY_COUNTS>,
    _pad0: array<u32, 3>,
    flux: array<f32, TALLY_FLUXES>,
    _pad1: array<u32, 2>,
}

// Tallied counts: emitted, paths, segments, specular paths, stored.
const TALLY_COUNTS: u32 = 5u;
// Tallied fluxes: emitted, stored, escaped, direct, depth limited, absorbed.
const TALLY_FLUXES: u32 = 6u;

// Twin of prismatic_gpu::layout::ScanParams.
struct ScanParams {
    n: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
}

// ---- rng.rs ----

fn pcg_hash(input: u32) -> u32 {
    let state = input * 747796405u + 2891336453u;
    let word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

fn random_u32(seed: u32, index: u32, dimension: u32) -> u32 {
    return pcg_hash(pcg_hash(pcg_hash(seed) ^ index) + dimension);
}

fn random_f32(seed: u32, index: u32, dimension: u32) -> f32 {
    return f32(random_u32(seed, index, dimension) >> 8u) * (1.0 / 16777216.0);
}

// sobol::sobol_u32: dimension 0 (bits reversed), 1 (x + 1) or 2 (x² + x + 1).
fn sobol_u32(index: u32, dimension: u32) -> u32 {
    if dimension == 0u {
        return reverseBits(index);
    }
    var x = 0u;
    var v = 1u << 31u;
    var prev = 0x55555555u;
    var i = index;
    while i != 0u {
        if (i & 1u) != 0u {
            x ^= v;
        }
        let next = select(v ^ prev ^ (prev >> 2u), v ^ (v >> 1u), dimension == 1u);
        prev = v;
        v = next;
        i >>= 1u;
    }
    return x;
}

// sobol::owen_scramble
fn owen_scramble(x: u32, seed: u32) -> u32 {
    var y = reverseBits(x) + seed;
    y ^= y * 0x6c50b47cu;
    y ^= y * 0xb82f1e52u;
    y ^= y * 0xc7afe638u;
    y ^= y * 0x8d22f6e6u;
    return reverseBits(y);
}

// sobol::sobol_f32
fn sobol_f32(seed: u32, index: u32, dimension: u32) -> f32 {
    let scrambled = owen_scramble(sobol_u32(index, dimension), random_u32(seed, 0xffffffffu, dimension));
    return f32(scrambled >> 8u) * (1.0 / 16777216.0);
}

// rng::dim::scatter
fn scatter_dim(band: u32, bounce: u32) -> u32 {
    return DIM_PATH + ((band + 1u) % 65536u) * DIM_PER_BAND + bounce;
}

// rng::dim::absorb
fn absorb_dim(band: u32, bounce: u32) -> u32 {
    return scatter_dim(band, bounce) + DIM_ABSORB;
}

// rng::dim::bounce: the first of a diffuse bounce's two dimensions (the
// second is DIM_ABSORB above it).
fn bounce_dim(band: u32, bounce: u32) -> u32 {
    return scatter_dim(band, bounce) + DIM_BOUNCE;
}

// rng::dim::choose: which wavelength an indirect photon goes on as at
// dispersive glass.
fn choose_dim(bounce: u32) -> u32 {
    return scatter_dim(WHITE_BAND, bounce) + DIM_CHOOSE;
}

// rng::dim::metal_part: whether a path goes on as a blended metal's specular part.
fn metal_part_dim(band: u32, bounce: u32) -> u32 {
    return scatter_dim(band, bounce) + DIM_METAL_PART;
}

// rng::dim::base_bounce: the first of the two dimensions of the diffuse
// bounce of a path a specular layer passed to its base (the second is
// DIM_ABSORB above it).
fn base_bounce_dim(band: u32, bounce: u32) -> u32 {
    return scatter_dim(band, bounce) + DIM_BASE_BOUNCE;
}

// ---- math.rs ----

// glam's normalize: v · (1 / |v|).
fn nrm(v: vec3<f32>) -> vec3<f32> {
    return v * (1.0 / sqrt(dot(v, v)));
}

// f32::copysign (the sign bit of `s`, also for -0.0).
fn copysign(x: f32, s: f32) -> f32 {
    return bitcast<f32>((bitcast<u32>(x) & 0x7fffffffu) | (bitcast<u32>(s) & 0x80000000u));
}

fn max_abs(v: vec3<f32>) -> f32 {
    return max(max(abs(v.x), abs(v.y)), abs(v.z));
}

// math::sin_cos_turns: (sin 2πu, cos 2πu) from + − × floor only.
fn sin_cos_turns(u: f32) -> vec2<f32> {
    let h = (u - floor(u + 0.5)) * PI;
    let h2 = h * h;
    let s = h * (SIN_C0 + h2 * (SIN_C1 + h2 * (SIN_C2 + h2 * (SIN_C3 + h2 * (SIN_C4 + h2 * SIN_C5)))));
    let c = COS_C0 + h2 * (COS_C1 + h2 * (COS_C2 + h2 * (COS_C3 + h2 * (COS_C4 + h2 * (COS_C5 + h2 * COS_C6)))));
    return vec2<f32>(2.0 * s * c, 1.0 - 2.0 * s * s);
}

struct Basis {
    t: vec3<f32>,
    b: vec3<f32>,
}

// geometry::basis (Duff et al. 2017).
fn basis(n: vec3<f32>) -> Basis {
    let sign = copysign(1.0, n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    return Basis(
        vec3<f32>(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        vec3<f32>(b, sign + n.y * n.y * a, -n.y),
    );
}

// Light::is_hidden: no ray can meet it (a spot, a point, a beam or a sun
// of its own; not an area light or a drawn sun).
fn light_is_hidden(l: GpuLight) -> bool {
    return l.kind != LIGHT_AREA && (l.sun == 0u || all(l.mean_toward == vec3<f32>(0.0)));
}

// spot_cone::SpotCone::measure
fn spot_measure(l: GpuLight) -> f32 {
    return (1.0 - l.cos_inner) + (l.cos_inner - l.cos_max) / 3.0;
}

// light_range::range_window: light that has travelled `distance` from a
// light of `range` (0: none).
fn range_window(distance: f32, range: f32) -> f32 {
    if range <= 0.0 {
        return 1.0;
    }
    let ratio = distance / range;
    let squared = ratio * ratio;
    return clamp(1.0 - squared * squared, 0.0, 1.0);
}

// spot_cone::SpotCone::falloff
fn spot_falloff(l: GpuLight, c: f32) -> f32 {
    if c < l.cos_max {
        return 0.0;
    }
    if c >= l.cos_inner {
        return 1.0;
    }
    let x = (c - l.cos_max) / (l.cos_inner - l.cos_max);
    return x * x;
}

// geometry::primitive::cone_direction
fn cone_direction(axis: vec3<f32>, cos_t: f32, u: f32) -> vec3<f32> {
    let sin_t = sqrt(max(1.0 - cos_t * cos_t, 0.0));
    let sc = sin_cos_turns(u);
    let tb = basis(axis);
    return nrm(tb.t * (sin_t * sc.y) + tb.b * (sin_t * sc.x) + axis * cos_t);
}

// photon::oct_pack
fn oct_pack(v: vec3<f32>) -> u32 {
    return pack2x16snorm(oct_encode(v));
}

// photon::oct_unpack
fn oct_unpack(packed: u32) -> vec3<f32> {
    return oct_decode(unpack2x16snorm(packed));
}

// photon::oct_encode
fn sign_not_zero(x: f32) -> f32 {
    return select(-1.0, 1.0, x >= 0.0);
}

fn oct_encode(v: vec3<f32>) -> vec2<f32> {
    let n = v / (abs(v.x) + abs(v.y) + abs(v.z));
    if n.z >= 0.0 {
        return n.xy;
    }
    return vec2<f32>((1.0 - abs(n.y)) * sign_not_zero(n.x), (1.0 - abs(n.x)) * sign_not_zero(n.y));
}

fn oct_decode(e: vec2<f32>) -> vec3<f32> {
    let z = 1.0 - abs(e.x) - abs(e.y);
    var xy = e;
    if z < 0.0 {
        xy = vec2<f32>((1.0 - abs(e.y)) * sign_not_zero(e.x), (1.0 - abs(e.x)) * sign_not_zero(e.y));
    }
    return nrm(vec3<f32>(xy, z));
}

// ---- optics.rs ----

fn reflect_dir(d: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    return d - n * (2.0 * dot(d, n));
}

// ---- geometry/shading.rs ----

// Triangle::barycentrics: the weights of the second and third corners at
// p, by least squares.
fn barycentrics(v0: vec3<f32>, e1: vec3<f32>, e2: vec3<f32>, p: vec3<f32>) -> vec2<f32> {
    let d = p - v0;
    let d11 = dot(e1, e1);
    let d12 = dot(e1, e2);
    let d22 = dot(e2, e2);
    let d1 = dot(d, e1);
    let d2 = dot(d, e2);
    let inv = 1.0 / (d11 * d22 - d12 * d12);
    return vec2<f32>((d22 * d1 - d12 * d2) * inv, (d11 * d2 - d12 * d1) * inv);
}

// shading_normal: the interpolated normal, bent where the ray mirrored
// about it would rise less than MIN_REFLECTED_LIFT above the triangle.
fn shading_normal(d: vec3<f32>, geometric: vec3<f32>, interpolated: vec3<f32>) -> vec3<f32> {
    if !(dot(interpolated, geometric) > 0.0) {
        return geometric;
    }
    let len = length(interpolated);
    let side = select(-1.0, 1.0, dot(d, geometric) < 0.0);
    let facing = geometric * side;
    let interpolated_unit = interpolated * (side / len);
    let mirrored = d - interpolated_unit * (2.0 * dot(d, interpolated_unit));
    let lift = dot(mirrored, facing);
    if lift >= MIN_REFLECTED_LIFT {
        return interpolated_unit * side;
    }
    let flat = mirrored - facing * lift;
    let rcp = 1.0 / length(flat);
    let along = select(facing, flat * rcp, rcp > 0.0 && rcp <= BIG);
    let lifted = along * sqrt(1.0 - MIN_REFLECTED_LIFT * MIN_REFLECTED_LIFT) + facing * MIN_REFLECTED_LIFT;
    return nrm(lifted - d) * side;
}

// normal_map::mapped_normal: the texel's tangent-space normal in the frame
// of unit normal `n` and tangent `tangent` (made perpendicular to it).
fn mapped_normal(n: vec3<f32>, tangent: vec3<f32>, sign: f32, texel: vec3<f32>, scale: f32) -> vec3<f32> {
    let across = tangent - n * dot(n, tangent);
    let across_len = length(across);
    if !(across_len > MIN_TANGENT_SHARE * length(tangent)) {
        return n;
    }
    let t = across / across_len;
    let b = cross(n, t) * sign;
    let m = texel * 2.0 - vec3<f32>(1.0);
    let mapped = t * (m.x * scale) + b * (m.y * scale) + n * m.z;
    let mapped_len = length(mapped);
    if !(mapped_len > MIN_MAPPED_LENGTH) {
        return n;
    }
    return mapped / mapped_len;
}

fn cos2_transmitted(cos_i: f32, n1: f32, n2: f32) -> f32 {
    let eta = n1 / n2;
    return (n2 - n1) * (n2 + n1) / (n2 * n2) + eta * eta * cos_i * cos_i;
}

fn fresnel(cos_in: f32, n1: f32, n2: f32) -> f32 {
    if n1 == n2 {
        return 0.0;
    }
    let cos_i = clamp(cos_in, 0.0, 1.0);
    let cos2_t = cos2_transmitted(cos_i, n1, n2);
    if cos2_t <= 0.0 {
        return 1.0;
    }
    let cos_t = sqrt(cos2_t);
    let rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
    let rp = (n1 * cos_t - n2 * cos_i) / (n1 * cos_t + n2 * cos_i);
    return clamp(0.5 * (rs * rs + rp * rp), 0.0, 1.0);
}

// optics::refract; w = 0 on total internal reflection.
fn refract_dir(d: vec3<f32>, n: vec3<f32>, n1: f32, n2: f32) -> vec4<f32> {
    let eta = n1 / n2;
    let cos_i = clamp(-dot(d, n), 0.0, 1.0);
    let cos2_t = cos2_transmitted(cos_i, n1, n2);
    if cos2_t < 0.0 {
        return vec4<f32>(0.0);
    }
    let cos_t = sqrt(cos2_t);
    return vec4<f32>(nrm(d * eta + n * (eta * cos_i - cos_t)), 1.0);
}

// optics::interface: the normal facing the ray and (n_incident, n_transmitted).
struct Interface {
    n: vec3<f32>,
    n1: f32,
    n2: f32,
}

fn facing_interface(d: vec3<f32>, outward: vec3<f32>, ior: f32) -> Interface {
    if dot(d, outward) < 0.0 {
        return Interface(outward, 1.0, ior);
    }
    return Interface(-outward, ior, 1.0);
}

// ---- gather.rs ----

// gather::finish: caustic irradiance from a gather's sums within `radius`
// (`estimator` as Params encodes it, `band_count` bands).
fn finish_estimate(estimator: u32, band_count: u32, sums: vec3<f32>, total: u32, flux: f32, radius: f32) -> vec3<f32> {
    let area = PI * radius * radius;
    if estimator == ESTIMATOR_DENSITY {
        return sums / area;
    }
    if total == 0u {
        return vec3<f32>(0.0);
    }
    return sums * (f32(band_count) / f32(total)) * (flux / area);
}

// tolerance::surface_offset and optics::scatter::offset_origin
fn surface_offset(p: vec3<f32>) -> f32 {
    return SURFACE_OFFSET_ABS + SURFACE_OFFSET_REL * max_abs(p);
}

fn offset_origin(p: vec3<f32>, n: vec3<f32>, dir: vec3<f32>) -> vec3<f32> {
    let eps = surface_offset(p);
    if dot(dir, n) >= 0.0 {
        return p + n * eps;
    }
    return p - n * eps;
}

// ---- optics/scatter.rs: the one branch choice at glass ----

// A ray leaving a surface.
struct Scattered {
    origin: vec3<f32>,
    dir: vec3<f32>,
}

// optics::fresnel::sheet_reflectance: both faces of a thin sheet and what
// bounces between them.
fn sheet_reflectance(r: f32) -> f32 {
    return 2.0 * r / (1.0 + r);
}

// ---- optics/thin_film.rs: complex numbers as vec2 (re, im) ----

fn c_mul(a: vec2<f32>, b: vec2<f32>) -> vec2<f32> {
    return vec2<f32>(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x);
}

fn c_div(a: vec2<f32>, b: vec2<f32>) -> vec2<f32> {
    let d = b.x * b.x + b.y * b.y;
    return vec2<f32>((a.x * b.x + a.y * b.y) / d, (a.y * b.x - a.x * b.y) / d);
}

// Complex::sqrt_of: √x of a real x, or i√−x (the root whose wave decays).
fn c_sqrt_of(x: f32) -> vec2<f32> {
    if x >= 0.0 {
        return vec2<f32>(sqrt(x), 0.0);
    }
    return vec2<f32>(0.0, sqrt(-x));
}

// Complex::exp_i: e^{i z}.
fn c_exp_i(z: vec2<f32>) -> vec2<f32> {
    let sc = sin_cos_turns(z.x * (0.5 / PI));
    let decay = exp(-z.y);
    return vec2<f32>(decay * sc.y, decay * sc.x);
}

// The Airy sum |(r01 + r12 e^{iδ}) / (1 + r01 r12 e^{iδ})|².
fn airy(r01: vec2<f32>, r12: vec2<f32>, phase: vec2<f32>) -> f32 {
    let r = c_div(r01 + c_mul(r12, phase), vec2<f32>(1.0, 0.0) + c_mul(c_mul(r01, r12), phase));
    return r.x * r.x + r.y * r.y;
}

// ThinFilm::reflectance: a film of index n1, thickness d_nm and factor
// `factor` between n0 and a base n2, at wavelength lambda_nm.
fn thin_film_reflectance(cos_in: f32, n0: f32, n1: f32, n2: f32, d_nm: f32, factor: f32, lambda_nm: f32) -> f32 {
    return thin_film_on(cos_in, n0, n1, vec2<f32>(n2, 0.0), d_nm, factor, lambda_nm);
}

// Complex::sqrt: the principal root (on the negative real axis i√−x).
fn c_sqrt(z: vec2<f32>) -> vec2<f32> {
    let r = sqrt(z.x * z.x + z.y * z.y);
    let re = sqrt(0.5 * max(r + z.x, 0.0));
    let im = sqrt(0.5 * max(r - z.x, 0.0));
    return vec2<f32>(re, select(im, -im, z.y < 0.0));
}

// The amplitudes between media (na, qa) and (nb, qb), q = n cos θ (complex
// n for an absorbing base): s (qa − qb)/(qa + qb), p (nb² qa − na² qb)/(nb² qa + na² qb).
fn amplitude_s(qa: vec2<f32>, qb: vec2<f32>) -> vec2<f32> {
    return c_div(qa - qb, qa + qb);
}

fn amplitude_p(na: vec2<f32>, qa: vec2<f32>, nb: vec2<f32>, qb: vec2<f32>) -> vec2<f32> {
    let a = c_mul(c_mul(nb, nb), qa);
    let b = c_mul(c_mul(na, na), qb);
    return c_div(a - b, a + b);
}

// ThinFilm::reflectance_on: the film over a base of complex index base =
// (n2, k2); below a factor of 1, mixed with the bare base's Fresnel.
fn thin_film_on(cos_in: f32, n0: f32, n1: f32, base: vec2<f32>, d_nm: f32, factor: f32, lambda_nm: f32) -> f32 {
    let cos0 = clamp(cos_in, 0.0, 1.0);
    let sin2 = 1.0 - cos0 * cos0;
    let c1 = c_sqrt_of(1.0 - (n0 / n1) * (n0 / n1) * sin2);
    let q2 = c_sqrt(c_mul(base, base) - vec2<f32>(n0 * n0 * sin2, 0.0));
    let phase = c_exp_i(c1 * (4.0 * PI * n1 * d_nm / lambda_nm));
    let top = vec2<f32>(n0, 0.0);
    let film = vec2<f32>(n1, 0.0);
    let q0 = vec2<f32>(n0 * cos0, 0.0);
    let q1 = c1 * n1;
    let rs = airy(amplitude_s(q0, q1), amplitude_s(q1, q2), phase);
    let rp = airy(amplitude_p(top, q0, film, q1), amplitude_p(film, q1, base, q2), phase);
    var r = 0.5 * (rs + rp);
    if factor < 1.0 {
        let s0 = amplitude_s(q0, q2);
        let p0 = amplitude_p(top, q0, base, q2);
        let bare = 0.5 * (dot(s0, s0) + dot(p0, p0));
        r = bare + (r - bare) * factor;
    }
    return clamp(r, 0.0, 1.0);
}

// optics::scatter::Face: what a path meets at glass (film_nm = 0: no film).
struct Face {
    ior: f32,
    thin: bool,
    film_ior: f32,
    film_nm: f32,
    film_factor: f32,
    lambda_nm: f32,
}

// Face::bare.
fn bare_face(ior: f32, thin: bool) -> Face {
    return Face(ior, thin, 1.0, 0.0, 1.0, 0.0);
}

// Face::interface_reflectance: Fresnel's, or the film's Airy sum.
fn interface_reflectance(f: Face, cos_i: f32, n1: f32, n2: f32) -> f32 {
    if f.film_nm > 0.0 {
        return thin_film_reflectance(cos_i, n1, f.film_ior, n2, f.film_nm, f.film_factor, f.lambda_nm);
    }
    return fresnel(cos_i, n1, n2);
}

// Face::reflectance (a sheet: both faces).
fn face_reflectance(f: Face, cos_i: f32, n1: f32, n2: f32) -> f32 {
    if f.thin {
        return sheet_reflectance(interface_reflectance(f, cos_i, 1.0, f.ior));
    }
    return interface_reflectance(f, cos_i, n1, n2);
}

// optics::scatter::scatter_dielectric: reflected where u < R or under total
// internal reflection, refracted otherwise (a thin sheet: straight on);
// photons and sampled view paths.
fn scatter_dielectric(d: vec3<f32>, point: vec3<f32>, outward: vec3<f32>, face: Face, u: f32) -> Scattered {
    let f = facing_interface(d, outward, face.ior);
    let cos_i = -dot(d, f.n);
    var out = reflect_dir(d, f.n);
    if !(u < face_reflectance(face, cos_i, f.n1, f.n2)) {
        if face.thin {
            out = d;
        } else {
            let r = refract_dir(d, f.n, f.n1, f.n2);
            if r.w != 0.0 {
                out = r.xyz;
            }
        }
    }
    return Scattered(offset_origin(point, f.n, out), out);
}

// optics::scatter::scatter_diffuse: Lambert's law on the side the ray
// came from; indirect light's photons.
fn scatter_diffuse(d: vec3<f32>, point: vec3<f32>, normal: vec3<f32>, u1: f32, u2: f32) -> Scattered {
    let n = select(-normal, normal, dot(d, normal) < 0.0);
    let out = cone_direction(n, sqrt(1.0 - u1), u2);
    return Scattered(offset_origin(point, n, out), out);
}

// optics::scatter::split_dielectric: both branches with their Fresnel
// weights (R reflected; 1 - R refracted unless `tir`), for view rays that
// follow both.
struct DielectricBranches {
    reflected: Scattered,
    reflectance: f32,
    refracted: Scattered,
    tir: bool,
}

fn split_dielectric(d: vec3<f32>, point: vec3<f32>, outward: vec3<f32>, face: Face) -> DielectricBranches {
    let f = facing_interface(d, outward, face.ior);
    let cos_i = -dot(d, f.n);
    let reflectance = face_reflectance(face, cos_i, f.n1, f.n2);
    var t = refract_dir(d, f.n, f.n1, f.n2);
    if face.thin {
        t = vec4<f32>(d, 1.0);
    }
    let r = reflect_dir(d, f.n);
    let reflected = Scattered(offset_origin(point, f.n, r), r);
    let refracted = Scattered(offset_origin(point, f.n, t.xyz), t.xyz);
    return DielectricBranches(reflected, reflectance, refracted, t.w == 0.0);
}

// PixelSampler::facet: the two numbers of the rough metal's facet that
// hero path `path` reflects off at specular bounce `depth`.
fn pixel_facet(scramble: u32, pass_index: u32, path: u32, depth: u32) -> vec2<f32> {
    let d = VIEW_FACET + 2u * (path * VIEW_PER_PATH + depth);
    return vec2<f32>(random_f32(scramble, pass_index, d), random_f32(scramble, pass_index, d + 1u));
}

// PixelSampler::branch: the number that chooses the Fresnel branch of hero
// path `path` (0 before the split) at specular bounce `depth`.
fn pixel_branch(scramble: u32, pass_index: u32, path: u32, depth: u32) -> f32 {
    return random_f32(scramble, pass_index, VIEW_BRANCH + path * VIEW_PER_PATH + depth);
}

// grid::cell_of: the integer cell of `p` (float → int conversions saturate).
fn cell_of(p: vec3<f32>, inv_cell: f32) -> vec3<i32> {
    return vec3<i32>(floor(p * inv_cell));
}

// grid::bucket_of (Teschner et al. primes, wrapping u32 arithmetic).
fn bucket_of(c: vec3<i32>, mask: u32) -> u32 {
    return ((bitcast<u32>(c.x) * 73856093u) ^ (bitcast<u32>(c.y) * 19349663u) ^ (bitcast<u32>(c.z) * 83492791u)) & mask;
}

// Flattens a 2D dispatch (workgroups beyond the per-dimension limit wrap
// into y) into one invocation index.
fn flat_index(wid: vec3<u32>, nwg: vec3<u32>, lid: u32) -> u32 {
    return (wid.y * nwg.x + wid.x) * WORKGROUP_SIZE + lid;
}

// ---- metal.rs and microfacet.rs ----

// MetalOptics::fresnel: Schlick's per RGB channel at facet cosine `c`.
fn metal_fresnel(f0: vec3<f32>, c: f32) -> vec3<f32> {
    let x = 1.0 - clamp(c, 0.0, 1.0);
    let x2 = x * x;
    return f0 + (vec3<f32>(1.0) - f0) * (x2 * x2 * x);
}

// SpecularLayer::fresnel: Schlick's from `f0` to `f90` at facet cosine `c`.
fn layer_schlick(f0: vec3<f32>, f90: f32, c: f32) -> vec3<f32> {
    let x = 1.0 - clamp(c, 0.0, 1.0);
    let x2 = x * x;
    return f0 + (vec3<f32>(f90) - f0) * (x2 * x2 * x);
}

// microfacet::conductor_fresnel: the unpolarised reflectance of a
// conductor of complex index `eta` + i`k` at incidence cosine `cos_i`.
fn conductor_fresnel(cos_i: f32, eta: f32, k: f32) -> f32 {
    let c = clamp(cos_i, 0.0, 1.0);
    let c2 = c * c;
    let s2 = 1.0 - c * c;
    let t0 = eta * eta - k * k - s2;
    let a2b2 = sqrt(t0 * t0 + 4.0 * eta * eta * k * k);
    let a = sqrt(max(0.5 * (a2b2 + t0), 0.0));
    let rs = (a2b2 + c2 - 2.0 * a * c) / (a2b2 + c2 + 2.0 * a * c);
    let rp = rs * (c2 * a2b2 + s2 * s2 - 2.0 * a * c * s2) / (c2 * a2b2 + s2 * s2 + 2.0 * a * c * s2);
    return clamp(0.5 * (rs + rp), 0.0, 1.0);
}

// Ggx::lambda: Smith's Λ for GGX of width `alpha` of a direction at
// cosine `c` to the normal (a huge number for the core's infinity below
// the horizon).
fn ggx_lambda(alpha: f32, c: f32) -> f32 {
    let c2 = c * c;
    if c2 <= 0.0 {
        return 3.0e38;
    }
    let a2_tan2 = alpha * alpha * max(1.0 - c2, 0.0) / c2;
    return 0.5 * a2_tan2 / (1.0 + sqrt(1.0 + a2_tan2));
}

// Ggx::sample_visible_normal (Heitz 2018): a normal among those `wo` sees.
fn ggx_visible_normal(alpha: f32, wo: vec3<f32>, u1: f32, u2: f32) -> vec3<f32> {
    let vh = nrm(vec3<f32>(alpha * wo.x, alpha * wo.y, wo.z));
    let len2 = vh.x * vh.x + vh.y * vh.y;
    var t1 = vec3<f32>(1.0, 0.0, 0.0);
    if len2 > 0.0 {
        t1 = vec3<f32>(-vh.y, vh.x, 0.0) / sqrt(len2);
    }
    let t2 = cross(vh, t1);
    let r = sqrt(u1);
    let sc = sin_cos_turns(u2);
    let p1 = r * sc.y;
    let s = 0.5 * (1.0 + vh.z);
    let p2 = (1.0 - s) * sqrt(max(1.0 - p1 * p1, 0.0)) + s * r * sc.x;
    let nh = t1 * p1 + t2 * p2 + vh * sqrt(max(1.0 - p1 * p1 - p2 * p2, 0.0));
    return nrm(vec3<f32>(alpha * nh.x, alpha * nh.y, max(nh.z, 0.0)));
}

// scatter::MetalBounce (`ok` false: the path ends).
struct MetalBounce {
    ok: bool,
    origin: vec3<f32>,
    dir: vec3<f32>,
    cos_facet: f32,
    unshadowed: f32,
}

// scatter::scatter_metal: the reflection off a metal of GGX width `alpha`
// (0: polished, the mirror direction) at `point` for a ray along `d`.
fn scatter_metal(d: vec3<f32>, point: vec3<f32>, normal: vec3<f32>, alpha: f32, u1: f32, u2: f32) -> MetalBounce {
    let n = select(-normal, normal, dot(d, normal) < 0.0);
    let none = MetalBounce(false, point, d, 0.0, 0.0);
    if alpha <= 0.0 {
        let r = reflect_dir(d, n);
        return MetalBounce(true, offset_origin(point, n, r), r, -dot(d, n), 1.0);
    }
    let f = basis(n);
    let local = vec3<f32>(dot(-d, f.t), dot(-d, f.b), dot(-d, n));
    if local.z <= 0.0 {
        return none;
    }
    let m = ggx_visible_normal(alpha, local, u1, u2);
    let wi = m * (2.0 * dot(local, m)) - local;
    if wi.z <= 0.0 {
        return none;
    }
    // Ggx::sample_reflection's weight G2/G1 (both directions above the surface).
    let lo = ggx_lambda(alpha, local.z);
    let unshadowed = (1.0 + lo) / (1.0 + lo + ggx_lambda(alpha, wi.z));
    let dir = nrm(f.t * wi.x + f.b * wi.y + n * wi.z);
    return MetalBounce(true, offset_origin(point, n, dir), dir, dot(local, nrm(local + wi)), unshadowed);
}

// Ggx::d: the density of facet normals at cosine `c` to the normal.
fn ggx_d(alpha: f32, c: f32) -> f32 {
    if c <= 0.0 {
        return 0.0;
    }
    let a2 = alpha * alpha;
    let t = c * c * (a2 - 1.0) + 1.0;
    return a2 / (PI * t * t);
}

// Ggx::reflection for facets that reflect 1, from `wi` toward `wo` about
// the normal `n`: D G2 / (4 cos θo cos θi), zero unless both are above it.
fn ggx_reflection(alpha: f32, wo: vec3<f32>, wi: vec3<f32>, n: vec3<f32>) -> f32 {
    let co = dot(wo, n);
    let ci = dot(wi, n);
    if co <= 0.0 || ci <= 0.0 {
        return 0.0;
    }
    let g2 = 1.0 / (1.0 + ggx_lambda(alpha, co) + ggx_lambda(alpha, ci));
    return ggx_d(alpha, dot(nrm(wo + wi), n)) * g2 / (4.0 * co * ci);
}


// ---- rough glass (scatter.rs, rough_glass.rs) ----

// The largest f32 below 1 (scatter::ONE_BELOW).
const ONE_BELOW: f32 = 0.99999994;

// scatter::Facet: where a ray meets one facet of rough glass (`through.w`
// 0: totally internally reflected).
struct GlassFacet {
    n: vec3<f32>,
    reflectance: f32,
    reflected: vec3<f32>,
    through: vec4<f32>,
}

// scatter::Facet::draw: the facet a ray along `d` meets, drawn from the
// visible normals of GGX width `alpha` by `u`.
fn glass_facet(d: vec3<f32>, outward: vec3<f32>, face: Face, alpha: f32, u: vec2<f32>) -> GlassFacet {
    let f = facing_interface(d, outward, face.ior);
    let bs = basis(f.n);
    let wo = vec3<f32>(-dot(d, bs.t), -dot(d, bs.b), -dot(d, f.n));
    let ml = ggx_visible_normal(alpha, wo, u.x, u.y);
    let m = nrm(bs.t * ml.x + bs.b * ml.y + f.n * ml.z);
    let reflectance = face_reflectance(face, clamp(-dot(d, m), 0.0, 1.0), f.n1, f.n2);
    let reflected = reflect_dir(d, m);
    var through = refract_dir(d, m, f.n1, f.n2);
    if face.thin {
        // A sheet: the facet's reflection mirrored through the surface.
        through = vec4<f32>(reflected - f.n * (2.0 * dot(reflected, f.n)), 1.0);
    }
    return GlassFacet(f.n, reflectance, reflected, through);
}

// scatter::Facet::unshadowed: G2/G1 of a ray leaving along `out`, or -1
// where it leaves on the wrong side (the path ends).
fn glass_unshadowed(alpha: f32, n: vec3<f32>, d: vec3<f32>, out: vec3<f32>, crossed: bool) -> f32 {
    let cos_o = -dot(d, n);
    let cos_i = dot(out, n);
    if cos_o <= 0.0 || cos_i == 0.0 || (cos_i < 0.0) != crossed {
        return -1.0;
    }
    let lo = ggx_lambda(alpha, cos_o);
    return (1.0 + lo) / (1.0 + lo + ggx_lambda(alpha, cos_i));
}

// scatter::GlassBounce (`ok` false: the path ends).
struct GlassBounce {
    ok: bool,
    origin: vec3<f32>,
    dir: vec3<f32>,
    unshadowed: f32,
    crossed: bool,
    leftover: f32,
}

// scatter::scatter_rough_dielectric: Fresnel's choice (`u`) off the facet
// `facet` draws, at the path's own index.
fn scatter_rough_dielectric(d: vec3<f32>, point: vec3<f32>, outward: vec3<f32>, face: Face, alpha: f32, facet: vec2<f32>, u: f32) -> GlassBounce {
    let f = glass_facet(d, outward, face, alpha, facet);
    let r = f.reflectance;
    var out = f.reflected;
    var crossed = false;
    var leftover = 0.0;
    if f.through.w != 0.0 && u >= r {
        out = f.through.xyz;
        crossed = true;
        leftover = (u - r) / (1.0 - r);
    } else {
        leftover = u / r;
    }
    let unshadowed = glass_unshadowed(alpha, f.n, d, out, crossed);
    if unshadowed < 0.0 {
        return GlassBounce(false, point, d, 0.0, false, 0.0);
    }
    return GlassBounce(true, offset_origin(point, f.n, out), out, unshadowed, crossed, min(leftover, ONE_BELOW));
}

// scatter::RoughBranches: each branch's ray and weight (< 0: none).
struct RoughBranches {
    reflected: Scattered,
    reflected_weight: f32,
    crossed: Scattered,
    crossed_weight: f32,
}

// scatter::split_rough_dielectric: both branches off the facet `facet` draws.
fn split_rough_dielectric(d: vec3<f32>, point: vec3<f32>, outward: vec3<f32>, face: Face, alpha: f32, facet: vec2<f32>) -> RoughBranches {
    let f = glass_facet(d, outward, face, alpha, facet);
    var r = 1.0;
    if f.through.w != 0.0 {
        r = f.reflectance;
    }
    var reflected_weight = -1.0;
    let ur = glass_unshadowed(alpha, f.n, d, f.reflected, false);
    if ur >= 0.0 {
        reflected_weight = r * ur;
    }
    var crossed_weight = -1.0;
    if f.through.w != 0.0 {
        let uc = glass_unshadowed(alpha, f.n, d, f.through.xyz, true);
        if uc >= 0.0 {
            crossed_weight = (1.0 - r) * uc;
        }
    }
    let reflected = Scattered(offset_origin(point, f.n, f.reflected), f.reflected);
    let crossed = Scattered(offset_origin(point, f.n, f.through.xyz), f.through.xyz);
    return RoughBranches(reflected, reflected_weight, crossed, crossed_weight);
}

// rough_glass::rough_glass_bsdf: what rough glass (GGX width `alpha`)
// sends toward `wo` of light from `wi`: reflection off its facets, or
// transmission through them (Walter et al. 2007; a sheet: the reflection
// mirrored through the surface).
fn rough_glass_bsdf(wo: vec3<f32>, wi: vec3<f32>, outward: vec3<f32>, face: Face, alpha: f32) -> f32 {
    let f = facing_interface(-wo, outward, face.ior);
    let bs = basis(f.n);
    let o = vec3<f32>(dot(wo, bs.t), dot(wo, bs.b), dot(wo, f.n));
    let i = vec3<f32>(dot(wi, bs.t), dot(wi, bs.b), dot(wi, f.n));
    if o.z <= 0.0 || i.z == 0.0 {
        return 0.0;
    }
    let z = vec3<f32>(0.0, 0.0, 1.0);
    if i.z > 0.0 {
        let m = nrm(o + i);
        return ggx_reflection(alpha, o, i, z) * face_reflectance(face, clamp(dot(o, m), 0.0, 1.0), f.n1, f.n2);
    }
    if face.thin {
        let mirrored = vec3<f32>(i.x, i.y, -i.z);
        let m = nrm(o + mirrored);
        return ggx_reflection(alpha, o, mirrored, z) * (1.0 - face_reflectance(face, clamp(dot(o, m), 0.0, 1.0), f.n1, f.n2));
    }
    // Ggx::refraction_normal and Ggx::transmission.
    let eta = f.n2 / f.n1;
    let h = o + i * eta;
    if dot(h, h) == 0.0 {
        return 0.0;
    }
    let m = nrm(select(h, -h, h.z < 0.0));
    let om = dot(o, m);
    let im = dot(i, m);
    if !(om > 0.0 && im < 0.0) {
        return 0.0;
    }
    let t = 1.0 - face_reflectance(face, clamp(om, 0.0, 1.0), f.n1, f.n2);
    let den = om + eta * im;
    let g2 = 1.0 / (1.0 + ggx_lambda(alpha, o.z) + ggx_lambda(alpha, i.z));
    return om * abs(im) / (o.z * abs(i.z)) * eta * eta * t * ggx_d(alpha, m.z) * g2 / (den * den);
}
