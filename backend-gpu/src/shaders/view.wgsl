// The view rays: twin of prismatic_core::view.
// One invocation per pixel. WGSL has no recursion, so the reference's
// recursion becomes a stack of pending rays, each with the RGB tint and
// the weight it carries back to the pixel (as the CPU backend's queue
// does); the split of a white view ray into bands is a stack entry that
// hands out one band at a time. Direct light, ambient and background go
// straight into the pixel; each diffuse hit that needs the caustic becomes
// a visible point for gather.wgsl, appended to the chunk's points with the
// pixel it belongs to, so that no invocation runs a gather (a software
// device caps the loop iterations of one invocation) and the gathers run
// over the points there are, not over slots per pixel.
//
// Per-pass view paths (ViewPaths::Hero and ::Sampled, params.view_paths
// other than VIEW_PATHS_CENTRE) take pass params.view_pass's numbers of
// prismatic_core::pixel_sample: M hero paths (each at its own wavelength
// with continuous wavelengths) at the first dispersive glass, handed out
// by the split entry like bands, and with sampled paths a jittered start
// and one Fresnel branch at glass (a pixel then has at most M visible
// points); their first radius is the pixel's.

@group(1) @binding(0) var<storage, read_write> pixels: array<vec4<f32>>;
@group(1) @binding(1) var<storage, read_write> points: array<VisiblePoint>;
// Points appended so far (those past `point_capacity` are counted, not
// written: the host reads the count back and traces again with room), and
// the pixels whose paths the device cut short (RenderStats::view_paths_cut).
struct ViewCounts {
    points: atomic<u32>,
    cut: atomic<u32>,
}
@group(1) @binding(2) var<storage, read_write> counts: ViewCounts;
// Per pixel of the chunk: its first radius as a fraction of R, stored as
// the complement of its bits (0: none, the pilot found no point there;
// see session.wgsl's first_radius).
@group(1) @binding(3) var<storage, read> pixel_ratios: array<u32>;

struct Pending {
    origin: vec3<f32>,
    weight: f32,
    dir: vec3<f32>,
    band: u32,
    tint: vec3<f32>,
    depth: u32,
    // For a band split: the glass's outward normal at `origin` (the hit point).
    normal: vec3<f32>,
    // NO_SPLIT for a ray to trace, else the next band to hand out.
    next_band: u32,
    // The glass at `origin` for a band split, and its mesh triangle.
    object: u32,
    triangle: u32,
    // The path's wavelength (< 0: its band's own index).
    lambda_nm: f32,
    // A sampled path's hero path (0 before the split).
    hero: u32,
    // It left a rough surface where the hidden lights' light is counted
    // (view::behind_rough): no highlights, no rough visible points.
    behind: bool,
}

const NO_SPLIT: u32 = 0xffffffffu;

// A pending ray as the stack keeps it: 12 words, not a `Pending`'s 20.
// Lavapipe keeps the stack in registers, each access with a varying index
// a chain of selects, and its compile time grows faster than the stack's
// words: at depth 44 (48 entries) the view pipeline compiled in 95 s with
// whole entries and 54 s with these, at depth 64 in about 200 s and 94 s
// (2026-11-29, 2-core container).
struct Stacked {
    origin: vec3<f32>,
    weight: f32,
    dir: vec3<f32>,
    lambda_nm: f32,
    tint: vec3<f32>,
    // band (16 bits), depth (8), hero (7) and behind (1); SPLIT_PENDING
    // for the split.
    packed: u32,
}

// The stacked entry that stands for `split`.
const SPLIT_PENDING: u32 = 0xffffffffu;

var<private> stack: array<Stacked, STACK_SIZE>;
var<private> top: u32;
// The one band split pending, whole (its glass's hit and next band): only
// a white ray splits, and everything above a split on the stack is one of
// its bands' rays, so a split is handed out to its end before a white ray
// below it can meet glass and split again.
var<private> split: Pending;

