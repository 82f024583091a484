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

// CameraConnection::reflects: π times the BSDF by which the surface at `hit`
// (seen along `dir`, `n` its normal facing the eye) sends `photon`'s light
// toward the eye: a photon stored on a diffuse surface, its albedo (times
// a blended metal's diffuse share toward the eye) where it lit the side
// the eye sees; one met on a rough surface, π times the rough metal's BRDF
// (a blended metal's specular part's) or rough glass's BSDF on either
// side, a tinted sheet's crossing colouring what passes it and what
// leaves solid glass taking (n_eye/n_photon)² (radiance_across).
fn splat_reflects(photon: Photon, dir: vec3<f32>, hit: Hit, n: vec3<f32>) -> vec3<f32> {
    let band = photon.band_bounces & 0xffffu;
    let lambda = photon.lambda_nm;
    let wo = -dir;
    let wi = -oct_unpack(photon.direction_oct);
    let s = surface_at(hit, surfaces[hit.object]);
    let blended = (s.flags & SURFACE_BLENDED) != 0u;
    if ((photon.band_bounces >> 16u) & ON_ROUGH_SURFACE) == 0u {
        var share = select(0.0, 1.0, s.kind == SURFACE_DIFFUSE);
        if blended {
            let toward_eye = abs(dot(dir, scattering_normal(hit, dir)));
            share = blend_diffuse_share(s, metalness_at(hit, s), toward_eye, band, lambda);
        }
        if share == 0.0 || dot(wi, n) <= 0.0 {
            return vec3<f32>(0.0);
        }
        return reflectance(albedo_at(hit, n), band, lambda) * share;
    }
    let normal = scattering_normal(hit, dir);
    let alpha = facets_alpha(hit, s);
    if alpha <= 0.0 {
        return vec3<f32>(0.0);
    }
    if s.kind == SURFACE_METAL {
        // MetalOptics::reflection about the shading normal facing the eye.
        let facing = select(-normal, normal, dot(dir, normal) < 0.0);
        let density = ggx_reflection(alpha, wo, wi, facing);
        if density == 0.0 {
            return vec3<f32>(0.0);
        }
        let m = metalness_at(hit, s);
        return PI * (specular_tint(s, m, dot(wo, nrm(wo + wi)), band, lambda) * density);
    }
    if s.kind != SURFACE_DIELECTRIC {
        return vec3<f32>(0.0);
    }
    let own = band < params.band_count
        && (params.wavelengths == WAVELENGTHS_CONTINUOUS || params.wavelengths == WAVELENGTHS_HERO);
    let face = path_face(s, band, select(-1.0, lambda, own));
    let f = PI * rough_glass_bsdf(wo, wi, normal, face, alpha);
    if dot(wi, normal) * dot(wo, normal) < 0.0 {
        if is_sheet(s) {
            return sheet_crossing_rgb(s, band) * f;
        }
        // light_tracing::radiance_across: (n_eye/n_photon)².
        let i = facing_interface(dir, normal, face.ior);
        let ratio = i.n1 / i.n2;
        return vec3<f32>(f * (ratio * ratio));
    }
    return vec3<f32>(f);
}
