// A diffuse surface's albedo at a hit (checker, texture): twin of
// prismatic_core::prepared::PreparedScene::albedo_at over the scene's
// bindings (scene.wgsl), shared by the view rays and light tracing.

// PreparedScene::albedo_at: Surface::albedo_at (checker evaluated a hair
// below the surface) times the texture at the hit's coordinates.
fn albedo_at(hit: Hit, n: vec3<f32>) -> vec3<f32> {
    let s = surfaces[hit.object];
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
    return base * sample_texture(s, texture_coordinates(objects[hit.object], s, hit.triangle, hit.point));
}

// TriangleUv::at
fn texture_coordinates(obj: GpuObject, s: GpuSurface, tri: u32, p: vec3<f32>) -> vec2<f32> {
    let a = geometry[s.uv_first + 2u * tri];
    let du2 = geometry[s.uv_first + 2u * tri + 1u].xy;
    let b = triangle_barycentrics(obj, tri, p);
    return a.xy + a.zw * b.x + du2 * b.y;
}

// texture::wrap_texel (wrap: 0 repeat, 1 clamp to edge, 2 mirrored repeat).
fn wrap_texel(i: i32, size: u32, wrap: u32) -> u32 {
    let n = i32(size);
    if wrap == WRAP_CLAMP_TO_EDGE {
        return u32(clamp(i, 0, n - 1));
    }
    if wrap == WRAP_MIRRORED_REPEAT {
        let m = rem_euclid(i, 2 * n);
        return u32(select(m, 2 * n - 1 - m, m >= n));
    }
    return u32(rem_euclid(i, n));
}

fn rem_euclid(i: i32, n: i32) -> i32 {
    let r = i % n;
    return select(r, r + n, r < 0);
}

// One texel in linear light (the decoding table precedes the texels).
fn fetch_texel(s: GpuSurface, i: i32, j: i32) -> vec3<f32> {
    let col = wrap_texel(i, s.texture_width, (s.flags >> TEXTURE_WRAP_U_SHIFT) & 3u);
    let row = wrap_texel(j, s.texture_height, (s.flags >> TEXTURE_WRAP_V_SHIFT) & 3u);
    let t = u32(tables[s.texture_first + 256u + row * s.texture_width + col]);
    let lut = s.texture_first;
    return vec3<f32>(tables[lut + (t & 255u)], tables[lut + ((t >> 8u) & 255u)], tables[lut + (t >> 16u)]);
}

// texture::sample (coordinates are finite: validated corners, non-degenerate triangles).
fn sample_texture(s: GpuSurface, uv: vec2<f32>) -> vec3<f32> {
    var x = clamp(uv.x * f32(s.texture_width), -TEXEL_LIMIT, TEXEL_LIMIT);
    var y = clamp(uv.y * f32(s.texture_height), -TEXEL_LIMIT, TEXEL_LIMIT);
    if (s.flags & SURFACE_TEXTURE_NEAREST) != 0u {
        return fetch_texel(s, i32(floor(x)), i32(floor(y)));
    }
    x -= 0.5;
    y -= 0.5;
    let x0 = floor(x);
    let y0 = floor(y);
    let fx = x - x0;
    let fy = y - y0;
    let i = i32(x0);
    let j = i32(y0);
    let top = fetch_texel(s, i, j) * (1.0 - fx) + fetch_texel(s, i + 1, j) * fx;
    let bottom = fetch_texel(s, i, j + 1) * (1.0 - fx) + fetch_texel(s, i + 1, j + 1) * fx;
    return top * (1.0 - fy) + bottom * fy;
}
