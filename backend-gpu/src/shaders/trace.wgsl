// Emit + trace: twin of prismatic_core::photons::{trace, indirect}. One
// invocation per photon of the chunk (caustic, then indirect light's); its stored photons go to its own `slots` scratch
// slots in (band) order, its count to `counts`, so that the compaction pass
// can put the chunk into canonical (emission, band, bounces) order without atomics.
// The workgroup sums its statistics into its `tallies` slot.

@group(1) @binding(0) var<storage, read_write> scratch: array<Photon>;
@group(1) @binding(1) var<storage, read_write> counts: array<u32>;
@group(1) @binding(2) var<storage, read_write> tallies: array<Tally>;

// Emitted, paths, segments, specular paths, stored.
var<private> tally_counts: array<u32, TALLY_COUNTS>;
// Flux emitted, stored, escaped, direct, depth limited, absorbed.
var<private> tally_flux: array<f32, TALLY_FLUXES>;
var<private> slot_base: u32;
var<private> slot_used: u32;
// The range of the light the invocation's photon left (0: none).
var<private> photon_range: f32;
// trace::Source::recorded_on_rough: that light is hidden
// (Light::is_hidden) and the plan records caustic photons on rough
// surfaces (EffectPlan::rough_records), so they are recorded there
// (record_on_rough).
var<private> photon_recorded: bool;
// The surface where `follow` last split a path, as its maps make it there.
var<private> split_surface: GpuSurface;

var<workgroup> reduce_counts: array<u32, TALLY_COUNTS * WORKGROUP_SIZE>;
var<workgroup> reduce_flux: array<f32, TALLY_FLUXES * WORKGROUP_SIZE>;

struct Path {
    origin: vec3<f32>,
    dir: vec3<f32>,
    flux: f32,
    band: u32,
    // The wavelength of a continuous-spectrum photon; < 0 for none.
    lambda_nm: f32,
    bounces: u32,
}

const FOLLOW_END: u32 = 0u;
const FOLLOW_SPLIT: u32 = 1u;

// trace::absorbed_crossing: whether a tinted thin sheet absorbs path `p`,
// which has just `crossed` it, tallying its flux; its bounces are still
// the crossing's.
fn absorbed_crossing(s: GpuSurface, crossed: bool, p: Path, seed: u32, index: u32) -> bool {
    if !is_sheet(s) || (s.flags & SURFACE_ABSORBS) == 0u || !crossed {
        return false;
    }
    let u = random_f32(seed, index, absorb_dim(p.band, p.bounces));
    if u >= exp(-absorption_coefficient(s, p.band)) {
        tally_flux[5] += p.flux;
        return true;
    }
    return false;
}


// trace::stored_wavelength: the path's own, its band's, or 0 for white light.
fn stored_wavelength(band: u32, lambda_nm: f32) -> f32 {
    if band >= params.band_count {
        return 0.0;
    }
    return select(bands[band].lambda_nm, lambda_nm, lambda_nm >= 0.0);
}

fn store(p: ptr<function, Path>, point: vec3<f32>, index: u32) {
    tally_flux[1] += (*p).flux;
    put(p, point, index, min((*p).bounces, 0x7fffu));
}

// Path::photon into the next slot, its bounces field `bounces`.
fn put(p: ptr<function, Path>, point: vec3<f32>, index: u32, bounces: u32) {
    tally_counts[4] += 1u;
    if slot_used < params.slots {
        scratch[slot_base + slot_used] = Photon(
            point,
            (*p).flux,
            oct_pack((*p).dir),
            stored_wavelength((*p).band, (*p).lambda_nm),
            index,
            ((*p).band & 0xffffu) | (bounces << 16u),
        );
    }
    slot_used++;
}

// trace::record_on_rough: a caustic path of a recorded light
// (photon_recorded), past its first specular interaction, met where the
// metal (a blended metal's specular part) or glass `s` at `hit` is rough:
// a photon marked ON_ROUGH_SURFACE, counted as stored but not its flux.
fn record_on_rough(p: ptr<function, Path>, hit: Hit, s: GpuSurface, index: u32) {
    if (*p).bounces > 0u && photon_recorded && facets_alpha(hit, s) > 0.0 {
        put(p, hit.point, index, min((*p).bounces, 0x7fffu) | ON_ROUGH_SURFACE);
    }
}