// `e` as the stack keeps it (a split kept whole in `split`).
fn stacked(e: Pending) -> Stacked {
    if e.next_band != NO_SPLIT {
        split = e;
        return Stacked(vec3<f32>(0.0), 0.0, vec3<f32>(0.0), 0.0, vec3<f32>(0.0), SPLIT_PENDING);
    }
    let packed = e.band | (e.depth << 16u) | (e.hero << 24u) | (u32(e.behind) << 31u);
    return Stacked(e.origin, e.weight, e.dir, e.lambda_nm, e.tint, packed);
}

fn pop() -> Pending {
    top--;
    let s = stack[top];
    if s.packed == SPLIT_PENDING {
        return split;
    }
    let band = s.packed & 0xffffu;
    let depth = (s.packed >> 16u) & 0xffu;
    let hero = (s.packed >> 24u) & 0x7fu;
    let behind = (s.packed >> 31u) != 0u;
    return Pending(s.origin, s.weight, s.dir, band, s.tint, depth, vec3<f32>(0.0), NO_SPLIT, 0u, 0u, s.lambda_nm, hero, behind);
}

// What the entry being handled spawns, pushed in one place (each access
// to `stack` is a chain of selects on lavapipe, see `Stacked`).
var<private> kids: array<Stacked, 3>;
var<private> kid_count: u32;
// A sampled path's pixel scramble (PixelSampler).
var<private> scramble: u32;

// The surface whose light a visit adds (ViewContext's shade_diffuse and
// highlights): the path as it met it, where, and rough glass's face.
struct LightQuery {
    on: bool,
    e: Pending,
    hit: Hit,
    face: Face,
    // The surface there as its maps make it (surface_at), read once, and
    // a metal's metalness there (metalness_at; 1 elsewhere).
    s: GpuSurface,
    metalness: f32,
}
var<private> light_query: LightQuery;

// Whether each pass traces its own paths (ViewPaths::per_pass).
fn per_pass() -> bool {
    return params.view_paths != VIEW_PATHS_CENTRE;
}

// Whether a path starts jittered and takes one Fresnel branch (ViewPaths::jittered).
fn jittered() -> bool {
    return params.view_paths == VIEW_PATHS_SAMPLED;
}

fn spawn(e: Pending) {
    kids[kid_count] = stacked(e);
    kid_count++;
}

fn spawn_ray(e: Pending, origin: vec3<f32>, dir: vec3<f32>, band: u32, weight: f32, tint: vec3<f32>) {
    spawn(Pending(origin, weight, dir, band, tint, e.depth + 1u, vec3<f32>(0.0), NO_SPLIT, 0u, 0u, e.lambda_nm, e.hero, e.behind));
}

// One branch off rough glass: its weight times, where it `crossed` a
// tinted sheet, the crossing's colour.
fn follow_rough(e: Pending, s: Scattered, w: f32, crossed: bool, crossing: vec3<f32>, band: u32, weight: f32, tint: vec3<f32>) {
    var f = vec3<f32>(w);
    if crossed {
        f = crossing * w;
    }
    let next = weight * max(f.x, max(f.y, f.z));
    if next > MIN_VIEW_WEIGHT {
        spawn_ray(e, s.origin, s.dir, band, next, tint * f);
    }
}

