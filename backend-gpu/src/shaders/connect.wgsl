// What light tracing (splat.wgsl) and the caustic layer (layer.wgsl) share:
// the pass's stored photons, the camera's projection onto a pixel of this
// chunk, and a splat added to that pixel's exact sums (sums.wgsl), so the
// sums do not depend on the order the photons come in.

// The photons the pass stored (the compaction's cursor).
@group(1) @binding(1) var<storage, read> stored_count: u32;

// PinholeCamera::project: the pixel (x, y) whose square the ray from the
// eye to `p` crosses and p's depth along the optical axis (z); z ≤ 0 when
// no pixel sees it.
fn project(p: vec3<f32>) -> vec3<f32> {
    let v = p - params.cam_origin;
    let depth = dot(v, params.cam_forward);
    if !(depth > 0.0) {
        return vec3<f32>(0.0);
    }
    let q = v / depth - params.cam_corner;
    let u = dot(q, params.cam_right) / dot(params.cam_right, params.cam_right);
    let w = dot(q, params.cam_down) / dot(params.cam_down, params.cam_down);
    if !(u >= 0.0 && u < f32(params.width) && w >= 0.0 && w < f32(params.height)) {
        return vec3<f32>(0.0);
    }
    return vec3<f32>(min(floor(u), f32(params.width - 1u)), min(floor(w), f32(params.height - 1u)), depth);
}

// The image-wide pixel that sees `p`, when this chunk has it, with the
// projection (x, y, depth); NO_PIXEL otherwise.
const NO_PIXEL: u32 = 0xffffffffu;

fn chunk_pixel(seen: vec3<f32>) -> u32 {
    if seen.z <= 0.0 {
        return NO_PIXEL;
    }
    let pixel = u32(seen.y) * params.width + u32(seen.x);
    if pixel < params.pixel_offset || pixel - params.pixel_offset >= params.pixel_count {
        return NO_PIXEL;
    }
    return pixel;
}

// Adds `c` to the sums of this chunk's `pixel`.
fn add_splat(pixel: u32, c: vec3<f32>) {
    let k = pixel - params.pixel_offset;
    for (var ch = 0u; ch < 3u; ch++) {
        add_to_sum(6u * k + 2u * ch, to_fixed(c[ch], 32));
    }
}
