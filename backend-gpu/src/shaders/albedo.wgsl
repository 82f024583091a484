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

// A diffuse surface's base-colour texture (its flags hold the sampler's bits).
fn surface_texture(s: GpuSurface) -> TextureRef {
    return TextureRef(s.texture_first, s.texture_width, s.texture_height, s.flags);
}