// ViewContext::through_dielectric: the Fresnel-weighted reflection and
// refraction (a jittered path: the one branch its number chooses); rough
// glass: off one facet (through_rough_dielectric), its highlights left to
// `light_query`.
fn through_dielectric(e: Pending, face: Face, band: u32, weight: f32, tint: vec3<f32>) {
    let thin = face.thin;
    // What crossing a tinted sheet keeps (1 elsewhere).
    let crossing = sheet_crossing_rgb(surfaces[e.object], band);
    let kept = max(crossing.x, max(crossing.y, crossing.z));
    let hit = Hit(true, 0.0, e.origin, e.normal, e.object, e.triangle);
    let alpha = facets_alpha(hit, surfaces[e.object]);
    if alpha > 0.0 {
        var on = e;
        on.behind = behind_rough(e.behind, e.depth, alpha);
        let at = Pending(e.origin, weight, e.dir, band, tint, e.depth, e.normal, NO_SPLIT, e.object, e.triangle, e.lambda_nm, e.hero, e.behind);
        light_query = LightQuery(true, at, hit, face, surfaces[e.object], 1.0);
        let facet = pixel_facet(scramble, select(0u, params.view_pass, per_pass()), e.hero, e.depth);
        if jittered() {
            let u = pixel_branch(scramble, params.view_pass, e.hero, e.depth);
            let b = scatter_rough_dielectric(e.dir, e.origin, e.normal, face, alpha, facet, u);
            if b.ok {
                follow_rough(on, Scattered(b.origin, b.dir), b.unshadowed, b.crossed, crossing, band, weight, tint);
            }
            return;
        }
        let split = split_rough_dielectric(e.dir, e.origin, e.normal, face, alpha, facet);
        if split.crossed_weight >= 0.0 {
            follow_rough(on, split.crossed, split.crossed_weight, true, crossing, band, weight, tint);
        }
        if split.reflected_weight >= 0.0 {
            follow_rough(on, split.reflected, split.reflected_weight, false, crossing, band, weight, tint);
        }
        return;
    }
    if jittered() {
        let s = scatter_dielectric(e.dir, e.origin, e.normal, face, pixel_branch(scramble, params.view_pass, e.hero, e.depth));
        if thin && all(s.dir == e.dir) {
            spawn_ray(e, s.origin, s.dir, band, weight * kept, tint * crossing);
        } else {
            spawn_ray(e, s.origin, s.dir, band, weight, tint);
        }
        return;
    }
    let split = split_dielectric(e.dir, e.origin, e.normal, face);
    let r = split.reflectance;
    let t = 1.0 - r;
    if t * weight > MIN_VIEW_WEIGHT && !split.tir {
        spawn_ray(e, split.refracted.origin, split.refracted.dir, band, weight * t * kept, tint * t * crossing);
    }
    if r * weight > MIN_VIEW_WEIGHT {
        spawn_ray(e, split.reflected.origin, split.reflected.dir, band, weight * r, tint * r);
    }
}

// One edge (x to y, relative to the point) of form_factor::triangle_view's
// clipping: x if above the tangent plane, and where the edge crosses it.
fn clip_edge(x: vec3<f32>, y: vec3<f32>, n: vec3<f32>, corners: ptr<function, array<vec3<f32>, 4>>, count: ptr<function, u32>) {
    let hx = dot(x, n);
    let hy = dot(y, n);
    if hx > 0.0 {
        (*corners)[*count] = x;
        *count += 1u;
    }
    if (hx > 0.0) != (hy > 0.0) {
        (*corners)[*count] = x + (y - x) * (hx / (hx - hy));
        *count += 1u;
    }
}

// One edge's term of Lambert's formula: Θ (n · γ̂).
fn edge_term(x: vec3<f32>, y: vec3<f32>, n: vec3<f32>) -> f32 {
    let c = cross(x, y);
    let sin_len = sqrt(dot(c, c));
    if sin_len > 0.0 {
        return atan2(sin_len, dot(x, y)) * dot(c, n) / sin_len;
    }
    return 0.0;
}

// geometry::form_factor::triangle_view: the projected solid angle of the
// part of triangle (a, b, c) above p's tangent plane (xyz: that part's
// centre, w: the angle; w = 0 when none of it is). Written without loops:
// lavapipe's per-invocation cap on loop iterations also counts loops in
// branches no invocation takes (see direct_irradiance).
fn triangle_view(p: vec3<f32>, n: vec3<f32>, a: vec3<f32>, b: vec3<f32>, c: vec3<f32>) -> vec4<f32> {
    var corners: array<vec3<f32>, 4>;
    var count = 0u;
    clip_edge(a - p, b - p, n, &corners, &count);
    clip_edge(b - p, c - p, n, &corners, &count);
    clip_edge(c - p, a - p, n, &corners, &count);
    if count < 3u {
        return vec4<f32>(p, 0.0);
    }
    var sum = edge_term(corners[0], corners[1], n);
    sum += edge_term(corners[1], corners[2], n);
    var centre = corners[0] + corners[1] + corners[2];
    if count == 3u {
        sum += edge_term(corners[2], corners[0], n);
    } else {
        sum += edge_term(corners[2], corners[3], n);
        sum += edge_term(corners[3], corners[0], n);
        centre += corners[3];
    }
    return vec4<f32>(p + centre / f32(count), 0.5 * abs(sum));
}

