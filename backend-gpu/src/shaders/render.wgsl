// Ray tracing and gather: twin of prismatic_core::render and
// prismatic_core::gather. One invocation per pixel. WGSL has no recursion,
// so the reference's recursion becomes a stack of pending rays, each with
// the RGB tint and the weight it carries back to the pixel (as the CPU
// backend's queue does); the split of a white view ray into bands is a
// stack entry that hands out one band at a time, which keeps the stack at
// two entries per depth.

@group(1) @binding(0) var<storage, read> cells: array<u32>;
@group(1) @binding(1) var<storage, read_write> pixels: array<vec4<f32>>;

struct Pending {
    origin: vec3<f32>,
    weight: f32,
    dir: vec3<f32>,
    band: u32,
    tint: vec3<f32>,
    depth: u32,
    // For a band split: the glass's outward normal at `origin` (the hit point).
    normal: vec3<f32>,
    // NO_SPLIT for a ray to trace, else the next band to hand out.
    next_band: u32,
    object: u32,
}

const NO_SPLIT: u32 = 0xffffffffu;

var<private> stack: array<Pending, STACK_SIZE>;
var<private> top: u32;

fn push(e: Pending) {
    if top < STACK_SIZE {
        stack[top] = e;
        top++;
    }
}

fn push_ray(origin: vec3<f32>, dir: vec3<f32>, band: u32, depth: u32, weight: f32, tint: vec3<f32>) {
    push(Pending(origin, weight, dir, band, tint, depth, vec3<f32>(0.0), NO_SPLIT, 0u));
}

// RenderContext::through_dielectric: the Fresnel-weighted reflection and refraction.
fn through_dielectric(e: Pending, ior: f32, band: u32, weight: f32, tint: vec3<f32>) {
    let f = facing_interface(e.dir, e.normal, ior);
    let cos_i = -dot(e.dir, f.n);
    let r = fresnel(cos_i, f.n1, f.n2);
    let t = 1.0 - r;
    if t * weight > MIN_VIEW_WEIGHT {
        let d = refract_dir(e.dir, f.n, f.n1, f.n2);
        if d.w != 0.0 {
            push_ray(offset_origin(e.origin, f.n, d.xyz), d.xyz, band, e.depth + 1u, weight * t, tint * t);
        }
    }
    if r * weight > MIN_VIEW_WEIGHT {
        let d = reflect_dir(e.dir, f.n);
        push_ray(offset_origin(e.origin, f.n, d), d, band, e.depth + 1u, weight * r, tint * r);
    }
}

// Surface::albedo_at (checker evaluated a hair below the surface).
fn albedo_at(s: GpuSurface, p: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    if (s.flags & SURFACE_HAS_CHECKER) == 0u {
        return s.albedo;
    }
    let q = (p + s.checker_offset - n * (s.checker_size * 1e-3)) / s.checker_size;
    let parity = floor(q.x) + floor(q.y) + floor(q.z);
    if parity - 2.0 * floor(parity * 0.5) == 0.0 {
        return s.albedo;
    }
    return s.checker_albedo;
}

// Direction to a point light, distance and surface cosine (w < 0: not lit).
fn visible_point(light: vec3<f32>, p: vec3<f32>, n: vec3<f32>, shadows: bool) -> vec4<f32> {
    let to = light - p;
    let dist = length(to);
    let l = to / dist;
    let cos_s = dot(l, n);
    if cos_s <= 0.0 {
        return vec4<f32>(0.0, 0.0, 0.0, -1.0);
    }
    if shadows {
        let origin = offset_origin(p, n, l);
        if occluded(origin, l, length(light - origin)) {
            return vec4<f32>(0.0, 0.0, 0.0, -1.0);
        }
    }
    return vec4<f32>(l, dist);
}

// RenderContext::direct_irradiance
fn direct_irradiance(l: GpuLight, p: vec3<f32>, n: vec3<f32>) -> f32 {
    let shadows = l.shadows != 0u;
    if l.kind == LIGHT_BEAM {
        let along = dot(p - l.position, l.axis);
        let cos_s = -dot(l.axis, n);
        if along <= 0.0 || cos_s <= 0.0 || length(p - l.position - l.axis * along) > l.radius {
            return 0.0;
        }
        if shadows && occluded(offset_origin(p, n, -l.axis), -l.axis, along) {
            return 0.0;
        }
        return l.power / (PI * l.radius * l.radius) * cos_s;
    }
    let v = visible_point(l.position, p, n, shadows);
    if v.w < 0.0 {
        return 0.0;
    }
    let cos_s = dot(v.xyz, n);
    let dist = v.w;
    if l.kind == LIGHT_SPOT {
        if dot(-v.xyz, l.axis) < l.cos_max {
            return 0.0;
        }
        let intensity = l.power / (2.0 * PI * (1.0 - l.cos_max));
        return intensity * cos_s / (dist * dist);
    }
    return l.power / (4.0 * PI) * cos_s / (dist * dist);
}

fn step_limit(lo: i32, hi: i32) -> i32 {
    // hi.min(lo.saturating_add(1))
    if lo == 2147483647 {
        return lo;
    }
    return min(hi, lo + 1);
}

