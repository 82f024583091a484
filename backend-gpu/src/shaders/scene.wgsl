// Ray–scene intersection over the scene on the device (its bindings:
// scene_bindings.wgsl, or the gather's own, gather.wgsl):
// twins of prismatic_core::geometry (primitives) and
// prismatic_core::prepared (nearest hit, occlusion, surface indices).

// A mesh's triangle hit (`triangle`, in its hierarchy's order) or 0.
struct SurfaceHit {
    ok: bool,
    t: f32,
    normal: vec3<f32>,
    triangle: u32,
}

struct Hit {
    ok: bool,
    t: f32,
    point: vec3<f32>,
    normal: vec3<f32>,
    object: u32,
    triangle: u32,
}

fn no_hit() -> SurfaceHit {
    return SurfaceHit(false, 0.0, vec3<f32>(0.0), 0u);
}

fn plane_t(o: vec3<f32>, d: vec3<f32>, point: vec3<f32>, normal: vec3<f32>) -> vec2<f32> {
    let denom = dot(d, normal);
    if abs(denom) < 1e-12 {
        return vec2<f32>(0.0, 0.0);
    }
    return vec2<f32>(dot(point - o, normal) / denom, 1.0);
}

// Primitive::intersect_sphere (the normal normalised: see there).
fn hit_sphere(o: vec3<f32>, d: vec3<f32>, center: vec3<f32>, radius: f32, t_min: f32, t_max: f32) -> SurfaceHit {
    let f = o - center;
    let b = dot(f, d);
    let perp = f - d * b;
    let disc = radius * radius - dot(perp, perp);
    if disc < 0.0 {
        return no_hit();
    }
    let c = dot(f, f) - radius * radius;
    let q = -b - copysign(sqrt(disc), b);
    var t0 = 0.0;
    var t1 = 0.0;
    if q != 0.0 {
        t0 = c / q;
        t1 = q;
    }
    let near = select(t1, t0, t0 < t1);
    let far = select(t0, t1, t0 < t1);
    var t: f32;
    if near > t_min && near < t_max {
        t = near;
    } else if far > t_min && far < t_max {
        t = far;
    } else {
        return no_hit();
    }
    return SurfaceHit(true, t, nrm(o + d * t - center), 0u);
}

fn hit_convex(o: vec3<f32>, d: vec3<f32>, first: u32, count: u32, t_min: f32, t_max: f32) -> SurfaceHit {
    let skin = SURFACE_SKIN_FACTOR * surface_offset(o);
    var t_enter = -BIG;
    var t_exit = BIG;
    var n_enter = vec3<f32>(0.0);
    var n_exit = vec3<f32>(0.0);
    for (var i = 0u; i < count; i++) {
        let face = geometry[first + i];
        let denom = dot(face.xyz, d);
        var dist = face.w - dot(face.xyz, o);
        if denom < 0.0 && dist < 0.0 && dist > -skin {
            dist = 0.0;
        }
        if denom == 0.0 {
            if dist < 0.0 {
                return no_hit();
            }
            continue;
        }
        let t = dist / denom;
        if denom < 0.0 {
            if t > t_enter {
                t_enter = t;
                n_enter = face.xyz;
            }
        } else if t < t_exit {
            t_exit = t;
            n_exit = face.xyz;
        }
    }
    if t_enter > t_exit {
        return no_hit();
    }
    if t_enter > t_min && t_enter < t_max {
        return SurfaceHit(true, t_enter, n_enter, 0u);
    }
    if t_exit > t_min && t_exit < t_max {
        return SurfaceHit(true, t_exit, n_exit, 0u);
    }
    return no_hit();
}

