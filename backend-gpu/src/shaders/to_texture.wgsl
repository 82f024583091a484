// Copies the rendered linear-RGB pixels into a caller's storage texture, so
// that an engine can show the caustics without a trip through the CPU.

@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var<storage, read> pixels: array<vec4<f32>>;
@group(0) @binding(2) var target_: texture_storage_2d<TEXEL_FORMAT, write>;

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
    textureStore(target_, vec2<u32>(i % params.width, i / params.width), pixels[k]);
}