// Path::reach: a path on its first segment windowed by its light's range
// at its first hit, `t` from the light, what the window takes tallied as
// escaped; false when nothing is left.
fn reach(p: ptr<function, Path>, t: f32) -> bool {
    if (*p).bounces > 0u || photon_range <= 0.0 {
        return true;
    }
    let kept = (*p).flux * range_window(t, photon_range);
    tally_flux[2] += (*p).flux - kept;
    (*p).flux = kept;
    return kept > 0.0;
}

// Follows a path until it is stored, escapes, is absorbed or hits the
// depth limit (FOLLOW_END), or reaches glass or a coloured metal where a
// white photon splits into bands (FOLLOW_SPLIT, with the hit in `split_at`).
fn follow(p: ptr<function, Path>, index: u32, split_at: ptr<function, Hit>) -> u32 {
    let seed = params.seed;
    loop {
        tally_counts[2] += 1u;
        let hit = intersect_scene((*p).origin, (*p).dir, BIG);
        if !hit.ok {
            tally_flux[2] += (*p).flux;
            return FOLLOW_END;
        }
        if !reach(p, hit.t) {
            return FOLLOW_END;
        }
        let s = surface_at(hit, surfaces[hit.object]);
        let blended = (s.flags & SURFACE_BLENDED) != 0u;
        if s.kind == SURFACE_DIFFUSE || blended {
            if (*p).bounces == 0u {
                tally_flux[3] += (*p).flux;
            } else {
                store(p, hit.point, index);
                // What a blended metal's specular part reflects of it.
                record_on_rough(p, hit, s, index);
            }
            // path::goes_on_as_metal: a blended metal's metal part, with its metalness's probability.
            if s.kind == SURFACE_DIFFUSE || !goes_on_as_metal(*p, hit, s, index) {
                return FOLLOW_END;
            }
        }
        if !arrives_at_specular(*p, hit, s, index) {
            return FOLLOW_END;
        }
        if (*p).bounces == 0u {
            tally_counts[3] += 1u;
        }
        if s.kind == SURFACE_METAL && (*p).band == WHITE_BAND && metal_is_chromatic(s) {
            // trace_path: a coloured metal splits white light as glass
            // does, or it goes on as one random band with the whole flux.
            if split_paths() > 1u {
                *split_at = hit;
                split_surface = s;
                return FOLLOW_SPLIT;
            }
            let b = spectrum_share(photon_f32(seed, index, DIM_SPECTRUM), 0u, 1u);
            (*p).band = b.band;
            (*p).lambda_nm = b.lambda_nm;
        }
        if s.kind == SURFACE_DIELECTRIC && (*p).band == WHITE_BAND && (s.flags & SURFACE_SPLITS_PHOTONS) != 0u {
            if split_paths() > 1u {
                *split_at = hit;
                split_surface = s;
                return FOLLOW_SPLIT;
            }
            // trace::sample_band: continue as one random band with the whole flux.
            let b = spectrum_share(photon_f32(seed, index, DIM_SPECTRUM), 0u, 1u);
            (*p).band = b.band;
            (*p).lambda_nm = b.lambda_nm;
        }
        if !blended {
            record_on_rough(p, hit, s, index);
        }
        if !cross_specular(p, hit, s, index) {
            return FOLLOW_END;
        }
        (*p).bounces += 1u;
    }
    return FOLLOW_END;
}

// path::goes_on_as_metal: whether path `p`, stored on the blended metal `s`
// at `hit`, goes on as its specular part (probability: specular_share there).
fn goes_on_as_metal(p: Path, hit: Hit, s: GpuSurface, index: u32) -> bool {
    let m = metalness_at(hit, s);
    return random_f32(params.seed, index, metal_part_dim(p.band, p.bounces)) < specular_share(s, m);
}