// ViewContext::direct_irradiance. Each kind of light gives its unblocked
// irradiance and the shadow ray that may block it, and one call traces
// that ray: lavapipe's cap of 65,535 loop iterations an invocation counts
// every inlined copy of the hierarchy's loop, in branches taken or not (a
// fourth copy, for area lights, cut 10 view paths of the environment
// glass test, which one copy for all lights does not).
fn direct_irradiance(l: GpuLight, p: vec3<f32>, n: vec3<f32>) -> f32 {
    var value = 0.0;
    // What is left where the shadow ray is blocked (an area light's drawn
    // point takes only its share: plan::area_aims).
    var hidden = 0.0;
    // The shadow ray: its origin, direction and length.
    var origin = p;
    var dir = vec3<f32>(0.0);
    var reach = 0.0;
    if l.sun != 0u {
        // A sun: its beam's irradiance wherever it is not blocked, inside
        // the disc or not.
        let e = l.power / (PI * l.radius * l.radius);
        let cos_s = -dot(l.axis, n);
        let mean_cos = dot(l.mean_toward, n);
        if mean_cos > 0.0 {
            // A drawn sun's control variate (plan::drawn_suns): the mean
            // unshadowed light, less the draw's where it is not lit.
            value = e * mean_cos;
            hidden = e * (mean_cos - cos_s);
            if cos_s <= 0.0 {
                return hidden;
            }
        } else if cos_s <= 0.0 {
            return 0.0;
        } else {
            value = e * cos_s;
        }
        dir = -l.axis;
        origin = offset_origin(p, n, dir);
        reach = BIG;
    } else if l.kind == LIGHT_BEAM {
        let along = dot(p - l.position, l.axis);
        let cos_s = -dot(l.axis, n);
        if along <= 0.0 || cos_s <= 0.0 || length(p - l.position - l.axis * along) > l.radius {
            return 0.0;
        }
        value = l.power / (PI * l.radius * l.radius) * cos_s;
        dir = -l.axis;
        origin = offset_origin(p, n, dir);
        reach = along;
    } else if l.kind == LIGHT_AREA {
        // form_factor::in_front_of
        if dot(p - l.position, l.axis) <= surface_offset(p) {
            return 0.0;
        }
        let seen = triangle_view(p, n, l.position, l.position + l.tangent, l.position + l.bitangent);
        if seen.w <= 0.0 {
            return 0.0;
        }
        value = l.radius * seen.w;
        var aim_at = seen.xyz;
        if l.aimed != 0u {
            // area_aims::shadow_sample: the pass's point y, and what it
            // stands for, taken where it is hidden.
            aim_at = l.position + l.tangent * l.aim.x + l.bitangent * l.aim.y;
            let d = aim_at - p;
            let cos_p = dot(n, d);
            if cos_p <= 0.0 {
                return value;
            }
            let cos_y = -dot(l.axis, d);
            let r2 = dot(d, d);
            hidden = value - l.power / PI * cos_p * max(cos_y, 0.0) / (r2 * r2);
        }
        dir = nrm(aim_at - p);
        origin = offset_origin(p, n, dir);
        reach = length(aim_at - origin) * (1.0 - CONNECTION_REL);
    } else {
        // A point or spot light.
        let to = l.position - p;
        let dist = length(to);
        dir = to / dist;
        let cos_s = dot(dir, n);
        if cos_s <= 0.0 {
            return 0.0;
        }
        if l.kind == LIGHT_SPOT {
            let falloff = spot_falloff(l, dot(-dir, l.axis)) * range_window(dist, l.range);
            if falloff == 0.0 {
                return 0.0;
            }
            let intensity = l.power / (2.0 * PI * spot_measure(l));
            value = falloff * (intensity * cos_s / (dist * dist));
        } else {
            value = range_window(dist, l.range) * (l.power / (4.0 * PI) * cos_s / (dist * dist));
        }
        origin = offset_origin(p, n, dir);
        reach = length(l.position - origin);
    }
    if l.shadows != 0u && occluded(origin, dir, reach) {
        return hidden;
    }
    return value;
}