// geometry::intersect_triangle; returns t, or -1 for a miss (t_min ≥ 0 always).
fn hit_triangle(o: vec3<f32>, d: vec3<f32>, tri: u32, t_min: f32, t_max: f32, skin: f32) -> f32 {
    let v0 = geometry[tri].xyz;
    let e1 = geometry[tri + 1u].xyz;
    let e2 = geometry[tri + 2u].xyz;
    let normal = geometry[tri + 3u].xyz;
    let p = cross(d, e2);
    let det = dot(e1, p);
    if abs(det) < 1e-12 {
        return -1.0;
    }
    let height = dot(normal, o - v0);
    if height > 0.0 && height < skin && dot(normal, d) < 0.0 {
        return -1.0;
    }
    let inv = 1.0 / det;
    let s = o - v0;
    let u = dot(s, p) * inv;
    let lo = -BARYCENTRIC_EPS;
    let hi = 1.0 + BARYCENTRIC_EPS;
    if !(u >= lo && u <= hi) {
        return -1.0;
    }
    let q = cross(s, e1);
    let v = dot(d, q) * inv;
    if v < lo || u + v > hi {
        return -1.0;
    }
    let t = dot(e2, q) * inv;
    if t > t_min && t < t_max {
        return t;
    }
    return -1.0;
}

// bvh::inverse_direction
fn inverse_direction(d: vec3<f32>) -> vec3<f32> {
    let tiny = 1e-30;
    let guarded = vec3<f32>(copysign(tiny, d.x), copysign(tiny, d.y), copysign(tiny, d.z));
    return 1.0 / select(d, guarded, abs(d) < vec3<f32>(tiny));
}

// bvh::box_entry for node record `node` (lo, first; hi, count): the entry
// distance, or -1 when the ray misses the box before `limit`.
fn box_entry(o: vec3<f32>, inv: vec3<f32>, node: u32, limit: f32) -> f32 {
    let a = (geometry[node].xyz - o) * inv;
    let b = (geometry[node + 1u].xyz - o) * inv;
    let lo = min(a, b);
    let hi = max(a, b);
    let near = max(max(max(lo.x, lo.y), lo.z), 0.0);
    let far = min(min(hi.x, hi.y), hi.z);
    if near <= far && near <= limit * BOX_MARGIN {
        return near;
    }
    return -1.0;
}

// The mesh's traversal state: NearestTriangle, or the any-hit flag.
struct MeshSearch {
    skin: f32,
    has_enter: bool,
    t_enter: f32,
    i_enter: u32,
    has_leave: bool,
    t_leave: f32,
    i_leave: u32,
    any: bool,
}

// NearestTriangle::reach
fn search_reach(s: MeshSearch) -> f32 {
    var r = BIG;
    if s.has_enter {
        r = s.t_enter;
    }
    if s.has_leave {
        r = min(r, s.t_leave + s.skin);
    }
    return r;
}

// MeshBvh::intersect (any_hit false) and MeshBvh::hits_any (true): nodes
// from record obj.first, triangles from record obj.second.
fn search_mesh(o: vec3<f32>, d: vec3<f32>, obj: GpuObject, t_min: f32, t_max: f32, any_hit: bool) -> MeshSearch {
    var s = MeshSearch(SURFACE_SKIN_FACTOR * surface_offset(o), false, 0.0, 0u, false, 0.0, 0u, false);
    let inv = inverse_direction(d);
    var limit = t_max;
    if box_entry(o, inv, obj.first, limit) < 0.0 {
        return s;
    }
    var pending: array<u32, MAX_BVH_DEPTH>;
    var depth = 0u;
    var node = 0u;
    loop {
        let record = obj.first + 2u * node;
        let first = bitcast<u32>(geometry[record].w);
        let count = bitcast<u32>(geometry[record + 1u].w);
        var descend = false;
        if count > 0u {
            for (var index = first; index < first + count; index++) {
                let tri = obj.second + 4u * index;
                let t = hit_triangle(o, d, tri, t_min, t_max, s.skin);
                if t < 0.0 {
                    continue;
                }
                if any_hit {
                    s.any = true;
                    return s;
                }
                if t > search_reach(s) {
                    continue;
                }
                if dot(geometry[tri + 3u].xyz, d) < 0.0 {
                    if !s.has_enter || t < s.t_enter || (t == s.t_enter && index < s.i_enter) {
                        s.has_enter = true;
                        s.t_enter = t;
                        s.i_enter = index;
                    }
                } else if !s.has_leave || t < s.t_leave || (t == s.t_leave && index < s.i_leave) {
                    s.has_leave = true;
                    s.t_leave = t;
                    s.i_leave = index;
                }
            }
            limit = min(search_reach(s), t_max);
        } else {
            let ta = box_entry(o, inv, obj.first + 2u * first, limit);
            let tb = box_entry(o, inv, obj.first + 2u * (first + 1u), limit);
            if ta >= 0.0 && tb >= 0.0 {
                var near = first;
                var far = first + 1u;
                if tb < ta {
                    near = first + 1u;
                    far = first;
                }
                pending[depth] = far;
                depth++;
                node = near;
                descend = true;
            } else if ta >= 0.0 {
                node = first;
                descend = true;
            } else if tb >= 0.0 {
                node = first + 1u;
                descend = true;
            }
        }
        if !descend {
            // Pop the next node still within reach.
            var found = false;
            loop {
                if depth == 0u {
                    break;
                }
                depth--;
                if box_entry(o, inv, obj.first + 2u * pending[depth], limit) >= 0.0 {
                    node = pending[depth];
                    found = true;
                    break;
                }
            }
            if !found {
                return s;
            }
        }
    }
    return s;
}

