// What a surface's textures make of it at a hit: a diffuse surface's
// albedo (checker, texture), a metal's or rough glass's facets (their
// roughness map) and a blended metal's metalness: twins of
// prismatic_core::prepared::PreparedScene's albedo_at, facets and
// metalness_at over the scene's bindings (scene.wgsl), shared by
// the photons, the view rays and light tracing.

// PreparedScene::albedo_at: Surface::albedo_at (checker evaluated a hair
// below the surface) times the texture at the hit's coordinates.
fn albedo_at(hit: Hit, n: vec3<f32>) -> vec3<f32> {
    let s = surfaces[hit.object];
    if s.kind == SURFACE_METAL {
        // A blended metal's diffuse part: its F0 there.
        return metal_at(hit, s).albedo;
    }
    var base = s.albedo;
    if (s.flags & SURFACE_HAS_CHECKER) != 0u {
        let q = (hit.point + s.checker_offset - n * (s.checker_size * 1e-3)) / s.checker_size;
        let parity = floor(q.x) + floor(q.y) + floor(q.z);
        if parity - 2.0 * floor(parity * 0.5) != 0.0 {
            base = s.checker_albedo;
        }
    }
    if (s.flags & SURFACE_HAS_TEXTURE) == 0u {
        return base;
    }
    let uv = texture_coordinates(objects[hit.object], s, hit.triangle, hit.point);
    return base * sample_texture(surface_texture(s), uv);
}

// TriangleUv::at
fn texture_coordinates(obj: GpuObject, s: GpuSurface, tri: u32, p: vec3<f32>) -> vec2<f32> {
    let a = geometry[s.uv_first + 2u * tri];
    let du2 = geometry[s.uv_first + 2u * tri + 1u].xy;
    let b = triangle_barycentrics(obj, tri, p);
    return a.xy + a.zw * b.x + du2 * b.y;
}

// PreparedScene::facets: the GGX α of the metal (in white_ior) or rough
// glass (in albedo.x) `s` at `hit`, its roughness scaled by its roughness
// map's green channel there (Ggx::scaled, so α by its square); 0 where
// polished.
fn facets_alpha(hit: Hit, s: GpuSurface) -> f32 {
    let alpha = select(s.albedo.x, s.white_ior, s.kind == SURFACE_METAL);
    if alpha == 0.0 || (s.flags & SURFACE_HAS_TEXTURE) == 0u {
        return alpha;
    }
    let uv = texture_coordinates(objects[hit.object], s, hit.triangle, hit.point);
    let g = sample_texture(surface_texture(s), uv).y;
    let scaled = alpha * (g * g);
    return select(0.0, max(scaled, MIN_ALPHA), scaled > 0.0);
}

// PreparedScene::metal_at's colour: the metal `s` at `hit` with its F0
// scaled by its colour texture there (SURFACE_HAS_COLOUR_MAP, then
// cleared: the returned surface's F0 is the point's). Its facets stay
// facets_alpha's.
fn metal_at(hit: Hit, s: GpuSurface) -> GpuSurface {
    if (s.flags & SURFACE_HAS_COLOUR_MAP) == 0u {
        return s;
    }
    var m = s;
    let bits = bitcast<vec3<u32>>(s.checker_albedo);
    let colour = TextureRef(bits.x, bits.y, bits.z, bitcast<u32>(s.checker_size));
    let uv = texture_coordinates(objects[hit.object], s, hit.triangle, hit.point);
    m.albedo = s.albedo * sample_texture(colour, uv);
    m.flags = s.flags & ~SURFACE_HAS_COLOUR_MAP;
    return m;
}

// The surface `s` at `hit`: a metal's colour there (metal_at) and a
// film's thickness and factor as its maps say there (PreparedScene::film_at:
// in emission.xy, SURFACE_FILM_AT_HIT set and the map flags cleared).
fn surface_at(hit: Hit, s: GpuSurface) -> GpuSurface {
    var m = metal_at(hit, s);
    let maps = SURFACE_FILM_THICKNESS_MAP | SURFACE_FILM_FACTOR_MAP;
    if (s.flags & maps) == 0u {
        return m;
    }
    let f = s.film_first;
    let uv = texture_coordinates(objects[hit.object], s, hit.triangle, hit.point);
    var thickness = tables[f + 1u];
    var factor = tables[f + 2u];
    if (s.flags & SURFACE_FILM_THICKNESS_MAP) != 0u {
        let min_nm = tables[f + 3u];
        let t = bitcast<vec4<u32>>(vec4<f32>(tables[f + 4u], tables[f + 5u], tables[f + 6u], tables[f + 7u]));
        thickness = min_nm + sample_texture(TextureRef(t.x, t.y, t.z, t.w), uv).y * (thickness - min_nm);
    }
    if (s.flags & SURFACE_FILM_FACTOR_MAP) != 0u {
        let t = bitcast<vec4<u32>>(vec4<f32>(tables[f + 8u], tables[f + 9u], tables[f + 10u], tables[f + 11u]));
        factor *= sample_texture(TextureRef(t.x, t.y, t.z, t.w), uv).x;
    }
    m.emission = vec3<f32>(thickness, factor, 0.0);
    m.flags = (m.flags & ~maps) | SURFACE_FILM_AT_HIT;
    return m;
}

// PreparedScene::metalness_at: the metalness of the metal `s` at `hit`
// (1: a whole metal), its factor times the blue channel of its roughness
// map where SURFACE_METALNESS_MAP.
fn metalness_at(hit: Hit, s: GpuSurface) -> f32 {
    if (s.flags & SURFACE_BLENDED) == 0u {
        return 1.0;
    }
    let factor = s.checker_offset.x;
    if (s.flags & SURFACE_METALNESS_MAP) == 0u {
        return factor;
    }
    let uv = texture_coordinates(objects[hit.object], s, hit.triangle, hit.point);
    return factor * sample_texture(surface_texture(s), uv).z;
}

// A surface's texture: a diffuse surface's base colour, a metal's or
// rough glass's roughness map (its flags hold the sampler's bits).
fn surface_texture(s: GpuSurface) -> TextureRef {
    return TextureRef(s.texture_first, s.texture_width, s.texture_height, s.flags);
}