var<private> pixel_index: u32;

// A diffuse hit's caustic, left to the gather pass: the point, its normal
// on the viewer's side, what unit reflected caustic irradiance there adds
// to the pixel, the surface's albedo, and the pixel (within the chunk).
fn add_visible_point(point: vec3<f32>, normal: vec3<f32>, weight: vec3<f32>, albedo: vec3<f32>) {
    add_point(point, normal, weight, albedo, 0u, vec3<f32>(0.0), 0u);
}

// view::gathers_on_rough: whether a path meeting rough metal or glass of
// width `alpha` (0: polished) after `depth` bounces leaves a visible point
// there: the plan gathers on rough surfaces, the facets are rough enough
// (Ggx::gathers) and light tracing does not bring that light (depth 0).
fn gathers_on_rough(depth: u32, alpha: f32) -> bool {
    return params.rough_gathers != 0u && alpha >= GATHER_ALPHA && (depth > 0u || params.light_tracing == 0u);
}

// view::behind_rough: whether what a path sends on from rough metal or
// glass of width `alpha` met after `depth` bounces (`behind`: it is behind
// such a surface already) is behind one where the hidden lights' light is
// counted, light traced (depth 0, light_tracing::traces_behind_rough) or
// gathered.
fn behind_rough(behind: bool, depth: u32, alpha: f32) -> bool {
    let traced = depth == 0u && params.light_tracing != 0u && params.caustic_photons > 0u;
    return behind || (alpha > 0.0 && (traced || gathers_on_rough(depth, alpha)));
}

// VisiblePoint::on_rough: path `e`'s visible point on the rough metal or
// glass at `bent` (its normal the shading normal), for gather_rough.
fn add_rough_point(e: Pending, bent: Hit) {
    let weight = e.tint * params.white_balance * (params.exposure / PI);
    add_point(bent.point, bent.normal, weight, vec3<f32>(1.0), bent.object | ROUGH_POINT, e.dir, bent.triangle);
}

// A visible point appended to the chunk's (VisiblePoint's fields; one past
// the capacity is counted, not written).
fn add_point(point: vec3<f32>, normal: vec3<f32>, weight: vec3<f32>, albedo: vec3<f32>, rough: u32, toward: vec3<f32>, triangle: u32) {
    let i = atomicAdd(&counts.points, 1u);
    if i < params.point_capacity {
        let none = vec2<u32>(0u);
        let sums = array<vec2<u32>, 3>(none, none, none);
        // A per-pass path's point starts from its pixel's first radius.
        var ratio = 1.0;
        if per_pass() && pixel_ratios[pixel_index] != 0u {
            ratio = bitcast<f32>(~pixel_ratios[pixel_index]);
        }
        points[i] = VisiblePoint(point, 0u, normal, params.radius, weight, 0u, sums, none, pixel_index, ratio, 0u, 0u, albedo, rough, toward, triangle);
    }
}

// Light::hidden_direction: toward a light no ray can meet (light_is_hidden), else 0.
fn hidden_direction(l: GpuLight, p: vec3<f32>) -> vec3<f32> {
    if !light_is_hidden(l) {
        return vec3<f32>(0.0);
    }
    if l.kind == LIGHT_BEAM {
        return -l.axis;
    }
    return nrm(l.position - p);
}

