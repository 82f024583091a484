// Reading a texture (twin of prismatic_core::geometry::texture): where
// an image sits in the tables (its 256-entry decoding table, sRGB for a
// base colour or linear for a normal map, then its texels as exact
// integers r + 256 g + 65536 b), its size, and its sampler's bits (the
// SURFACE_TEXTURE_NEAREST bit and the wraps at TEXTURE_WRAP_*_SHIFT).
struct TextureRef {
    first: u32,
    width: u32,
    height: u32,
    flags: u32,
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

// One texel, decoded (the decoding table precedes the texels).
fn fetch_texel(t: TextureRef, i: i32, j: i32) -> vec3<f32> {
    let col = wrap_texel(i, t.width, (t.flags >> TEXTURE_WRAP_U_SHIFT) & 3u);
    let row = wrap_texel(j, t.height, (t.flags >> TEXTURE_WRAP_V_SHIFT) & 3u);
    let x = u32(tables[t.first + 256u + row * t.width + col]);
    let lut = t.first;
    return vec3<f32>(tables[lut + (x & 255u)], tables[lut + ((x >> 8u) & 255u)], tables[lut + (x >> 16u)]);
}

// texture::sample (coordinates are finite: validated corners, non-degenerate triangles).
fn sample_texture(t: TextureRef, uv: vec2<f32>) -> vec3<f32> {
    var x = clamp(uv.x * f32(t.width), -TEXEL_LIMIT, TEXEL_LIMIT);
    var y = clamp(uv.y * f32(t.height), -TEXEL_LIMIT, TEXEL_LIMIT);
    if (t.flags & SURFACE_TEXTURE_NEAREST) != 0u {
        return fetch_texel(t, i32(floor(x)), i32(floor(y)));
    }
    x -= 0.5;
    y -= 0.5;
    let x0 = floor(x);
    let y0 = floor(y);
    let fx = x - x0;
    let fy = y - y0;
    let i = i32(x0);
    let j = i32(y0);
    let top = fetch_texel(t, i, j) * (1.0 - fx) + fetch_texel(t, i + 1, j) * fx;
    let bottom = fetch_texel(t, i, j + 1) * (1.0 - fx) + fetch_texel(t, i + 1, j + 1) * fx;
    return top * (1.0 - fy) + bottom * fy;
}
