// What a surface sends toward an eye of a photon's light: twin of
// prismatic_core::photons::reflects, for light tracing (splat.wgsl) and the
// gathers of visible points on rough surfaces (gather.wgsl).

// reflects: π times the BSDF by which the surface at `hit` (seen along
// `dir`, `n` its normal facing the eye) sends `photon`'s light toward the
// eye: a photon stored on a diffuse surface, its albedo (times a blended
// metal's diffuse share toward the eye) where it lit the side the eye
// sees; one met on a rough surface, rough_reflects about the shading
// normal there.
fn splat_reflects(photon: Photon, dir: vec3<f32>, hit: Hit, n: vec3<f32>) -> vec3<f32> {
    if ((photon.band_bounces >> 16u) & ON_ROUGH_SURFACE) != 0u {
        var bent = hit;
        bent.normal = scattering_normal(hit, dir);
        return rough_reflects(photon, dir, bent);
    }
    let band = photon.band_bounces & 0xffffu;
    let lambda = photon.lambda_nm;
    let s = surface_at(hit, surfaces[hit.object]);
    var share = select(0.0, 1.0, s.kind == SURFACE_DIFFUSE);
    if (s.flags & SURFACE_BLENDED) != 0u {
        let toward_eye = abs(dot(dir, scattering_normal(hit, dir)));
        share = blend_diffuse_share(s, metalness_at(hit, s), toward_eye, band, lambda);
    }
    if share == 0.0 || dot(oct_unpack(photon.direction_oct), n) >= 0.0 {
        return vec3<f32>(0.0);
    }
    return reflectance(albedo_at(hit, n), band, lambda) * share;
}

// rough_reflects: π times the BSDF by which the rough metal or glass at
// `bent` (its normal the shading normal) sends the light of `photon`, met
// there, toward an eye looking along `dir` (rough_reflects_on).
fn rough_reflects(photon: Photon, dir: vec3<f32>, bent: Hit) -> vec3<f32> {
    return rough_reflects_on(photon, dir, bent, rough_surface(bent));
}

// reflects::RoughSurface: the surface at `bent` as its maps make it there,
// its facets' α (0: polished) and its metalness, read once for every
// photon a visible point there weighs.
struct RoughSurface {
    s: GpuSurface,
    alpha: f32,
    metalness: f32,
}

fn rough_surface(bent: Hit) -> RoughSurface {
    let s = surface_at(bent, surfaces[bent.object]);
    return RoughSurface(s, facets_alpha(bent, s), metalness_at(bent, s));
}

// RoughSurface::reflects: a rough metal's GGX reflection (a blended
// metal's specular part's), or rough glass's BSDF on either side, a tinted
// sheet's crossing colouring what passes it and what leaves solid glass
// taking (n_eye/n_photon)² (radiance_across), of `photon` toward an eye
// looking along `dir`, at `bent` on the surface `r`.
fn rough_reflects_on(photon: Photon, dir: vec3<f32>, bent: Hit, r: RoughSurface) -> vec3<f32> {
    let band = photon.band_bounces & 0xffffu;
    let lambda = photon.lambda_nm;
    let wo = -dir;
    let wi = -oct_unpack(photon.direction_oct);
    let normal = bent.normal;
    let s = r.s;
    let alpha = r.alpha;
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
        return PI * (specular_tint(s, r.metalness, dot(wo, nrm(wo + wi)), band, lambda) * density);
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
        // reflects::radiance_across: (n_eye/n_photon)².
        let i = facing_interface(dir, normal, face.ior);
        let ratio = i.n1 / i.n2;
        return vec3<f32>(f * (ratio * ratio));
    }
    return vec3<f32>(f);
}