// What the surface `s` at `hit` sends back along `e`'s ray of the lights'
// direct light, its one call of direct_irradiance (lavapipe counts each
// inlined copy's loop iterations): ViewContext::shade_diffuse less the
// caustic (see add_visible_point; with light tracing only behind a
// specular bounce, view::gathers_at) for a diffuse surface,
// ViewContext::metal_highlights for a rough metal and
// ViewContext::rough_glass_highlights for rough glass (its `face`); a
// metal (met at `hit`, its normal the geometric one) blended with a
// diffuse surface of its colour takes both, the diffuse part's weighted by
// its share toward the viewer and the specular part's by its Fresnel,
// which holds m (ViewContext::blended_metal; m as visit_path read it, 1
// but for metals). The shading normal faces the viewer on the geometric
// normal's side, so both parts share its irradiance.
fn surface_light(e: Pending, hit: Hit, s: GpuSurface, face: Face, m: f32) -> vec3<f32> {
    let dir = e.dir;
    let n = select(-hit.normal, hit.normal, dot(dir, hit.normal) < 0.0);
    let metal = s.kind == SURFACE_METAL;
    let glass = s.kind == SURFACE_DIELECTRIC;
    let crossing = sheet_crossing_rgb(s, e.band);
    var albedo = vec3<f32>(0.0);
    var alpha = 0.0;
    var lambda = e.lambda_nm;
    // A diffuse surface takes its lights' cosines with the smooth normal,
    // about which a metal reflects.
    var shading = n;
    if !glass {
        shading = scattering_normal(hit, dir);
        shading = select(-shading, shading, dot(dir, hit.normal) < 0.0);
    }
    // The diffuse part's share, and whether the specular part's highlights show.
    var diffuse_share = select(1.0, 0.0, glass);
    var highlights = false;
    if metal || glass {
        alpha = facets_alpha(hit, s);
    }
    // Behind a rough surface where the hidden lights' light is counted, it is the photons'.
    let shows_highlights = !e.behind;
    if glass && !shows_highlights {
        return vec3<f32>(0.0);
    }
    if metal {
        if lambda < 0.0 && e.band < params.band_count {
            lambda = bands[e.band].lambda_nm;
        }
        diffuse_share = blend_diffuse_share(s, m, abs(dot(dir, shading)), e.band, lambda);
        highlights = alpha > 0.0 && specular_part(e, s, m) > 0.0 && shows_highlights;
        albedo = s.albedo;
    } else if !glass {
        albedo = albedo_at(hit, n);
    }
    // Each light's irradiance, in the colour the surface reflects of its spectrum.
    var reflected = vec3<f32>(0.0);
    for (var i = 0u; i < params.light_count; i++) {
        let l = lights[i];
        var factor = albedo * (diffuse_share / PI);
        var lit_side = shading;
        if glass {
            // Either side: a light behind the glass shines through it.
            let wi = hidden_direction(l, hit.point);
            let f = rough_glass_bsdf(-dir, wi, hit.normal, face, alpha);
            if f == 0.0 {
                continue;
            }
            factor = vec3<f32>(f);
            if dot(wi, hit.normal) * dot(dir, hit.normal) > 0.0 {
                factor = crossing * f;
            }
            lit_side = select(-hit.normal, hit.normal, dot(wi, hit.normal) > 0.0);
        }
        if highlights {
            let wi = hidden_direction(l, hit.point);
            let density = ggx_reflection(alpha, -dir, wi, shading);
            if density > 0.0 {
                let h = nrm(wi - dir);
                factor += specular_tint(s, m, dot(-dir, h), e.band, lambda) * density;
            }
        }
        if all(factor == vec3<f32>(0.0)) {
            continue;
        }
        let m = mat3x3<f32>(l.reflected_r, l.reflected_g, l.reflected_b);
        reflected += m * factor * direct_irradiance(l, hit.point, lit_side);
    }
    if glass || diffuse_share == 0.0 {
        return reflected;
    }
    if params.stored > 0u && (e.depth > 0u || params.light_tracing == 0u) {
        let weight = e.tint * diffuse_share * params.white_balance * (params.exposure / PI);
        add_visible_point(hit.point, n, weight, albedo);
    }
    var emitted = vec3<f32>(0.0);
    if !metal && dot(dir, hit.normal) < 0.0 {
        emitted = surfaces[hit.object].emission;
    }
    return reflected + albedo * (params.ambient * diffuse_share) + emitted;
}

// One pending entry: what it adds to the pixel (with the light of the
// surface it met: the one call of surface_light); what it spawns goes to `kids`.
fn visit(e: Pending) -> vec3<f32> {
    light_query.on = false;
    let sum = visit_path(e);
    if !light_query.on {
        return sum;
    }
    let q = light_query;
    return sum + q.e.tint * surface_light(q.e, q.hit, q.s, q.face, q.metalness);
}

