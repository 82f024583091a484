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
    // A blended metal's diffuse part reflects its share toward the eye.
    let band = photon.band_bounces & 0xffffu;
    let s = surfaces[hit.object];
    var diffuse_share = select(0.0, 1.0, s.kind == SURFACE_DIFFUSE);
    if (s.flags & SURFACE_BLENDED) != 0u {
        let toward_eye = abs(dot(dir, scattering_normal(hit, dir)));
        let here = surface_at(hit, s);
        diffuse_share = blend_diffuse_share(here, metalness_at(hit, s), toward_eye, band, photon.lambda_nm);
    }
    if diffuse_share == 0.0 {
        return;
    }
    let n = select(-hit.normal, hit.normal, dot(dir, hit.normal) < 0.0);
    if dot(oct_unpack(photon.direction_oct), n) >= 0.0 {
        return;
    }
    let albedo = albedo_at(hit, n);
    let importance = -dot(v, n) / (seen.z * seen.z * seen.z) * params.splat_scale * diffuse_share;
    let flux = rgb_of_flux(band, photon.lambda_nm, photon.flux);
    let c = flux * reflectance(albedo, band, photon.lambda_nm) * importance * params.white_balance;
    add_splat(pixel, c);
}