// trace::arrives_at_specular: whether path `p` goes on at the mirror or
// glass `s` it reached at `hit` (not past the depth limit, not absorbed
// inside coloured glass); an ended path's flux is tallied.
fn arrives_at_specular(p: Path, hit: Hit, s: GpuSurface, index: u32) -> bool {
    if p.bounces >= params.max_depth {
        tally_flux[4] += p.flux;
        return false;
    }
    // trace::absorbed: a segment inside coloured glass ends here.
    if (s.flags & SURFACE_ABSORBS) != 0u && !is_sheet(s) && dot(p.dir, hit.normal) > 0.0 {
        let u = random_f32(params.seed, index, absorb_dim(p.band, p.bounces));
        if u >= exp(-absorption_coefficient(s, p.band) * hit.t) {
            tally_flux[5] += p.flux;
            return false;
        }
    }
    return true;
}

// Set by cross_specular: the uniform number left for the diffuse base's
// own choice where a specular layer passed the path to it (path::Crossing::ToBase),
// else negative.
var<private> to_base: f32;

// trace::cross_specular: path `p` (one that does not split here) across
// the mirror, metal or glass `s` at `hit`; false when the metal, rough
// glass's microsurface or a tinted sheet absorbed it, or a specular layer
// passed it to its base (`to_base` set, nothing tallied).
fn cross_specular(p: ptr<function, Path>, hit: Hit, s: GpuSurface, index: u32) -> bool {
    let n = scattering_normal(hit, (*p).dir);
    to_base = -1.0;
    if s.kind == SURFACE_METAL {
        // A facet of the metal, and its specular part's Fresnel times the
        // unshadowed share as the path's survival probability; what the
        // layer's facet passes goes to the base.
        let alpha = facets_alpha(hit, s);
        var u = vec2<f32>(0.0);
        if alpha > 0.0 {
            let d = bounce_dim((*p).band, (*p).bounces);
            u = vec2<f32>(random_f32(params.seed, index, d), random_f32(params.seed, index, d + DIM_ABSORB));
        }
        let v = random_f32(params.seed, index, scatter_dim((*p).band, (*p).bounces));
        let b = scatter_metal((*p).dir, hit.point, n, alpha, u.x, u.y);
        if b.ok {
            let lambda = stored_wavelength((*p).band, (*p).lambda_nm);
            let m = metalness_at(hit, s);
            let parts = specular_parts(s, m, b.cos_facet, (*p).band, lambda);
            let reflects = b.unshadowed * parts.x;
            if v < reflects {
                (*p).origin = b.origin;
                (*p).dir = b.dir;
                return true;
            }
            let passes = parts.y;
            if v < reflects + passes {
                to_base = (v - reflects) / passes;
                return false;
            }
        }
        tally_flux[5] += (*p).flux;
        return false;
    }
    if s.kind == SURFACE_MIRROR {
        let d = reflect_dir((*p).dir, n);
        (*p).origin = offset_origin(hit.point, n, d);
        (*p).dir = d;
        return true;
    }
    let u = random_f32(params.seed, index, scatter_dim((*p).band, (*p).bounces));
    let face = path_face(s, (*p).band, (*p).lambda_nm);
    let before = (*p).dir;
    // Rough glass (α 0: polished).
    let alpha = facets_alpha(hit, s);
    var crossed = false;
    if alpha > 0.0 {
        // A facet, Fresnel's choice at it, and survival with the unshadowed share.
        let d = bounce_dim((*p).band, (*p).bounces);
        let facet = vec2<f32>(random_f32(params.seed, index, d), random_f32(params.seed, index, d + DIM_ABSORB));
        let b = scatter_rough_dielectric(before, hit.point, n, face, alpha, facet, u);
        if !b.ok || !(b.leftover < b.unshadowed) {
            tally_flux[5] += (*p).flux;
            return false;
        }
        (*p).origin = b.origin;
        (*p).dir = b.dir;
        crossed = b.crossed;
    } else {
        let out = scatter_dielectric(before, hit.point, n, face, u);
        (*p).origin = out.origin;
        (*p).dir = out.dir;
        crossed = all(out.dir == before);
    }
    return !absorbed_crossing(s, crossed, *p, params.seed, index);
}

