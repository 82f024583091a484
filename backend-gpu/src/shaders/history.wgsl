// A caustic layer's temporal accumulation (session/history.rs): per pixel,
// this frame's estimate (the image, one pass) folded into the running mean
// of the frames since the pixel's surface last changed, at most `cap`
// frames long (an exponential window past it), and the image replaced by
// that mean. A pixel whose surface changed between the last frame and this
// one (depth or normal; or it saw none) starts again.

struct HistoryParams {
    pixels: u32,
    // Frames the running mean spans at most.
    cap: u32,
    // LAYER_PLANE_REL: how far the new surface may lie from the old one's plane.
    plane_rel: f32,
    pad: u32,
}

@group(0) @binding(0) var<uniform> history_params: HistoryParams;
@group(0) @binding(1) var<storage, read_write> image: array<vec4<f32>>;
// Per pixel: the running mean (rgb) and the frames in it (w).
@group(0) @binding(2) var<storage, read_write> history: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> previous: array<vec2<u32>>;
@group(0) @binding(4) var<storage, read> current: array<vec2<u32>>;

// Whether a frame's pixel sees a surface.
fn seen(texel: vec2<u32>) -> bool {
    let depth = bitcast<f32>(texel.y);
    return depth > 0.0 && depth <= BIG;
}

// Whether the surface a pixel sees is the same in both frames.
fn same_surface(a: vec2<u32>, b: vec2<u32>) -> bool {
    if !seen(a) || !seen(b) {
        return false;
    }
    let da = bitcast<f32>(a.y);
    let db = bitcast<f32>(b.y);
    return abs(da - db) <= history_params.plane_rel * db && dot(oct_unpack(a.x), oct_unpack(b.x)) > 0.999;
}

@compute @workgroup_size(WORKGROUP_SIZE)
fn blend_history(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) nwg: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let i = flat_index(wid, nwg, lid);
    if i >= history_params.pixels {
        return;
    }
    var h = history[i];
    if !same_surface(previous[i], current[i]) {
        h = vec4<f32>(0.0);
    }
    let n = min(h.w + 1.0, f32(history_params.cap));
    let mean = h.xyz + (image[i].xyz - h.xyz) / n;
    history[i] = vec4<f32>(mean, n);
    image[i] = vec4<f32>(mean, 1.0);
}