// ViewContext::blended_metal: the most the specular part of the metal `s`
// of metalness m reflects of a path `e` (a whole metal's: 1), 0 past the
// depth limit or where that share is too small to follow.
fn specular_part(e: Pending, s: GpuSurface, m: f32) -> f32 {
    let most = specular_share(s, m);
    if most <= 0.0 || e.depth >= params.max_depth || (most < 1.0 && e.weight * most <= MIN_VIEW_WEIGHT) {
        return 0.0;
    }
    return most;
}

// What a band of the split entry `e` (at its glass's hit) meets there:
// the band's index, and the film as it is at that point.
fn split_face(e: Pending, band: u32, lambda_nm: f32) -> Face {
    let at = Hit(true, 0.0, e.origin, e.normal, e.object, e.triangle);
    return path_face(surface_at(at, surfaces[e.object]), band, lambda_nm);
}

// What entry `e` adds to the pixel, less the light of the surface it met
// (left to `light_query`).
fn visit_path(e: Pending) -> vec3<f32> {
    if e.next_band != NO_SPLIT && per_pass() {
        // Hero path i of a per-pass split: band ⌊v·N⌋ at v = (i + u)/M,
        // (N/M)·C_b or the colour of its wavelength over M.
        let i = e.next_band;
        let m = min(HERO_WAVELENGTHS, params.band_count);
        if i + 1u < m {
            var rest = e;
            rest.next_band = i + 1u;
            spawn(rest);
        }
        let s = spectrum_share(sobol_f32(scramble, params.view_pass, 2u), i, m);
        var w = bands[s.band].weight * (f32(params.band_count) / f32(m));
        if s.lambda_nm >= 0.0 && params.colour_by_wavelength != 0u {
            w = wavelength_rgb(s.lambda_nm) / f32(m);
        }
        var hero = e;
        hero.hero = i;
        hero.lambda_nm = s.lambda_nm;
        let face = split_face(e, s.band, s.lambda_nm);
        through_dielectric(hero, face, s.band, e.weight * max_abs(w), e.tint * w);
        return vec3<f32>(0.0);
    }
    if e.next_band != NO_SPLIT {
        // One band of a split view ray: its RGB weight, its index. The rest
        // of the split goes below this band's rays.
        let b = e.next_band;
        if b + 1u < params.band_count {
            var rest = e;
            rest.next_band = b + 1u;
            spawn(rest);
        }
        let band = bands[b];
        let face = split_face(e, b, -1.0);
        through_dielectric(e, face, b, e.weight * band.max_weight, e.tint * band.weight);
        return vec3<f32>(0.0);
    }
    let hit = intersect_scene(e.origin, e.dir, BIG);
    if !hit.ok {
        return e.tint * background(e.dir);
    }
    let s = surface_at(hit, surfaces[hit.object]);
    if s.kind == SURFACE_DIFFUSE {
        light_query = LightQuery(true, e, hit, bare_face(1.0, false), s, 1.0);
        return vec3<f32>(0.0);
    }
    // Mirrors, metals and glass scatter about the shading normal.
    var bent = hit;
    bent.normal = scattering_normal(hit, e.dir);
    // A metal's facets and metalness here (glass reads its facets in through_dielectric).
    var alpha = 0.0;
    var m = 1.0;
    if s.kind == SURFACE_METAL {
        alpha = facets_alpha(bent, s);
        m = metalness_at(hit, s);
    }
    // Its light: a rough metal's highlights, a blended metal's diffuse part.
    if s.kind == SURFACE_METAL && ((alpha > 0.0 && e.depth < params.max_depth) || m < 1.0) {
        light_query = LightQuery(true, e, hit, bare_face(1.0, false), s, m);
    }
    if e.depth >= params.max_depth {
        return vec3<f32>(0.0);
    }
    if s.kind == SURFACE_METAL && specular_part(e, s, m) > 0.0 {
        // ViewContext::off_metal (a blended metal's specular part, its
        // Fresnel holding m): its visible point where it gathers, and one
        // facet, the path weighted by its Fresnel at the path's wavelength
        // times G2/G1.
        if !e.behind && gathers_on_rough(e.depth, alpha) {
            add_rough_point(e, bent);
        }
        var next = e;
        next.behind = behind_rough(e.behind, e.depth, alpha);
        var u = vec2<f32>(0.0);
        if alpha > 0.0 {
            u = pixel_facet(scramble, select(0u, params.view_pass, per_pass()), e.hero, e.depth);
        }
        let b = scatter_metal(e.dir, hit.point, bent.normal, alpha, u.x, u.y);
        if b.ok {
            var lambda = e.lambda_nm;
            if lambda < 0.0 && e.band < params.band_count {
                lambda = bands[e.band].lambda_nm;
            }
            let f = specular_tint(s, m, b.cos_facet, e.band, lambda) * b.unshadowed;
            let weight = e.weight * max(f.x, max(f.y, f.z));
            if weight > MIN_VIEW_WEIGHT {
                spawn_ray(next, b.origin, b.dir, e.band, weight, e.tint * f);
            }
        }
        return vec3<f32>(0.0);
    }
    if s.kind == SURFACE_METAL {
        return vec3<f32>(0.0);
    }
    if s.kind == SURFACE_MIRROR {
        let d = reflect_dir(e.dir, bent.normal);
        spawn_ray(e, offset_origin(hit.point, bent.normal, d), d, e.band, e.weight, e.tint);
        return vec3<f32>(0.0);
    }
    // What coloured glass left of a ray that crossed it.
    let kept = glass_transmittance(s, e.dir, hit.normal, hit.t, e.band);
    let weight = e.weight * max(kept.x, max(kept.y, kept.z));
    var at = Pending(hit.point, weight, e.dir, e.band, e.tint * kept, e.depth, bent.normal, NO_SPLIT, hit.object, hit.triangle, e.lambda_nm, e.hero, e.behind);
    // Rough glass's visible point, before a split into bands: one for the path.
    if !e.behind && gathers_on_rough(e.depth, facets_alpha(hit, surfaces[hit.object])) {
        add_rough_point(at, bent);
    }
    if e.band == WHITE_BAND && (s.flags & SURFACE_SPLITS_VIEW_RAYS) != 0u {
        at.next_band = 0u;
        spawn(at);
    } else {
        through_dielectric(at, path_face(s, e.band, e.lambda_nm), e.band, at.weight, at.tint);
    }
    return vec3<f32>(0.0);
}