// indirect::trace_indirect: photon `index` of indirect light, unaimed,
// carrying its wavelengths together until dispersive glass, stored (a
// photon per wavelength) at every diffuse hit after its first and going on
// from it with the surface's reflectance (Russian roulette); its stored
// photons sorted into (band, bounces) order at the end.
fn trace_indirect(index: u32) {
    let seed = params.seed;
    let e = emit_from(seed, index, false);
    var c: Carried;
    let flux = params.indirect_flux * carried_at_light(e.light, index, &c);
    tally_counts[0] += 1u;
    tally_counts[1] += 1u;
    tally_flux[0] += flux;
    photon_range = lights[e.light].range;
    if c.count == 0u {
        return;
    }
    var p = Path(e.origin, e.direction, flux, carried_band(&c), carried_lambda(&c), 0u);
    var bounced = false;
    loop {
        tally_counts[2] += 1u;
        let hit = intersect_scene(p.origin, p.dir, BIG);
        if !hit.ok {
            tally_flux[2] += p.flux;
            break;
        }
        if !reach(&p, hit.t) {
            break;
        }
        let s = surface_at(hit, surfaces[hit.object]);
        let blended = (s.flags & SURFACE_BLENDED) != 0u;
        if (s.kind == SURFACE_DIFFUSE || blended) && bounced {
            store_carried(&p, &c, hit.point, index);
        }
        // A blended metal: its diffuse part, unless the path goes on as its
        // specular part (whose layer may still pass it to the base): the
        // base's survival number and its bounce's first dimension.
        let diffuse = s.kind == SURFACE_DIFFUSE || (blended && !goes_on_as_metal(p, hit, s, index));
        var base = -1.0;
        var base_dim = bounce_dim(p.band, p.bounces);
        if diffuse {
            base = random_f32(seed, index, scatter_dim(p.band, p.bounces));
        } else {
            let glass_splits = s.kind == SURFACE_DIELECTRIC && (s.flags & SURFACE_SPLITS_PHOTONS) != 0u;
            let coloured_metal = s.kind == SURFACE_METAL && metal_is_chromatic(s);
            if c.count > 1u && (glass_splits || coloured_metal) {
                carried_choose(&c, random_f32(seed, index, choose_dim(p.bounces)));
                p.band = carried_band(&c);
                p.lambda_nm = carried_lambda(&c);
            }
            if !arrives_at_specular(p, hit, s, index) {
                break;
            }
            if p.bounces == 0u {
                tally_counts[3] += 1u;
            }
            if !cross_specular(&p, hit, s, index) {
                if to_base < 0.0 {
                    break;
                }
                base = to_base;
                base_dim = base_bounce_dim(p.band, p.bounces);
            }
        }
        if base >= 0.0 {
            if p.bounces >= params.max_depth {
                tally_flux[4] += p.flux;
                break;
            }
            let facing = select(-hit.normal, hit.normal, dot(p.dir, hit.normal) < 0.0);
            if !carried_bounce(&c, albedo_at(hit, facing), base) {
                tally_flux[5] += p.flux;
                break;
            }
            let u1 = random_f32(seed, index, base_dim);
            let u2 = random_f32(seed, index, base_dim + DIM_ABSORB);
            let out = scatter_diffuse(p.dir, hit.point, hit.normal, u1, u2);
            p.origin = out.origin;
            p.dir = out.dir;
            bounced = true;
        }
        p.bounces += 1u;
    }
    sort_slots_by_band();
}

// wavelengths::IndirectWavelengths: the wavelengths an indirect photon
// carries, each with its fraction of the path's flux.
struct Carried {
    count: u32,
    band: array<u32, HERO_WAVELENGTHS>,
    // < 0 for none (the band's own).
    lambda_nm: array<f32, HERO_WAVELENGTHS>,
    fraction: array<f32, HERO_WAVELENGTHS>,
}