// Primitive::intersect for a mesh: NearestTriangle::result.
fn hit_mesh(o: vec3<f32>, d: vec3<f32>, obj: GpuObject, t_min: f32, t_max: f32) -> SurfaceHit {
    let s = search_mesh(o, d, obj, t_min, t_max, false);
    if s.has_enter && (!s.has_leave || s.t_enter < s.t_leave + s.skin) {
        return SurfaceHit(true, s.t_enter, geometry[obj.second + 4u * s.i_enter + 3u].xyz, s.i_enter);
    }
    if s.has_leave {
        return SurfaceHit(true, s.t_leave, geometry[obj.second + 4u * s.i_leave + 3u].xyz, s.i_leave);
    }
    return no_hit();
}

fn hit_object(obj: GpuObject, o: vec3<f32>, d: vec3<f32>, t_min: f32, t_max: f32) -> SurfaceHit {
    switch obj.kind {
        case OBJECT_SPHERE: {
            return hit_sphere(o, d, obj.a, obj.ra, t_min, t_max);
        }
        case OBJECT_PLANE: {
            let t = plane_t(o, d, obj.a, obj.n);
            if t.y != 0.0 && t.x > t_min && t.x < t_max {
                return SurfaceHit(true, t.x, obj.n, 0u);
            }
            return no_hit();
        }
        case OBJECT_DISK: {
            let t = plane_t(o, d, obj.a, obj.n);
            if t.y == 0.0 || !(t.x > t_min && t.x < t_max) {
                return no_hit();
            }
            let r = o + d * t.x - obj.a;
            let d2 = dot(r, r);
            if d2 <= obj.ra && d2 >= obj.rb {
                return SurfaceHit(true, t.x, obj.n, 0u);
            }
            return no_hit();
        }
        case OBJECT_CONVEX: {
            return hit_convex(o, d, obj.first, obj.count, t_min, t_max);
        }
        default: {
            return hit_mesh(o, d, obj, t_min, t_max);
        }
    }
}

// PreparedScene::intersect: the nearest hit closer than t_max.
fn intersect_scene(o: vec3<f32>, d: vec3<f32>, t_max: f32) -> Hit {
    var best = Hit(false, 0.0, vec3<f32>(0.0), vec3<f32>(0.0), 0u, 0u);
    var limit = t_max;
    for (var i = 0u; i < params.object_count; i++) {
        let h = hit_object(objects[i], o, d, 0.0, limit);
        if h.ok {
            limit = h.t;
            best = Hit(true, h.t, o + d * h.t, h.normal, i, h.triangle);
        }
    }
    return best;
}

// Triangle::barycentrics of p on mesh `obj`'s triangle `tri`.
fn triangle_barycentrics(obj: GpuObject, tri: u32, p: vec3<f32>) -> vec2<f32> {
    let r = obj.second + 4u * tri;
    return barycentrics(geometry[r].xyz, geometry[r + 1u].xyz, geometry[r + 2u].xyz, p);
}

