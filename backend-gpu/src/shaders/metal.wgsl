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

// The spectral Fresnel at one wavelength, band `band` (for an RGB
// metal's F0 under a film): `wm` times the metal's where it is measured
// or filmed (MetalOptics::tint's per band) plus `wl` times the filmed
// layer's (MetalOptics::layer_tint's); each weight 0 leaves its part out.
fn spectral_fresnel(s: GpuSurface, wm: f32, wl: f32, c: f32, band: u32, lambda_nm: f32) -> f32 {
    var f = 0.0;
    if wm > 0.0 {
        if (s.flags & SURFACE_HAS_FILM) != 0u {
            f = wm * metal_filmed(s, c, band, lambda_nm);
        } else {
            f = wm * measured_fresnel(s, c, lambda_nm);
        }
    }
    if wl > 0.0 {
        f += wl * layer_filmed(s, c, lambda_nm);
    }
    return f;
}

// spectral_fresnel per RGB channel of a view path: a white path's
// Σ C_b F(λ_b) over the bands, a band path's one value in each channel.
// One loop for both (a band path runs it once) and for the metal and the
// layer together: lavapipe compiles an inlined copy of the film's Airy
// sum for each call, and each copy lengthens every pipeline's compile.
fn spectral_tint(s: GpuSurface, wm: f32, wl: f32, c: f32, band: u32, lambda_nm: f32) -> vec3<f32> {
    let white = band == WHITE_BAND;
    var sum = vec3<f32>(0.0);
    for (var i = 0u; i < select(1u, params.band_count, white); i++) {
        var b = band;
        var lambda = lambda_nm;
        var w = vec3<f32>(1.0);
        if white {
            b = i;
            lambda = bands[i].lambda_nm;
            w = bands[i].weight;
        }
        sum += w * spectral_fresnel(s, wm, wl, c, b, lambda);
    }
    return sum;
}

// Whether the metal's Fresnel is taken per wavelength (measured or filmed).
fn metal_spectral(s: GpuSurface) -> bool {
    return (s.flags & (SURFACE_MEASURED | SURFACE_HAS_FILM)) != 0u;
}

// The share of a photon path's flux from spectral_tint's `t` for it: a
// band path's one value, or a white path's bounce reflectance.
fn spectral_reflectance(t: vec3<f32>, band: u32, lambda_nm: f32) -> f32 {
    if band != WHITE_BAND {
        return t.x;
    }
    return bounce_reflectance(t, band, lambda_nm);
}

// MetalOptics::tint: what a facet met at cosine `c` keeps of each RGB
// channel of a view path (a measured or filmed metal's white path: Σ C_b F(λ_b)).
fn metal_tint(s: GpuSurface, c: f32, band: u32, lambda_nm: f32) -> vec3<f32> {
    if metal_spectral(s) {
        return spectral_tint(s, 1.0, 0.0, c, band, lambda_nm);
    }
    return reflectance(metal_fresnel(s.albedo, c), band, lambda_nm);
}

// MetalOptics::reflectance: the share of a photon path's flux a facet
// met at cosine `c` reflects.
fn metal_reflectance(s: GpuSurface, c: f32, band: u32, lambda_nm: f32) -> f32 {
    if metal_spectral(s) {
        return spectral_reflectance(spectral_tint(s, 1.0, 0.0, c, band, lambda_nm), band, lambda_nm);
    }
    return bounce_reflectance(metal_fresnel(s.albedo, c), band, lambda_nm);
}

// MetalOptics::is_chromatic: where some of it is metal, a measured metal,
// a colour texture, a film, or F0 not grey; a blend's coloured layer.
fn metal_is_chromatic(s: GpuSurface) -> bool {
    let f0 = s.albedo;
    let metal = (s.flags & (SURFACE_MEASURED | SURFACE_HAS_COLOUR_MAP | SURFACE_HAS_FILM)) != 0u || f0.x != f0.y || f0.y != f0.z;
    let blended = (s.flags & SURFACE_BLENDED) != 0u;
    let some_metal = !blended || s.checker_offset.x > 0.0;
    let l = layer_f0(s);
    let layer = s.checker_offset.y > 0.0 && (l.x != l.y || l.y != l.z || (s.flags & SURFACE_HAS_FILM) != 0u);
    return (metal && some_metal) || (layer && blended);
}

