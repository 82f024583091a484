// Photon emission: twin of prismatic_core::emit, sobol::photon_f32 and
// prismatic_core::projection::Projection::sample.

struct Emitted {
    origin: vec3<f32>,
    direction: vec3<f32>,
    light: u32,
    weight: f32,
}

fn pick(first: u32, count: u32, u: f32) -> u32 {
    for (var i = 0u; i < count; i++) {
        if u < tables[first + i] {
            return i;
        }
    }
    return count - 1u;
}

fn projected(l: GpuLight, u_target: f32, u1: f32, u2: f32) -> Emitted {
    if l.proj_count == 0u {
        return Emitted(vec3<f32>(0.0), vec3<f32>(0.0, 0.0, 1.0), 0u, 0.0);
    }
    let j = pick(l.proj_cdf, l.proj_count, u_target);
    let target_ = geometry[l.proj_first + j];
    if l.proj_kind == PROJECTION_CONES {
        let cos_t = 1.0 - u1 * (1.0 - target_.w);
        let d = cone_direction(target_.xyz, cos_t, u2);
        // The light's density there over a uniform cone's (a spot's soft edge).
        var density = 1.0;
        if l.kind == LIGHT_SPOT {
            density = spot_falloff(l, dot(d, l.axis)) * ((1.0 - l.cos_max) / spot_measure(l));
        } else if l.kind == LIGHT_BEAM {
            density = 0.0;
        }
        var covering = 0u;
        for (var i = 0u; i < l.proj_count; i++) {
            let c = geometry[l.proj_first + i];
            if dot(d, c.xyz) >= c.w {
                covering++;
            }
        }
        return Emitted(l.position, d, 0u, select(0.0, l.proj_scale / f32(max(covering, 1u)), density > 0.0) * density);
    }
    // Discs on the beam's emitting plane.
    let r = target_.w * sqrt(u1);
    let sc = sin_cos_turns(u2);
    let origin = target_.xyz + (l.tangent * sc.y + l.bitangent * sc.x) * r;
    let off = origin - l.position;
    let inside = dot(off, off) <= l.radius * l.radius;
    var covering = 0u;
    for (var i = 0u; i < l.proj_count; i++) {
        let c = geometry[l.proj_first + i];
        let e = origin - c.xyz;
        if dot(e, e) <= c.w * c.w {
            covering++;
        }
    }
    return Emitted(origin, l.axis, 0u, select(0.0, l.proj_scale / f32(max(covering, 1u)), inside));
}

// projection::sphere_cone: the cone of sphere `s` (centre, radius) seen
// from `p`: unit axis and 1 − cos of its half-angle.
fn sphere_cone(p: vec3<f32>, s: vec4<f32>) -> vec4<f32> {
    let to = s.xyz - p;
    let d = sqrt(dot(to, to));
    let s2 = (s.w / d) * (s.w / d);
    return vec4<f32>(to / d, s2 / (1.0 + sqrt(1.0 - s2)));
}

// emit::area_origin
fn area_origin(l: GpuLight, seed: u32, index: u32) -> vec3<f32> {
    let s = sqrt(random_f32(seed, index, DIM_AREA));
    let w2 = random_f32(seed, index, DIM_AREA + 1u);
    let point = l.position + l.tangent * (s * (1.0 - w2)) + l.bitangent * (s * w2);
    return offset_origin(point, l.axis, l.axis);
}

// Projection::sample_area (a sphere's probability follows the CDF in the tables).
fn aimed_from_area(l: GpuLight, origin: vec3<f32>, u_target: f32, u1: f32, u2: f32) -> Emitted {
    let j = pick(l.proj_cdf, l.proj_count, u_target);
    let cone = sphere_cone(origin, geometry[l.proj_first + j]);
    let d = cone_direction(cone.xyz, 1.0 - u1 * cone.w, u2);
    var density = 0.0;
    for (var k = 0u; k < l.proj_count; k++) {
        let c = sphere_cone(origin, geometry[l.proj_first + k]);
        if dot(d, c.xyz) >= 1.0 - c.w {
            density += tables[l.proj_cdf + l.proj_count + k] / (2.0 * PI * c.w);
        }
    }
    let cos_n = dot(d, l.axis);
    var weight = 0.0;
    if cos_n > 0.0 && density > 0.0 {
        weight = cos_n / PI / density;
    }
    return Emitted(origin, d, 0u, weight);
}

// spot_cone::SpotCone::sample_cos
fn spot_cos(l: GpuLight, u: f32) -> f32 {
    let t = u * spot_measure(l);
    let core = 1.0 - l.cos_inner;
    if t <= core {
        return 1.0 - t;
    }
    let w = l.cos_inner - l.cos_max;
    return l.cos_max + w * pow(max(1.0 - 3.0 * (t - core) / w, 0.0), 1.0 / 3.0);
}

// sobol::photon_f32 (sobol::sobol_dimension inlined).
fn photon_f32(seed: u32, index: u32, dimension: u32) -> f32 {
    if params.photon_sequence == SEQUENCE_SOBOL {
        if dimension == DIM_DIRECTION || dimension == DIM_DIRECTION + 1u {
            return sobol_f32(seed, index, dimension - DIM_DIRECTION);
        }
        if dimension == DIM_SPECTRUM {
            return sobol_f32(seed, index, 2u);
        }
    }
    return random_f32(seed, index, dimension);
}

// emit::emit: white photon `index` of the pass.
fn emit(seed: u32, index: u32) -> Emitted {
    return emit_from(seed, index, true);
}

// emit::emit_with: photon `index`, aimed by its light's projection map
// (caustic photons) or not (emit::emit_unaimed, indirect light's).
fn emit_from(seed: u32, index: u32, aimed: bool) -> Emitted {
    let u = random_f32(seed, index, DIM_LIGHT);
    let light = pick(params.light_cdf, params.light_count, u);
    let l = lights[light];
    // The light's own sample: a direction, or a point on a beam's disc.
    let u1 = photon_f32(seed, index, DIM_DIRECTION);
    let u2 = photon_f32(seed, index, DIM_DIRECTION + 1u);
    if aimed && l.proj_kind != PROJECTION_NONE {
        let u_target = random_f32(seed, index, DIM_TARGET);
        var e: Emitted;
        if l.kind == LIGHT_AREA {
            e = aimed_from_area(l, area_origin(l, seed, index), u_target, u1, u2);
        } else {
            e = projected(l, u_target, u1, u2);
        }
        e.light = light;
        return e;
    }
    if l.kind == LIGHT_SPOT {
        return Emitted(l.position, cone_direction(l.axis, spot_cos(l, u1), u2), light, 1.0);
    }
    if l.kind == LIGHT_AREA {
        // A cosine-weighted direction out of its front.
        return Emitted(area_origin(l, seed, index), cone_direction(l.axis, sqrt(1.0 - u1), u2), light, 1.0);
    }
    if l.kind == LIGHT_POINT {
        let z = 1.0 - 2.0 * u1;
        let r = sqrt(max(1.0 - z * z, 0.0));
        let sc = sin_cos_turns(u2);
        return Emitted(l.position, vec3<f32>(r * sc.y, r * sc.x, z), light, 1.0);
    }
    let r = l.radius * sqrt(u1);
    let sc = sin_cos_turns(u2);
    let origin = l.position + (l.tangent * sc.y + l.bitangent * sc.x) * r;
    return Emitted(origin, l.axis, light, 1.0);
}