// PreparedScene::scattering_normal: what a ray arriving along `d` at `hit`
// scatters about off a mirror, metal or glass, and what a diffuse surface
// takes its lights' cosines with (a mesh's vertex normals interpolated,
// TriangleNormals::at, tilted by its normal map, then bent by
// shading_normal; the geometric normal elsewhere). A smooth mesh's `rb`
// holds the first of its triangles' normal records (n0, d1, d2) as bits;
// a normal-mapped mesh's `ra` its map's first record (normal_map_texel).
fn scattering_normal(hit: Hit, d: vec3<f32>) -> vec3<f32> {
    let obj = objects[hit.object];
    let first = bitcast<u32>(obj.rb);
    let map = bitcast<u32>(obj.ra);
    if obj.kind != OBJECT_MESH || (first == NO_VERTEX_NORMALS && map == NO_NORMAL_MAP) {
        return hit.normal;
    }
    let b = triangle_barycentrics(obj, hit.triangle, hit.point);
    var n = hit.normal;
    if first != NO_VERTEX_NORMALS {
        let k = first + 3u * hit.triangle;
        n = geometry[k].xyz + geometry[k + 1u].xyz * b.x + geometry[k + 2u].xyz * b.y;
    }
    if map != NO_NORMAL_MAP {
        // Vec3::normalize_or(geometric)
        let length = length(n);
        if length > 0.0 {
            n = n * (1.0 / length);
        } else {
            n = hit.normal;
        }
        // The triangle's records follow the map's two: its texture
        // coordinates (uv0, du1; du2) and tangents (t0 with the sign; d1; d2).
        let k = map + 2u + 5u * hit.triangle;
        let a = geometry[k];
        let uv = a.xy + a.zw * b.x + geometry[k + 1u].xy * b.y;
        let t = geometry[k + 2u];
        let tangent = t.xyz + geometry[k + 3u].xyz * b.x + geometry[k + 4u].xyz * b.y;
        let m = geometry[map];
        let image = TextureRef(bitcast<u32>(m.x), bitcast<u32>(m.y), bitcast<u32>(m.z), bitcast<u32>(m.w));
        n = mapped_normal(n, tangent, t.w, sample_texture(image, uv), geometry[map + 1u].x);
    }
    return shading_normal(d, hit.normal, n);
}

// PreparedScene::occluded (Primitive::hits)
fn occluded(o: vec3<f32>, d: vec3<f32>, dist: f32) -> bool {
    for (var i = 0u; i < params.object_count; i++) {
        let obj = objects[i];
        if obj.kind == OBJECT_MESH {
            if search_mesh(o, d, obj, 0.0, dist, true).any {
                return true;
            }
        } else if hit_object(obj, o, d, 0.0, dist).ok {
            return true;
        }
    }
    return false;
}

// DielectricOptics::ior
fn band_ior(s: GpuSurface, band: u32) -> f32 {
    if band == WHITE_BAND {
        return s.white_ior;
    }
    return tables[s.ior_first + band];
}

// Absorption::coefficient: σ of a band, or of a white photon (the channels' mean).
fn absorption_coefficient(s: GpuSurface, band: u32) -> f32 {
    if band == WHITE_BAND {
        return (s.absorption.x + s.absorption.y + s.absorption.z) / 3.0;
    }
    return tables[s.absorption_first + band];
}

// EnvironmentLookup::texel_at: the map's texel (x, y), x wrapping, y clamped.
fn env_texel(x: i32, y: i32) -> vec3<f32> {
    let w = i32(params.env_width);
    let row = min(y, i32(params.env_height) - 1);
    let i = params.env_first + 3u * u32(row * w + ((x % w) + w) % w);
    return vec3<f32>(tables[i], tables[i + 1u], tables[i + 2u]);
}