// IndirectWavelengths::at_light: the wavelengths photon `index` of light
// `light` leaves with; returns the factor its flux takes.
fn carried_at_light(light: u32, index: u32, c: ptr<function, Carried>) -> f32 {
    let l = lights[light];
    let n = params.band_count;
    let m = min(split_paths(), HERO_WAVELENGTHS);
    let u = photon_f32(params.seed, index, DIM_SPECTRUM);
    let uniform = l.spectrum_len == 0u;
    let split = params.wavelengths == WAVELENGTHS_SPLIT;
    (*c).count = 0u;
    var total = 0.0;
    for (var i = 0u; i < m; i++) {
        var w = SpectrumSample(i, -1.0);
        var share = 1.0 / f32(m);
        if uniform || split {
            if !split || m != n {
                w = spectrum_share(u, i, m);
            }
            if !uniform {
                share = band_share(l, w.band) * f32(n) / f32(m);
            }
        } else if params.wavelengths == WAVELENGTHS_RANDOM_BAND {
            w = SpectrumSample(band_by_power(l, u), -1.0);
            share = 1.0;
        } else {
            w = light_spectrum_share(l, u, i, m);
        }
        if share > 0.0 {
            let k = (*c).count;
            (*c).band[k] = w.band;
            (*c).lambda_nm[k] = w.lambda_nm;
            (*c).fraction[k] = share;
            (*c).count = k + 1u;
            total += share;
        }
    }
    for (var j = 0u; j < (*c).count; j++) {
        (*c).fraction[j] /= total;
    }
    return total;
}

// IndirectWavelengths::path_band: the one wavelength's band, or white.
fn carried_band(c: ptr<function, Carried>) -> u32 {
    return select(WHITE_BAND, (*c).band[0], (*c).count == 1u);
}

// IndirectWavelengths::path_lambda.
fn carried_lambda(c: ptr<function, Carried>) -> f32 {
    return select(-1.0, (*c).lambda_nm[0], (*c).count == 1u);
}

// IndirectWavelengths::bounce: whether the path survives a diffuse bounce
// off `albedo` against `u` (p = Σ fⱼ ρⱼ), and if so its fractions fⱼ ρⱼ / p.
fn carried_bounce(c: ptr<function, Carried>, albedo: vec3<f32>, u: f32) -> bool {
    var rho: array<f32, HERO_WAVELENGTHS>;
    var p = 0.0;
    for (var j = 0u; j < (*c).count; j++) {
        rho[j] = bounce_reflectance(albedo, (*c).band[j], stored_wavelength((*c).band[j], (*c).lambda_nm[j]));
        p += (*c).fraction[j] * rho[j];
    }
    if u >= p {
        return false;
    }
    for (var j = 0u; j < (*c).count; j++) {
        (*c).fraction[j] = (*c).fraction[j] * rho[j] / p;
    }
    return true;
}

// IndirectWavelengths::choose: go on as wavelength j with probability fⱼ.
fn carried_choose(c: ptr<function, Carried>, u: f32) {
    var acc = 0.0;
    var j = (*c).count - 1u;
    for (var k = 0u; k < (*c).count; k++) {
        acc += (*c).fraction[k];
        if u < acc {
            j = k;
            break;
        }
    }
    (*c).band[0] = (*c).band[j];
    (*c).lambda_nm[0] = (*c).lambda_nm[j];
    (*c).fraction[0] = 1.0;
    (*c).count = 1u;
}

// IndirectWavelengths::photons: a photon per wavelength at `point`.
fn store_carried(p: ptr<function, Path>, c: ptr<function, Carried>, point: vec3<f32>, index: u32) {
    for (var j = 0u; j < (*c).count; j++) {
        var one = *p;
        one.flux = (*p).flux * (*c).fraction[j];
        one.band = (*c).band[j];
        one.lambda_nm = (*c).lambda_nm[j];
        store(&one, point, index);
    }
}

// The emission's stored photons (path order: bounce by bounce, a photon
// per wavelength) into (band, bounces) order: a stable insertion sort.
fn sort_slots_by_band() {
    let n = min(slot_used, params.slots);
    for (var i = 1u; i < n; i++) {
        let photon = scratch[slot_base + i];
        let band = photon.band_bounces & 0xffffu;
        var k = i;
        while k > 0u && (scratch[slot_base + k - 1u].band_bounces & 0xffffu) > band {
            scratch[slot_base + k] = scratch[slot_base + k - 1u];
            k--;
        }
        scratch[slot_base + k] = photon;
    }
}

