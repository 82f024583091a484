// A metal's Fresnel for a path: twin of prismatic_core::optics::metal's
// MetalOptics::{tint, reflectance} over the scene's bindings. A measured
// metal (SURFACE_MEASURED) keeps its optical constants in the tables
// buffer from `curve_first`: n and k at each row of model::metals
// (METAL_FIRST_NM, every METAL_STEP_NM).

// NamedMetal::optical_constants: (n, k) at `lambda_nm`, read linearly
// between rows (the end rows outside them).
fn metal_constants(s: GpuSurface, lambda_nm: f32) -> vec2<f32> {
    let x = clamp((lambda_nm - METAL_FIRST_NM) / METAL_STEP_NM, 0.0, f32(METAL_ROWS - 1u));
    let i = min(u32(x), METAL_ROWS - 2u);
    let f = x - f32(i);
    let at = s.curve_first + 2u * i;
    let a = vec2<f32>(tables[at], tables[at + 1u]);
    let b = vec2<f32>(tables[at + 2u], tables[at + 3u]);
    return a + (b - a) * f;
}

// metal::measured_fresnel
fn measured_fresnel(s: GpuSurface, c: f32, lambda_nm: f32) -> f32 {
    let nk = metal_constants(s, lambda_nm);
    return conductor_fresnel(c, nk.x, nk.y);
}

// MetalOptics::filmed: the film's Airy sum over the metal at the path's
// wavelength (a measured metal's complex index, an RGB metal's real index
// (1 + √F0)/(1 − √F0) from its F0 at that wavelength).
fn metal_filmed(s: GpuSurface, c: f32, band: u32, lambda_nm: f32) -> f32 {
    var base: vec2<f32>;
    if (s.flags & SURFACE_MEASURED) != 0u {
        base = metal_constants(s, lambda_nm);
    } else {
        let r = sqrt(min(bounce_reflectance(s.albedo, band, lambda_nm), MAX_FILMED_F0));
        base = vec2<f32>((1.0 + r) / (1.0 - r), 0.0);
    }
    let film = surface_film(s);
    return thin_film_on(c, 1.0, film.x, base, film.y, film.z, lambda_nm);
}

// MetalOptics::tint: what a facet met at cosine `c` keeps of each RGB
// channel of a view path (a measured or filmed metal's white path: Σ C_b F(λ_b)).
fn metal_tint(s: GpuSurface, c: f32, band: u32, lambda_nm: f32) -> vec3<f32> {
    if (s.flags & SURFACE_HAS_FILM) != 0u {
        if band == WHITE_BAND {
            var sum = vec3<f32>(0.0);
            for (var b = 0u; b < params.band_count; b++) {
                sum += bands[b].weight * metal_filmed(s, c, b, bands[b].lambda_nm);
            }
            return sum;
        }
        return vec3<f32>(metal_filmed(s, c, band, lambda_nm));
    }
    if (s.flags & SURFACE_MEASURED) == 0u {
        return reflectance(metal_fresnel(s.albedo, c), band, lambda_nm);
    }
    if band == WHITE_BAND {
        var sum = vec3<f32>(0.0);
        for (var b = 0u; b < params.band_count; b++) {
            sum += bands[b].weight * measured_fresnel(s, c, bands[b].lambda_nm);
        }
        return sum;
    }
    return vec3<f32>(measured_fresnel(s, c, lambda_nm));
}

// MetalOptics::reflectance: the share of a photon path's flux a facet
// met at cosine `c` reflects.
fn metal_reflectance(s: GpuSurface, c: f32, band: u32, lambda_nm: f32) -> f32 {
    if (s.flags & SURFACE_HAS_FILM) != 0u {
        if band != WHITE_BAND {
            return metal_filmed(s, c, band, lambda_nm);
        }
        return bounce_reflectance(metal_tint(s, c, band, lambda_nm), band, lambda_nm);
    }
    if (s.flags & SURFACE_MEASURED) == 0u {
        return bounce_reflectance(metal_fresnel(s.albedo, c), band, lambda_nm);
    }
    if band != WHITE_BAND {
        return measured_fresnel(s, c, lambda_nm);
    }
    return bounce_reflectance(metal_tint(s, c, band, lambda_nm), band, lambda_nm);
}

