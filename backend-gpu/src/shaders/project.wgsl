// The camera's projection, shared by light tracing (splat.wgsl) and the
// caustic layer (layer.wgsl).

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