// Band `b`'s share of coloured light `l`'s power (its table after the
// spectrum's samples).
fn band_share(l: GpuLight, b: u32) -> f32 {
    return tables[l.spectrum_first + 3u * l.spectrum_len + b];
}

// trace::band_by_power: the band at cumulative share `u` of light `l`'s
// band shares (the last with power when rounding leaves `u` past the sum).
fn band_by_power(l: GpuLight, u: f32) -> u32 {
    var band = params.band_count;
    var last = 0u;
    var acc = 0.0;
    for (var b = 0u; b < params.band_count; b++) {
        let s = band_share(l, b);
        acc += s;
        if s > 0.0 {
            last = b;
        }
        if band == params.band_count && u < acc {
            band = b;
        }
    }
    return select(band, last, band == params.band_count);
}

// trace::trace_emitted. Every path of the photon (a white path and the
// paths it splits into, or a coloured light's paths) is followed from one
// call of `follow`: the shader compiler inlines each call, with the
// scene's intersection and every material in it (on lavapipe the photon
// pass's first compile took 134 s with five calls, 24.2 s with one).
fn trace_emitted(index: u32) {
    let e = emit(params.seed, index);
    tally_counts[0] += 1u;
    if e.weight == 0.0 {
        return;
    }
    let flux = params.flux * e.weight;
    tally_counts[1] += 1u;
    tally_flux[0] += flux;
    let l = lights[e.light];
    photon_range = l.range;
    photon_recorded = params.rough_records != 0u && light_is_hidden(l);
    let coloured = l.spectrum_len > 0u;
    var p = Path(e.origin, e.direction, flux, WHITE_BAND, -1.0, 0u);
    // The number of the next path to make.
    var next = 0u;
    // One spectrum number for all the paths (trace::split_bands: hero only).
    var u = 0.0;
    if coloured {
        u = photon_f32(params.seed, index, DIM_SPECTRUM);
        tally_coloured_paths(l);
        if !coloured_path(e, l, flux, u, &next, &p) {
            return;
        }
    }
    // Where the white path split, and into how many paths.
    var white = p;
    var hit: Hit;
    var s: GpuSurface;
    var n = 0u;
    loop {
        // Paths made by a split or a coloured light are a band's: they
        // never split (`hit` stays the split's).
        let followed = follow(&p, index, &hit);
        if coloured {
            if !coloured_path(e, l, flux, u, &next, &p) {
                return;
            }
            continue;
        }
        if n == 0u {
            // The white path has ended, or split at `hit`.
            if followed != FOLLOW_SPLIT {
                return;
            }
            white = p;
            n = split_paths();
            tally_counts[1] += n - 1u;
            s = split_surface;
            if params.wavelengths != WAVELENGTHS_SPLIT {
                u = photon_f32(params.seed, index, DIM_SPECTRUM);
            }
        }
        if !split_path(white, hit, s, n, u, index, &next, &p) {
            return;
        }
    }
}

// trace::split_bands: into `p`, the first of paths `*next`.. of the `n`
// that `white` splits into at `hit` on `s` that crosses the surface (its
// bounces are the split's until it has crossed); false when none is left.
fn split_path(white: Path, hit: Hit, s: GpuSurface, n: u32, u: f32, index: u32, next: ptr<function, u32>, p: ptr<function, Path>) -> bool {
    while *next < n {
        let b = split_band(u, *next);
        *next += 1u;
        *p = Path(white.origin, white.dir, white.flux / f32(n), b.band, b.lambda_nm, white.bounces);
        if (s.flags & SURFACE_BLENDED) == 0u {
            record_on_rough(p, hit, s, index);
        }
        if cross_specular(p, hit, s, index) {
            (*p).bounces += 1u;
            return true;
        }
    }
    return false;
}

