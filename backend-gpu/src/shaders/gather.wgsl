// The caustic at the visible points of render.wgsl: twin of
// prismatic_core::gather. `gather_segment` adds the photons of one segment
// of each bucket the disc touches (`gather_span` photons after the first
// `gather_first`) to a point's running sums (GatherSums::add); the host
// repeats it over segments until the widest bucket is covered (one pass on
// a hardware GPU; several on a software device, which caps the loop
// iterations of one invocation). `finish_estimate` (common.wgsl) turns
// the sums into irradiance. The sums are i64 fixed point (fixed.wgsl):
// `params.sum_shift` and `params.flux_shift` are the powers of two the
// host chose for the pass (so that one photon is at most 2^30 units).

@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var<storage, read> bands: array<GpuBand>;
@group(0) @binding(2) var<storage, read> cells: array<u32>;
// The chunk's visible points: how many the view pass appended, and the points.
@group(0) @binding(3) var<storage, read> point_total: u32;
@group(0) @binding(4) var<storage, read_write> points: array<VisiblePoint>;
@group(0) @binding(5) var<storage, read_write> pixels: array<vec4<f32>>;
// The scene, for the BSDF of points on rough surfaces (reflects.wgsl).
@group(0) @binding(10) var<storage, read> objects: array<GpuObject>;
@group(0) @binding(11) var<storage, read> surfaces: array<GpuSurface>;
@group(0) @binding(12) var<storage, read> geometry: array<vec4<f32>>;
@group(0) @binding(13) var<storage, read> tables: array<f32>;

fn step_limit(lo: i32, hi: i32) -> i32 {
    // hi.min(lo.saturating_add(1))
    if lo == 2147483647 {
        return lo;
    }
    return min(hi, lo + 1);
}

// This pass's segment of each of the (at most 8) buckets the disc around
// the point touches, as [first, end) ranges of the sorted photons; the
// point's `widest` grows to the fullest of them (begin_pass empties it).
fn segment_ranges(vp: ptr<function, VisiblePoint>, ranges: ptr<function, array<vec2<u32>, 8>>) -> u32 {
    let point = (*vp).position;
    let r = (*vp).radius;
    let lo = cell_of(point - vec3<f32>(r), params.inv_cell);
    let hi = cell_of(point + vec3<f32>(r), params.inv_cell);
    var seen: array<u32, 8>;
    var seen_count = 0u;
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
        (*vp).widest = max((*vp).widest, size);
        let first = start + params.gather_first;
        (*ranges)[seen_count] = vec2<u32>(first, first + min(size - params.gather_first, params.gather_span));
        seen[seen_count] = b;
        seen_count++;
    }
    return seen_count;
}

// Whether photon `p` was met on a rough surface (Photon::on_rough_surface).
fn met_on_rough(p: Photon) -> bool {
    return ((p.band_bounces >> 16u) & ON_ROUGH_SURFACE) != 0u;
}

// GatherSums::add_reflected: photon `p`, of which the surface sends
// `reflected` on, added to the point's sums.
fn add_photon(vp: ptr<function, VisiblePoint>, p: Photon, reflected: vec3<f32>) {
    let band = p.band_bounces & 0xffffu;
    (*vp).found += 1u;
    var add: vec3<f32>;
    if params.estimator == ESTIMATOR_DENSITY {
        add = rgb_of_flux(band, p.lambda_nm, p.flux);
    } else {
        add = hue(band, p.lambda_nm);
    }
    add *= reflected;
    (*vp).total += select(params.band_count, 1u, band < params.band_count);
    // Unrolled: a varying index into the sums costs a software device dearly.
    (*vp).sums[0] = add_term((*vp).sums[0], add.x, params.sum_shift);
    (*vp).sums[1] = add_term((*vp).sums[1], add.y, params.sum_shift);
    (*vp).sums[2] = add_term((*vp).sums[2], add.z, params.sum_shift);
    (*vp).flux = add_term((*vp).flux, p.flux, params.flux_shift);
}

// GatherSums::add over this pass's segments at a point: on a diffuse
// surface (`rough` false) the photons stored there (not those met on rough
// surfaces, which the grid holds too where rough points gather), arriving
// at its front, each reflected by its albedo; on rough metal or glass
// (gather::gather_rough) the photons met on rough surfaces, from either
// side, each weighed by rough_reflects toward the viewer. Each entry point
// passes `rough` as a constant (session.wgsl), so the diffuse gather's
// loop compiles without the rough surface's BSDF (with it inlined there,
// lavapipe ran the GPU crate's tests in 176 s instead of 86).
fn gather_segment(vp: ptr<function, VisiblePoint>, rough: bool) {
    let point = (*vp).position;
    let normal = (*vp).normal;
    let bent = Hit(true, 0.0, point, normal, (*vp).rough & ~ROUGH_POINT, (*vp).triangle);
    // A rough surface's maps read once for the point, not per photon.
    var surface: RoughSurface;
    if rough {
        surface = rough_surface(bent);
    }
    let r2 = (*vp).radius * (*vp).radius;
    var ranges: array<vec2<u32>, 8>;
    let n = segment_ranges(vp, &ranges);
    for (var k = 0u; k < n; k++) {
        for (var i = ranges[k].x; i < ranges[k].y; i++) {
            let p = sorted_load(i);
            let d = p.position - point;
            if dot(d, d) > r2 || met_on_rough(p) != rough {
                continue;
            }
            if rough {
                add_photon(vp, p, rough_reflects_on(p, (*vp).toward, bent, surface));
            } else if dot(oct_unpack(p.direction_oct), normal) < 0.0 {
                add_photon(vp, p, reflectance((*vp).albedo, p.band_bounces & 0xffffu, p.lambda_nm));
            }
        }
    }
}

// The caustic irradiance at a point from its fixed-point sums.
fn point_caustic(vp: VisiblePoint) -> vec3<f32> {
    let s = params.sum_shift;
    let sums = vec3<f32>(from_fixed(vp.sums[0], s), from_fixed(vp.sums[1], s), from_fixed(vp.sums[2], s));
    let flux = from_fixed(vp.flux, params.flux_shift);
    return finish_estimate(params.estimator, params.band_count, sums, vp.total, flux, vp.radius);
}

// Whether index `i` holds a visible point of the current chunk.
fn is_point(i: u32) -> bool {
    return i < min(point_total, params.point_capacity);
}