// ViewContext::pixel: radiance through the pixel centre (a sampled path's
// jittered point), exposure applied, but for the caustics of its visible points.
fn pixel(x: u32, y: u32) -> vec3<f32> {
    var jitter = vec2<f32>(0.5);
    // Every path's numbers (a centre ray's: pass 0's, for rough metals).
    scramble = random_u32(params.view_seed, y * params.width + x, PIXEL_SCRAMBLE);
    if jittered() {
        jitter = vec2<f32>(sobol_f32(scramble, params.view_pass, 0u), sobol_f32(scramble, params.view_pass, 1u));
    }
    let d = params.cam_corner + params.cam_right * (f32(x) + jitter.x) + params.cam_down * (f32(y) + jitter.y);
    let white = vec3<f32>(1.0);
    stack[0] = stacked(Pending(params.cam_origin, 1.0, nrm(d), WHITE_BAND, white, 0u, vec3<f32>(0.0), NO_SPLIT, 0u, 0u, -1.0, 0u, false));
    top = 1u;
    var sum = vec3<f32>(0.0);
    while top > 0u {
        let e = pop();
        kid_count = 0u;
        sum += visit(e);
        // The stack never holds more than max_depth + 3 entries (see
        // prismatic_gpu::shaders::stack_size).
        for (var i = 0u; i < kid_count && top < STACK_SIZE; i++) {
            stack[top] = kids[i];
            top++;
        }
    }
    return sum * params.white_balance * params.exposure;
}

@compute @workgroup_size(WORKGROUP_SIZE)
fn main(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) nwg: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let k = flat_index(wid, nwg, lid);
    if k >= params.pixel_count {
        return;
    }
    let i = params.pixel_offset + k;
    pixel_index = k;
    pixels[k] = vec4<f32>(pixel(i % params.width, i / params.width), 1.0);
    // Entries left on the stack: the device stopped the loop (a software
    // device's cap on an invocation's loop iterations), not the paths.
    if top > 0u {
        atomicAdd(&counts.cut, 1u);
    }
}
