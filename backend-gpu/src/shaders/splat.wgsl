// Light tracing: twin of prismatic_core::photons::light_tracing. One
// invocation per slot of the photon map (those past the stored count return
// at once); each photon that a pixel of this chunk sees directly adds its
// reflected flux to that pixel's sums (connect.wgsl).


// CameraConnection::splat, added to the sums of its pixel when this chunk has it.
@compute @workgroup_size(WORKGROUP_SIZE)
fn splat(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) nwg: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let i = flat_index(wid, nwg, lid);
    if i >= stored_count {
        return;
    }
    let photon = map_load(i);
    let seen = project(photon.position);
    let pixel = chunk_pixel(seen);
    if pixel == NO_PIXEL {
        return;
    }
    let v = photon.position - params.cam_origin;
    let d = length(v);
    let dir = v / d;
    let hit = intersect_scene(params.cam_origin, dir, d * (1.0 + CONNECTION_REL));
    if !hit.ok || hit.t < d * (1.0 - CONNECTION_REL) {
        return;
    }
    let n = select(-hit.normal, hit.normal, dot(dir, hit.normal) < 0.0);
    let reflects = splat_reflects(photon, dir, hit, n);
    if all(reflects == vec3<f32>(0.0)) {
        return;
    }
    let band = photon.band_bounces & 0xffffu;
    let importance = -dot(v, n) / (seen.z * seen.z * seen.z) * params.splat_scale;
    let flux = rgb_of_flux(band, photon.lambda_nm, photon.flux);
    add_splat(pixel, flux * reflects * importance * params.white_balance);
}