// gather::gather over the photons in the (at most 8) buckets the disc touches.
fn gather(point: vec3<f32>, normal: vec3<f32>) -> vec3<f32> {
    let r = params.radius;
    let r2 = r * r;
    let area = PI * r2;
    let lo = cell_of(point - vec3<f32>(r), params.inv_cell);
    let hi = cell_of(point + vec3<f32>(r), params.inv_cell);
    var seen: array<u32, 8>;
    var seen_count = 0u;
    var density = vec3<f32>(0.0);
    var hue = vec3<f32>(0.0);
    var total = 0u;
    var flux = 0.0;
    let n_bands = params.band_count;
    let hi_lim = vec3<i32>(step_limit(lo.x, hi.x), step_limit(lo.y, hi.y), step_limit(lo.z, hi.z));
    let extent = vec3<u32>(hi_lim - lo) + vec3<u32>(1u);
    for (var c = 0u; c < extent.x * extent.y * extent.z; c++) {
        let cx = lo.x + i32(c % extent.x);
        let cy = lo.y + i32((c / extent.x) % extent.y);
        let cz = lo.z + i32(c / (extent.x * extent.y));
        let b = bucket_of(vec3<i32>(cx, cy, cz), params.grid_mask);
        // Cells may share a bucket: each bucket is visited once.
        var dup = false;
        for (var i = 0u; i < seen_count; i++) {
            dup = dup || seen[i] == b;
        }
        if !dup {
            seen[seen_count] = b;
            seen_count++;
            let end = cells[b + 1u];
            for (var i = cells[b]; i < end; i++) {
                let p = sorted_load(i);
                let d = p.position - point;
                if dot(d, d) <= r2 && dot(oct_decode(p.direction_oct), normal) < 0.0 {
                    let band = p.band_bounces & 0xffffu;
                    if band < n_bands {
                        density += bands[band].weight * (p.flux * f32(n_bands));
                        hue += bands[band].weight;
                        total += 1u;
                    } else {
                        density += vec3<f32>(p.flux);
                        hue += vec3<f32>(1.0);
                        total += n_bands;
                    }
                    flux += p.flux;
                }
            }
        }
    }
    if params.estimator == ESTIMATOR_DENSITY {
        return density / area;
    }
    if total == 0u {
        return vec3<f32>(0.0);
    }
    return hue * (f32(n_bands) / f32(total)) * (flux / area);
}

// RenderContext::shade_diffuse
fn shade_diffuse(dir: vec3<f32>, hit: Hit) -> vec3<f32> {
    let n = select(-hit.normal, hit.normal, dot(dir, hit.normal) < 0.0);
    let albedo = albedo_at(surfaces[hit.object], hit.point, n);
    var direct = 0.0;
    for (var i = 0u; i < params.light_count; i++) {
        direct += direct_irradiance(lights[i], hit.point, n);
    }
    var caustic = vec3<f32>(0.0);
    if params.stored > 0u {
        caustic = gather(hit.point, n);
    }
    return albedo * (caustic + vec3<f32>(direct)) * (1.0 / PI) + albedo * params.ambient;
}

// RenderContext::pixel: radiance through the pixel centre, exposure applied.
fn pixel(x: u32, y: u32) -> vec3<f32> {
    let d = params.cam_corner + params.cam_right * (f32(x) + 0.5) + params.cam_down * (f32(y) + 0.5);
    top = 0u;
    push_ray(params.cam_origin, nrm(d), WHITE_BAND, 0u, 1.0, vec3<f32>(1.0));
    var sum = vec3<f32>(0.0);
    while top > 0u {
        top--;
        let e = stack[top];
        if e.next_band != NO_SPLIT {
            // One band of a split view ray: its RGB weight, its index.
            let b = e.next_band;
            let band = bands[b];
            let ior = band_ior(surfaces[e.object], b);
            through_dielectric(e, ior, b, e.weight * band.max_weight, e.tint * band.weight);
            if b + 1u < params.band_count {
                var rest = e;
                rest.next_band = b + 1u;
                push(rest);
            }
            continue;
        }
        let hit = intersect_scene(e.origin, e.dir, BIG);
        if !hit.ok {
            sum += e.tint * params.background;
            continue;
        }
        let s = surfaces[hit.object];
        if s.kind == SURFACE_DIFFUSE {
            sum += e.tint * shade_diffuse(e.dir, hit);
            continue;
        }
        if e.depth >= params.max_depth {
            continue;
        }
        if s.kind == SURFACE_MIRROR {
            let d = reflect_dir(e.dir, hit.normal);
            push_ray(offset_origin(hit.point, hit.normal, d), d, e.band, e.depth + 1u, e.weight, e.tint);
            continue;
        }
        var at = Pending(hit.point, e.weight, e.dir, e.band, e.tint, e.depth, hit.normal, NO_SPLIT, hit.object);
        if e.band == WHITE_BAND && (s.flags & SURFACE_SPLITS_VIEW_RAYS) != 0u {
            at.next_band = 0u;
            push(at);
        } else {
            through_dielectric(at, band_ior(s, e.band), e.band, e.weight, e.tint);
        }
    }
    return sum * params.exposure;
}

@compute @workgroup_size(WORKGROUP_SIZE)
fn main(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) nwg: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let k = flat_index(wid, nwg, lid);
    if k >= params.pixel_count {
        return;
    }
    let i = params.pixel_offset + k;
    pixels[k] = vec4<f32>(pixel(i % params.width, i / params.width), 1.0);
}