// ---- the specular layer of a blend's base (MetalOptics over
// model::metalness::SpecularLayer): F0 per channel in `absorption`, F90
// in checker_offset.y (0: no layer), the base's index in checker_offset.z
// (a film's sits on it). m is the metalness at the point (metalness_at). ----

fn layer_f0(s: GpuSurface) -> vec3<f32> {
    return s.absorption;
}

// SpecularLayer::fresnel
fn layer_fresnel(s: GpuSurface, c: f32) -> vec3<f32> {
    return layer_schlick(layer_f0(s), s.checker_offset.y, c);
}

// metal::layer_filmed: F90 times the film's Airy sum over the base's index.
fn layer_filmed(s: GpuSurface, c: f32, lambda_nm: f32) -> f32 {
    let film = surface_film(s);
    return s.checker_offset.y * thin_film_on(c, 1.0, film.x, vec2<f32>(s.checker_offset.z, 0.0), film.y, film.z, lambda_nm);
}

// Whether there is a layer and a film on it.
fn layer_filmed_here(s: GpuSurface) -> bool {
    return s.checker_offset.y > 0.0 && (s.flags & SURFACE_HAS_FILM) != 0u;
}

// Metalness::specular_share: m + (1 − m) F90.
fn specular_share(s: GpuSurface, m: f32) -> f32 {
    if s.checker_offset.y > 0.0 {
        return m + (1.0 - m) * s.checker_offset.y;
    }
    return m;
}

// MetalOptics::diffuse_share: (1 − m)(1 − max F_layer(cos)) toward a viewer
// at `c` on a path of `band` at `lambda_nm` (under a film, the film's F_layer).
fn blend_diffuse_share(s: GpuSurface, m: f32, c: f32, band: u32, lambda_nm: f32) -> f32 {
    if s.checker_offset.y > 0.0 {
        var f = layer_fresnel(s, c);
        if (s.flags & SURFACE_HAS_FILM) != 0u {
            f = spectral_tint(s, 0.0, 1.0, c, band, lambda_nm);
        }
        return (1.0 - m) * (1.0 - max(f.x, max(f.y, f.z)));
    }
    return (1.0 - m) * 1.0;
}

// MetalOptics::specular_tint: m F_metal + (1 − m) F_layer per RGB channel,
// the spectral parts (a measured or filmed metal, a filmed layer) summed
// in one spectral_tint.
fn specular_tint(s: GpuSurface, m: f32, c: f32, band: u32, lambda_nm: f32) -> vec3<f32> {
    let layer = s.checker_offset.y > 0.0;
    let spectral_metal = m > 0.0 && metal_spectral(s);
    let filmed_layer = layer_filmed_here(s);
    var tint = vec3<f32>(0.0);
    if spectral_metal || filmed_layer {
        tint = spectral_tint(s, select(0.0, m, spectral_metal), select(0.0, 1.0 - m, filmed_layer), c, band, lambda_nm);
    }
    if m > 0.0 && !spectral_metal {
        tint += reflectance(metal_fresnel(s.albedo, c), band, lambda_nm) * m;
    }
    if layer && !filmed_layer {
        tint += reflectance(layer_fresnel(s, c), band, lambda_nm) * (1.0 - m);
    }
    return tint;
}

// MetalOptics::{specular_reflectance, layer_passes} of a photon path
// at once: its survival off the specular part (x; the metal's reflectance
// for a metal without a layer) and the share the layer passes to the base (y).
fn specular_parts(s: GpuSurface, m: f32, c: f32, band: u32, lambda_nm: f32) -> vec2<f32> {
    var metal = 0.0;
    if m > 0.0 {
        metal = metal_reflectance(s, c, band, lambda_nm);
    }
    if s.checker_offset.y <= 0.0 {
        return vec2<f32>(metal, 0.0);
    }
    var layer: f32;
    if (s.flags & SURFACE_HAS_FILM) != 0u {
        layer = spectral_reflectance(spectral_tint(s, 0.0, 1.0, c, band, lambda_nm), band, lambda_nm);
    } else {
        layer = bounce_reflectance(layer_fresnel(s, c), band, lambda_nm);
    }
    let share = specular_share(s, m);
    let passes = max((1.0 - m) * (s.checker_offset.y - layer) / share, 0.0);
    return vec2<f32>((m * metal + (1.0 - m) * layer) / share, passes);
}
