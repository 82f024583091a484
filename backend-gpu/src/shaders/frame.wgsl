// An engine's frame from its depth and normal textures (its prepass), into
// the layer's per-pixel frame (layer.wgsl): the view-space depth from the
// depth buffer's encoding, the world-space normal packed.

struct FrameParams {
    width: u32,
    height: u32,
    // DEPTH_REVERSE_INFINITE or DEPTH_FORWARD.
    depth_encoding: u32,
    // NORMAL_UNORM (n * 0.5 + 0.5) or NORMAL_SIGNED.
    normal_encoding: u32,
    near: f32,
    far: f32,
    pad0: u32,
    pad1: u32,
}

const DEPTH_REVERSE_INFINITE: u32 = 0u;
const DEPTH_FORWARD: u32 = 1u;
const NORMAL_UNORM: u32 = 0u;

@group(0) @binding(0) var<uniform> frame_params: FrameParams;
@group(0) @binding(1) var depth_texture: texture_depth_2d;
@group(0) @binding(2) var normal_texture: texture_2d<f32>;
@group(0) @binding(3) var<storage, read_write> frame: array<vec2<u32>>;

// The view-space depth a depth-buffer value `d` encodes; 0 where the
// buffer was left clear (nothing drawn).
fn view_depth(d: f32) -> f32 {
    let p = frame_params;
    if p.depth_encoding == DEPTH_REVERSE_INFINITE {
        // d = near / s.
        return select(0.0, p.near / d, d > 0.0);
    }
    // d = far (s − near) / (s (far − near)).
    return select(0.0, p.far * p.near / (p.far - d * (p.far - p.near)), d < 1.0);
}

@compute @workgroup_size(WORKGROUP_SIZE)
fn frame_from_textures(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) nwg: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let i = flat_index(wid, nwg, lid);
    let p = frame_params;
    if i >= p.width * p.height {
        return;
    }
    let xy = vec2<u32>(i % p.width, i / p.width);
    let depth = view_depth(textureLoad(depth_texture, xy, 0));
    var n = textureLoad(normal_texture, xy, 0).xyz;
    if p.normal_encoding == NORMAL_UNORM {
        n = n * 2.0 - vec3<f32>(1.0);
    }
    let usable = dot(n, n) > 1e-6 && depth > 0.0 && depth <= BIG;
    frame[i] = vec2<u32>(select(0u, oct_pack(nrm(n)), usable), bitcast<u32>(select(0.0, depth, usable)));
}