// MetalOptics::is_chromatic: where some of it is metal, a measured metal,
// a colour texture, a film, or F0 not grey; a blend's coloured layer.
fn metal_is_chromatic(s: GpuSurface) -> bool {
    let f0 = s.albedo;
    let metal = (s.flags & (SURFACE_MEASURED | SURFACE_HAS_COLOUR_MAP | SURFACE_HAS_FILM)) != 0u || f0.x != f0.y || f0.y != f0.z;
    let blended = (s.flags & SURFACE_BLENDED) != 0u;
    let some_metal = !blended || s.checker_offset.x > 0.0;
    let l = layer_f0(s);
    let layer = s.checker_offset.y > 0.0 && (l.x != l.y || l.y != l.z);
    return (metal && some_metal) || (layer && blended);
}

// ---- the specular layer of a blend's base (MetalOptics over
// model::metalness::SpecularLayer): F0 per channel in `absorption`, F90
// in checker_offset.y (0: no layer). m is the metalness at the point
// (metalness_at). ----

fn layer_f0(s: GpuSurface) -> vec3<f32> {
    return s.absorption;
}

// SpecularLayer::fresnel
fn layer_fresnel(s: GpuSurface, c: f32) -> vec3<f32> {
    return layer_schlick(layer_f0(s), s.checker_offset.y, c);
}

// Metalness::specular_share: m + (1 − m) F90.
fn specular_share(s: GpuSurface, m: f32) -> f32 {
    if s.checker_offset.y > 0.0 {
        return m + (1.0 - m) * s.checker_offset.y;
    }
    return m;
}

// Metalness::diffuse_share: (1 − m)(1 − max F_layer(cos)) toward a viewer at `c`.
fn blend_diffuse_share(s: GpuSurface, m: f32, c: f32) -> f32 {
    if s.checker_offset.y > 0.0 {
        let f = layer_fresnel(s, c);
        return (1.0 - m) * (1.0 - max(f.x, max(f.y, f.z)));
    }
    return (1.0 - m) * 1.0;
}

// MetalOptics::specular_tint: m F_metal + (1 − m) F_layer per RGB channel.
fn specular_tint(s: GpuSurface, m: f32, c: f32, band: u32, lambda_nm: f32) -> vec3<f32> {
    var metal = vec3<f32>(0.0);
    if m > 0.0 {
        metal = metal_tint(s, c, band, lambda_nm) * m;
    }
    if s.checker_offset.y > 0.0 {
        return metal + reflectance(layer_fresnel(s, c), band, lambda_nm) * (1.0 - m);
    }
    return metal;
}

// MetalOptics::specular_reflectance: a photon path's survival off the specular part.
fn specular_reflectance(s: GpuSurface, m: f32, c: f32, band: u32, lambda_nm: f32) -> f32 {
    var metal = 0.0;
    if m > 0.0 {
        metal = metal_reflectance(s, c, band, lambda_nm);
    }
    if s.checker_offset.y > 0.0 {
        let layer = bounce_reflectance(layer_fresnel(s, c), band, lambda_nm);
        return (m * metal + (1.0 - m) * layer) / specular_share(s, m);
    }
    return metal;
}

// MetalOptics::layer_passes: the share the layer passes to the base.
fn layer_passes(s: GpuSurface, m: f32, c: f32, band: u32, lambda_nm: f32) -> f32 {
    if s.checker_offset.y <= 0.0 {
        return 0.0;
    }
    let layer = bounce_reflectance(layer_fresnel(s, c), band, lambda_nm);
    return max((1.0 - m) * (s.checker_offset.y - layer) / specular_share(s, m), 0.0);
}