// acos to 2e-8 (Abramowitz & Stegun 4.4.46): drivers' own may be 1e-4 off
// (lavapipe's is), which moves a sky's edge by a visible fraction of a texel.
fn precise_acos(x: f32) -> f32 {
    let a = abs(x);
    let p = ((((((-0.0012624911 * a + 0.0066700901) * a - 0.0170881256) * a + 0.0308918810) * a - 0.0501743046) * a
        + 0.0889789874) * a - 0.2145988016) * a + 1.5707963050;
    let r = sqrt(1.0 - a) * p;
    return select(r, PI - r, x < 0.0);
}

// atan2 to 4e-8 (Abramowitz & Stegun 4.4.49 on the smaller over the larger
// of |y|, |x|), for the same reason.
fn precise_atan2(y: f32, x: f32) -> f32 {
    let ax = abs(x);
    let ay = abs(y);
    let big = max(ax, ay);
    if big == 0.0 {
        return 0.0;
    }
    let t = min(ax, ay) / big;
    let t2 = t * t;
    let p = ((((((-0.0040540580 * t2 + 0.0218612288) * t2 - 0.0559098861) * t2 + 0.0964200441) * t2 - 0.1390853351) * t2
        + 0.1994653599) * t2 - 0.3332985605) * t2 + 0.9999993329;
    var r = t * p;
    if ay > ax {
        r = 0.5 * PI - r;
    }
    if x < 0.0 {
        r = PI - r;
    }
    return select(r, -r, y < 0.0);
}

// PreparedScene::background: what a ray leaving the scene along unit `d`
// sees, the environment (EnvironmentLookup::radiance, bilinear) or the
// background colour.
fn background(d: vec3<f32>) -> vec3<f32> {
    if params.env_strength == 0.0 {
        return params.background;
    }
    let u = 0.5 + precise_atan2(d.x, -d.z) / (2.0 * PI) + params.env_turn;
    let v = precise_acos(clamp(d.y, -1.0, 1.0)) / PI;
    let fx = (u - floor(u)) * f32(params.env_width) - 0.5;
    let fy = clamp(v * f32(params.env_height) - 0.5, 0.0, f32(params.env_height - 1u));
    let x0 = floor(fx);
    let y0 = floor(fy);
    let tx = fx - x0;
    let ty = fy - y0;
    let xi = i32(x0);
    let yi = i32(y0);
    let top = env_texel(xi, yi) * (1.0 - tx) + env_texel(xi + 1, yi) * tx;
    let bottom = env_texel(xi, yi + 1) * (1.0 - tx) + env_texel(xi + 1, yi + 1) * tx;
    return (top * (1.0 - ty) + bottom * ty) * params.env_strength;
}

// DielectricOptics::thin: a sheet that rays pass straight through.
fn is_sheet(s: GpuSurface) -> bool {
    return (s.flags & SURFACE_THIN) != 0u;
}

// DielectricOptics::sheet_crossing_rgb: what a view ray of `band` keeps of
// each channel when it crosses a tinted thin sheet (1 elsewhere).
fn sheet_crossing_rgb(s: GpuSurface, band: u32) -> vec3<f32> {
    if !is_sheet(s) || (s.flags & SURFACE_ABSORBS) == 0u {
        return vec3<f32>(1.0);
    }
    if band == WHITE_BAND {
        return exp(-s.absorption);
    }
    return vec3<f32>(exp(-absorption_coefficient(s, band)));
}

// view::glass_transmittance: what a view ray keeps of each channel on a
// segment of length t that ends on the glass (only a segment inside counts).
fn glass_transmittance(s: GpuSurface, dir: vec3<f32>, normal: vec3<f32>, t: f32, band: u32) -> vec3<f32> {
    if (s.flags & SURFACE_ABSORBS) == 0u || is_sheet(s) || !(dot(dir, normal) > 0.0) {
        return vec3<f32>(1.0);
    }
    if band == WHITE_BAND {
        return vec3<f32>(exp(-s.absorption.x * t), exp(-s.absorption.y * t), exp(-s.absorption.z * t));
    }
    return vec3<f32>(exp(-absorption_coefficient(s, band) * t));
}

