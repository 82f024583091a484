// An engine's frame from its depth and normal textures (its prepass), into
// the layer's per-pixel frame (layer.wgsl): the view-space depth from the
// depth buffer's encoding, the world-space normal packed. Multisampled
// textures are averaged over a pixel's samples: the standard patterns are
// centred on the pixel, and the stored depth (near / s, or forward Z) is
// affine across a plane on the screen, so the mean is the depth at the
// pixel's centre; a pixel with a sample left clear (a silhouette against
// nothing) has no surface.

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

// Whether the depth-buffer value `d` was left clear (nothing drawn).
fn is_clear(d: f32) -> bool {
    if frame_params.depth_encoding == DEPTH_REVERSE_INFINITE {
        return !(d > 0.0);
    }
    return !(d < 1.0);
}

// The view-space depth a depth-buffer value `d` (not clear) encodes.
fn view_depth(d: f32) -> f32 {
    let p = frame_params;
    if p.depth_encoding == DEPTH_REVERSE_INFINITE {
        // d = near / s.
        return p.near / d;
    }
    // d = far (s − near) / (s (far − near)).
    return p.far * p.near / (p.far - d * (p.far - p.near));
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
    let samples = SAMPLES;
    var d = 0.0;
    var n = vec3<f32>(0.0);
    var clear = false;
    for (var k = 0u; k < samples; k++) {
        // The sample's index, or the mip level (0) of a single-sampled texture.
        let dk = textureLoad(depth_texture, xy, i32(k));
        clear = clear || is_clear(dk);
        d += dk;
        var nk = textureLoad(normal_texture, xy, i32(k)).xyz;
        if p.normal_encoding == NORMAL_UNORM {
            nk = nk * 2.0 - vec3<f32>(1.0);
        }
        n += nk;
    }
    let depth = select(view_depth(d / f32(samples)), 0.0, clear);
    let usable = !clear && dot(n, n) > 1e-6 && depth > 0.0 && depth <= BIG;
    frame[i] = vec2<u32>(select(0u, oct_pack(nrm(n)), usable), bitcast<u32>(select(0.0, depth, usable)));
}