// The paths a coloured light's photon adds to the tallies' paths.
fn tally_coloured_paths(l: GpuLight) {
    if params.wavelengths == WAVELENGTHS_SPLIT {
        var count = 0u;
        for (var b = 0u; b < params.band_count; b++) {
            count += select(0u, 1u, band_share(l, b) > 0.0);
        }
        tally_counts[1] += count - 1u;
    } else if params.wavelengths != WAVELENGTHS_RANDOM_BAND {
        tally_counts[1] += split_paths() - 1u;
    }
}

// trace::emission_paths: into `p`, path `*next` (or the next with power)
// of coloured light `l`'s photon `e`, which starts as its bands (split, with
// their shares of the light's power), one band drawn by power
// (random_band), or wavelengths drawn from the light's spectrum; false
// when none is left.
fn coloured_path(e: Emitted, l: GpuLight, flux: f32, u: f32, next: ptr<function, u32>, p: ptr<function, Path>) -> bool {
    let m = split_paths();
    while *next < m {
        let i = *next;
        *next += 1u;
        if params.wavelengths == WAVELENGTHS_SPLIT {
            let share = band_share(l, i);
            if share > 0.0 {
                *p = Path(e.origin, e.direction, flux * share, i, -1.0, 0u);
                return true;
            }
        } else if params.wavelengths == WAVELENGTHS_RANDOM_BAND {
            *p = Path(e.origin, e.direction, flux, band_by_power(l, u), -1.0, 0u);
            return true;
        } else {
            let share = light_spectrum_share(l, u, i, m);
            *p = Path(e.origin, e.direction, flux * (1.0 / f32(m)), share.band, share.lambda_nm, 0u);
            return true;
        }
    }
    return false;
}

// WavelengthSampling::paths: what a white photon splits into at dispersive glass.
fn split_paths() -> u32 {
    if params.wavelengths == WAVELENGTHS_SPLIT {
        return params.band_count;
    }
    if params.wavelengths == WAVELENGTHS_HERO {
        return min(HERO_WAVELENGTHS, params.band_count);
    }
    return 1u;
}

// Path `path` of trace::split_bands, with the photon's spectrum number `u`.
fn split_band(u: f32, path: u32) -> SpectrumSample {
    if params.wavelengths == WAVELENGTHS_SPLIT {
        return SpectrumSample(path, -1.0);
    }
    return spectrum_share(u, path, split_paths());
}


@compute @workgroup_size(WORKGROUP_SIZE)
fn main(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) nwg: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let k = flat_index(wid, nwg, lid);
    if k < params.chunk_len {
        slot_base = k * params.slots;
        let index = params.chunk_start + k;
        if index < params.caustic_photons {
            trace_emitted(index);
        } else {
            trace_indirect(index);
        }
        counts[k] = slot_used;
    }
    for (var j = 0u; j < TALLY_COUNTS; j++) {
        reduce_counts[j * WORKGROUP_SIZE + lid] = tally_counts[j];
    }
    for (var j = 0u; j < TALLY_FLUXES; j++) {
        reduce_flux[j * WORKGROUP_SIZE + lid] = tally_flux[j];
    }
    workgroupBarrier();
    for (var stride = WORKGROUP_SIZE / 2u; stride > 0u; stride /= 2u) {
        if lid < stride {
            for (var j = 0u; j < TALLY_COUNTS; j++) {
                reduce_counts[j * WORKGROUP_SIZE + lid] += reduce_counts[j * WORKGROUP_SIZE + lid + stride];
            }
            for (var j = 0u; j < TALLY_FLUXES; j++) {
                reduce_flux[j * WORKGROUP_SIZE + lid] += reduce_flux[j * WORKGROUP_SIZE + lid + stride];
            }
        }
        workgroupBarrier();
    }
    if lid == 0u {
        let slot = wid.y * nwg.x + wid.x;
        for (var j = 0u; j < TALLY_COUNTS; j++) {
            tallies[slot].counts[j] += reduce_counts[j * WORKGROUP_SIZE];
        }
        for (var j = 0u; j < TALLY_FLUXES; j++) {
            tallies[slot].flux[j] += reduce_flux[j * WORKGROUP_SIZE];
        }
    }
}