// IorCurve::at
fn curve_at(s: GpuSurface, lambda_nm: f32) -> f32 {
    let x = clamp(lambda_nm - VISIBLE_NM_LO, 0.0, f32(s.curve_len - 1u));
    let i = min(u32(x), s.curve_len - 2u);
    let f = x - f32(i);
    let a = tables[s.curve_first + i];
    return a + (tables[s.curve_first + i + 1u] - a) * f;
}

// DielectricOptics::ior_at_wavelength (lambda_nm < 0: no wavelength of its own).
fn path_ior(s: GpuSurface, band: u32, lambda_nm: f32) -> f32 {
    let n = band_ior(s, band);
    if lambda_nm < 0.0 || (s.flags & SURFACE_HAS_CURVE) == 0u {
        return n;
    }
    return n + (curve_at(s, lambda_nm) - curve_at(s, bands[band].lambda_nm));
}

// The film of the surface `s` (SURFACE_HAS_FILM): its index, thickness
// and factor, as they are at the hit where surface_at made `s`.
fn surface_film(s: GpuSurface) -> vec3<f32> {
    let f = s.film_first;
    if (s.flags & SURFACE_FILM_AT_HIT) != 0u {
        return vec3<f32>(tables[f], s.emission.x, s.emission.y);
    }
    return vec3<f32>(tables[f], tables[f + 1u], tables[f + 2u]);
}

// DielectricOptics::face: the path's index, and the film seen at its own
// wavelength, else its band's centre, else (white) the middle band's.
fn path_face(s: GpuSurface, band: u32, lambda_nm: f32) -> Face {
    let ior = path_ior(s, band, lambda_nm);
    if (s.flags & SURFACE_HAS_FILM) == 0u {
        return bare_face(ior, is_sheet(s));
    }
    var lambda = lambda_nm;
    if lambda < 0.0 {
        var b = band;
        if band == WHITE_BAND {
            b = params.band_count / 2u;
        }
        lambda = bands[b].lambda_nm;
    }
    let film = surface_film(s);
    return Face(ior, is_sheet(s), film.x, film.y, film.z, lambda);
}

struct SpectrumSample {
    band: u32,
    // < 0 for none (the band's own index).
    lambda_nm: f32,
}

// trace::spectrum_share: share `share` of `shares`, shifted by the number `u`.
fn spectrum_share(u: f32, share: u32, shares: u32) -> SpectrumSample {
    let n = params.band_count;
    let scaled = (f32(share) + u) / f32(shares) * f32(n);
    let band = min(u32(scaled), n - 1u);
    var lambda_nm = -1.0;
    if params.wavelengths == WAVELENGTHS_CONTINUOUS || params.wavelengths == WAVELENGTHS_HERO {
        let b = bands[band];
        lambda_nm = b.lo_nm + (b.hi_nm - b.lo_nm) * (scaled - f32(band));
    }
    return SpectrumSample(band, lambda_nm);
}

// trace::spectrum_share_of a coloured light's spectrum: the band ⌊v·N⌋,
// the wavelength the light's table puts at v.
fn light_spectrum_share(l: GpuLight, u: f32, share: u32, shares: u32) -> SpectrumSample {
    var s = spectrum_share(u, share, shares);
    if s.lambda_nm >= 0.0 {
        s.lambda_nm = light_wavelength(l, (f32(share) + u) / f32(shares));
    }
    return s;
}

// LightSpectrum::wavelength: the entry whose cumulative probability first
// exceeds v, and the point inside it.
fn light_wavelength(l: GpuLight, v: f32) -> f32 {
    let first = l.spectrum_first;
    let len = l.spectrum_len;
    var lo = 0u;
    var hi = len;
    while lo < hi {
        let mid = (lo + hi) / 2u;
        if tables[first + mid] <= v {
            lo = mid + 1u;
        } else {
            hi = mid;
        }
    }
    let k = min(lo, len - 1u);
    var before = 0.0;
    if k > 0u {
        before = tables[first + k - 1u];
    }
    let p = tables[first + k] - before;
    var f = 0.0;
    if p > 0.0 {
        f = clamp((v - before) / p, 0.0, 1.0);
    }
    return tables[first + len + k] + tables[first + 2u * len + k] * f;
}
