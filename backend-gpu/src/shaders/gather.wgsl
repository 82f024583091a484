// The caustic at the visible points of render.wgsl: twin of
// prismatic_core::gather. `gather` runs one invocation per point slot and
// adds the photons of one segment of each bucket the disc touches
// (`gather_span` photons after the first `gather_first`) to the point's
// running sums; the host repeats it over segments until the widest bucket
// is covered (one pass on a hardware GPU; several on a software device,
// which caps the loop iterations of one invocation). `resolve` then adds
// each pixel's points, in slot order, to the pixel.

@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var<storage, read> bands: array<GpuBand>;
@group(0) @binding(2) var<storage, read> cells: array<u32>;
@group(0) @binding(3) var<storage, read> point_counts: array<u32>;
@group(0) @binding(4) var<storage, read_write> points: array<VisiblePoint>;
@group(0) @binding(5) var<storage, read_write> pixels: array<vec4<f32>>;

// `x`, hidden from the shader compiler's algebra: WGSL marks no arithmetic
// exact, so a compiler may simplify Kahan's (s + y) - s - y to 0 (Mesa's
// NIR does); it cannot see through a select on a run-time 0.
fn opaque(x: vec3<f32>) -> vec3<f32> {
    return select(x, vec3<f32>(0.0), params.zero != 0u);
}

fn step_limit(lo: i32, hi: i32) -> i32 {
    // hi.min(lo.saturating_add(1))
    if lo == 2147483647 {
        return lo;
    }
    return min(hi, lo + 1);
}

// gather::gather's sums over this pass's segment of the (at most 8)
// buckets the disc around the point touches.
fn gather_segment(vp: ptr<function, VisiblePoint>) {
    let point = (*vp).position;
    let normal = (*vp).normal;
    let r = (*vp).radius;
    let r2 = r * r;
    let lo = cell_of(point - vec3<f32>(r), params.inv_cell);
    let hi = cell_of(point + vec3<f32>(r), params.inv_cell);
    var seen: array<u32, 8>;
    var seen_count = 0u;
    let n_bands = params.band_count;
    let density = params.estimator == ESTIMATOR_DENSITY;
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
        let start = cells[b];
        let size = cells[b + 1u] - start;
        if dup || size <= params.gather_first {
            continue;
        }
        seen[seen_count] = b;
        seen_count++;
        let first = start + params.gather_first;
        let end = first + min(size - params.gather_first, params.gather_span);
        for (var i = first; i < end; i++) {
            let p = sorted_load(i);
            let d = p.position - point;
            if dot(d, d) <= r2 && dot(oct_decode(p.direction_oct), normal) < 0.0 {
                let band = p.band_bounces & 0xffffu;
                (*vp).found += 1u;
                var add = select(vec3<f32>(1.0), vec3<f32>(p.flux), density);
                if band < n_bands {
                    add = select(bands[band].weight, bands[band].weight * (p.flux * f32(n_bands)), density);
                    (*vp).total += 1u;
                } else {
                    (*vp).total += n_bands;
                }
                // Kahan sums: the reference sums in f64 and integers.
                let y = add - (*vp).sums_c;
                let t = opaque((*vp).sums + y);
                (*vp).sums_c = (t - (*vp).sums) - y;
                (*vp).sums = t;
                let yf = p.flux - (*vp).flux_c;
                let tf = opaque(vec3<f32>((*vp).flux + yf)).x;
                (*vp).flux_c = (tf - (*vp).flux) - yf;
                (*vp).flux = tf;
            }
        }
    }
}

// The caustic irradiance at a point from its sums (gather::estimate).
fn caustic(vp: VisiblePoint) -> vec3<f32> {
    let area = PI * vp.radius * vp.radius;
    if params.estimator == ESTIMATOR_DENSITY {
        return vp.sums / area;
    }
    if vp.total == 0u {
        return vec3<f32>(0.0);
    }
    return vp.sums * (f32(params.band_count) / f32(vp.total)) * (vp.flux / area);
}

// Whether slot-major index `i` holds a visible point of the current chunk
// (slot j of pixel k is at `j * pixel_count + k`).
fn is_point(i: u32) -> bool {
    let slot = i / params.pixel_count;
    let k = i - slot * params.pixel_count;
    return slot < params.points_per_pixel && slot < point_counts[k];
}

// What pixel k's visible points add to it: weight × caustic, in slot order.
fn pixel_caustic(k: u32) -> vec3<f32> {
    var c = vec3<f32>(0.0);
    let n = min(point_counts[k], params.points_per_pixel);
    for (var slot = 0u; slot < n; slot++) {
        let vp = points[slot * params.pixel_count + k];
        c += vp.weight * caustic(vp);
    }
    return c;
}

@compute @workgroup_size(WORKGROUP_SIZE)
fn gather(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) nwg: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    // Slot-major: the invocations of empty slots fill whole workgroups.
    let i = flat_index(wid, nwg, lid);
    if !is_point(i) {
        return;
    }
    var vp = points[i];
    gather_segment(&vp);
    points[i] = vp;
}

// A progressive pass: one invocation per visible point of one grid level
// (the host uploads the points sorted by level: this level's are
// `pixel_offset` .. `pixel_offset + pixel_count`), each with its own
// radius; the host reads the sums back and finishes the estimate.
@compute @workgroup_size(WORKGROUP_SIZE)
fn gather_points(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) nwg: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let k = flat_index(wid, nwg, lid);
    if k >= params.pixel_count {
        return;
    }
    let i = params.pixel_offset + k;
    var vp = points[i];
    gather_segment(&vp);
    points[i] = vp;
}

@compute @workgroup_size(WORKGROUP_SIZE)
fn resolve(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) nwg: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let k = flat_index(wid, nwg, lid);
    if k >= params.pixel_count {
        return;
    }
    pixels[k] = vec4<f32>(pixels[k].xyz + pixel_caustic(k), 1.0);
}
