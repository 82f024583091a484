// The caustic layer: twin of prismatic_core::render::layer. One invocation
// per slot of the photon map (those past the stored count return at once);
// each photon that lies where the engine's frame sees a surface (on the
// plane of the pixel's surface, arrived on the side the camera sees) adds
// its irradiance to that pixel's sums (connect.wgsl).

// The engine's frame, per pixel of the whole image: its surface's
// world-space normal (oct_pack) and view-space depth (f32 bits; not
// finite, or 0, where it sees none).
@group(1) @binding(6) var<storage, read> frame: array<vec2<u32>>;

// LayerConnection::splat, added to the sums of its pixel when this chunk has it.
@compute @workgroup_size(WORKGROUP_SIZE)
fn layer_splat(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) nwg: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let i = flat_index(wid, nwg, lid);
    if i >= stored_count {
        return;
    }
    let photon = map_load(i);
    if ((photon.band_bounces >> 16u) & ON_ROUGH_SURFACE) != 0u {
        return; // irradiance of diffuse surfaces only
    }
    let seen = project(photon.position);
    let pixel = chunk_pixel(seen);
    if pixel == NO_PIXEL {
        return;
    }
    let surface = frame[pixel];
    let depth = bitcast<f32>(surface.y);
    if !(depth > 0.0 && depth <= BIG) {
        return;
    }
    let normal = oct_unpack(surface.x);
    let through = params.cam_corner + params.cam_right * (seen.x + 0.5) + params.cam_down * (seen.y + 0.5);
    let centre = params.cam_origin + through * depth;
    let n = select(-normal, normal, dot(centre - params.cam_origin, normal) < 0.0);
    if abs(dot(photon.position - centre, n)) > LAYER_PLANE_REL * depth
        || dot(oct_unpack(photon.direction_oct), n) >= 0.0 {
        return;
    }
    let v = photon.position - params.cam_origin;
    let importance = -dot(v, n) / (seen.z * seen.z * seen.z) * params.splat_scale * PI;
    let band = photon.band_bounces & 0xffffu;
    let c = rgb_of_flux(band, photon.lambda_nm, photon.flux) * importance * params.white_balance;
    add_splat(pixel, c);
}
