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
        return surface_at(hit, s).albedo;
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
// polished, and on other surfaces (a diffuse surface's albedo.x is its albedo).
fn facets_alpha(hit: Hit, s: GpuSurface) -> f32 {
    var alpha = 0.0;
    if s.kind == SURFACE_METAL {
        alpha = s.white_ior;
    } else if s.kind == SURFACE_DIELECTRIC {
        alpha = s.albedo.x;
    }
    if alpha == 0.0 || (s.flags & SURFACE_HAS_TEXTURE) == 0u {
        return alpha;
    }
    let uv = texture_coordinates(objects[hit.object], s, hit.triangle, hit.point);
    let g = sample_texture(surface_texture(s), uv).y;
    let scaled = alpha * (g * g);
    return select(0.0, max(scaled, MIN_ALPHA), scaled > 0.0);
}

// The surface `s` at `hit` as its maps make it there, in a copy: a
// metal's F0 times its colour texture (PreparedScene::metal_at's colour;
// SURFACE_HAS_COLOUR_MAP cleared), a film's thickness and factor as its
// maps say (PreparedScene::film_at: in emission.xy, SURFACE_FILM_AT_HIT
// set and the map flags cleared) and a metal's specular layer as its
// maps say (PreparedScene::layer_at: its F0 and F90 in absorption and
// checker_offset.y; F90 0 where the weight is). The maps are read in one
// loop, so each call compiles one copy of sample_texture. A metal's
// facets stay facets_alpha's.
fn surface_at(hit: Hit, s: GpuSurface) -> GpuSurface {
    let films = SURFACE_FILM_THICKNESS_MAP | SURFACE_FILM_FACTOR_MAP;
    let layers = SURFACE_SPECULAR_MAP | SURFACE_SPECULAR_COLOUR_MAP;
    if (s.flags & (SURFACE_HAS_COLOUR_MAP | films | layers)) == 0u {
        return s;
    }
    var m = s;
    let f = s.film_first;
    let l = s.absorption_first;
    if (s.flags & films) != 0u {
        m.emission = vec3<f32>(tables[f + 1u], tables[f + 2u], 0.0);
        m.flags |= SURFACE_FILM_AT_HIT;
    }
    m.flags &= ~(SURFACE_HAS_COLOUR_MAP | films | layers);
    let uv = texture_coordinates(objects[hit.object], s, hit.triangle, hit.point);
    // The layer's weight map's value there, and its F0 at its own weight.
    var weight = 1.0;
    var f0 = s.absorption;
    var flags = array<u32, 5>(SURFACE_HAS_COLOUR_MAP, SURFACE_FILM_THICKNESS_MAP, SURFACE_FILM_FACTOR_MAP,
        SURFACE_SPECULAR_MAP, SURFACE_SPECULAR_COLOUR_MAP);
    // 0: the colour map (its reference in the checker's fields); 1, 2: the
    // film's thickness and factor maps (theirs after the film's record);
    // 3, 4: the layer's weight and colour maps (theirs after its F0).
    for (var k = 0u; k < 5u; k++) {
        if (s.flags & flags[k]) == 0u {
            continue;
        }
        var bits = vec4<u32>(bitcast<vec3<u32>>(s.checker_albedo), bitcast<u32>(s.checker_size));
        if k > 0u {
            let r = select(f + 4u * k, l + 4u * (k - 2u), k > 2u);
            bits = bitcast<vec4<u32>>(vec4<f32>(tables[r], tables[r + 1u], tables[r + 2u], tables[r + 3u]));
        }
        let v = sample_texture(TextureRef(bits.x, bits.y, bits.z, bits.w), uv);
        if k == 0u {
            m.albedo = s.albedo * v;
        } else if k == 1u {
            let min_nm = tables[f + 3u];
            m.emission.x = min_nm + v.y * (tables[f + 1u] - min_nm);
        } else if k == 2u {
            m.emission.y = tables[f + 2u] * v.x;
        } else if k == 3u {
            weight = v.x;
        } else {
            f0 = min(vec3<f32>(tables[l], tables[l + 1u], tables[l + 2u]) * v, vec3<f32>(1.0)) * s.checker_offset.y;
        }
    }
    if (s.flags & layers) != 0u {
        m.absorption = f0 * weight;
        m.checker_offset.y = s.checker_offset.y * weight;
    }
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
