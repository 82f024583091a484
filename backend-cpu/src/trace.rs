//! Packet photon tracing: the core's `trace_photons`, eight photon paths per
//! packet, lane-parallel with masks.
//!
//! White photons travel in packets of eight; a lane whose path ends is
//! refilled with the chunk's next white photon (emitted in SIMD). When a
//! white photon meets dispersive glass, its N band photons leave that point
//! together as band packets (bands b..b+8 of one photon in the eight lanes,
//! each lane with its own index of refraction, loaded as one vector from the
//! glass's band table; hero wavelengths, one packet of M, each at its own
//! wavelength) and are traced to the end before the white packet goes on. With single-band sampling (random band, continuous) the white
//! photon's lane simply continues as its band, with its own index. Every step mirrors the scalar reference operation for
//! operation, so the photon map is the reference's bit for bit.

use crate::emit::Emitters;
use crate::intersect::{HitX8, intersect_scene, scattering_normals};
use crate::optics::{offset_origin, reflect, scatter_dielectric};
use crate::ray::{RayX8, limit_where};
use crate::simd::{Vec3x8, lt, random_f32};
use glam::Vec3;
use prismatic_core::model::bands::BandTable;
use prismatic_core::model::light_range::range_window;
use prismatic_core::model::photon::{Photon, TraceStats, WHITE_BAND, oct_pack};
use prismatic_core::model::scene::WavelengthSampling;
use prismatic_core::optics::scatter::scatter_dielectric as scalar_scatter;
use prismatic_core::optics::surface::{DielectricOptics, Surface};
use prismatic_core::photons::emit::light_of;
use prismatic_core::photons::path::{absorbed, absorbed_crossing, stored_wavelength};
use prismatic_core::photons::trace::trace_emitted;
use prismatic_core::photons::wavelengths::{sample_band, split_bands};
use prismatic_core::plan::prepared::PreparedScene;
use prismatic_core::util::rng::dim;
use wide::{f32x8, u32x8};

/// A lane mask with every bit set.
pub(crate) const ON: f32 = f32::from_bits(u32::MAX);

/// What a surface does, per object, as lane masks and index vectors.
struct ObjectOptics {
    id: f32x8,
    diffuse: f32x8,
    mirror: f32x8,
    dielectric: f32x8,
    /// Dielectric that splits white light.
    dispersive: f32x8,
    /// Coloured dielectric (absorbs inside).
    absorbing: f32x8,
    /// Thin sheet (rays pass straight through).
    thin: f32x8,
    /// Glass with a film (its lanes scatter by the core's scalar rule).
    coated: f32x8,
    /// n for white light (non-dispersive glass only).
    white_ior: f32x8,
    /// n per band, eight bands per vector.
    band_ior: Vec<f32x8>,
}

/// The scene's tracing tables, shared by all chunks.
pub struct TraceContext<'a> {
    pub(crate) scene: &'a PreparedScene,
    pub(crate) emitters: Emitters,
    objects: Vec<ObjectOptics>,
    flux: f32,
    /// Some light has a spectrum other than equal energy: its photons are
    /// traced by the core's scalar tracer (see [`trace_chunk`]).
    coloured_lights: bool,
    /// Some light has a range, which windows its photons' first segment
    /// ([`TraceContext::reach`]).
    pub(crate) ranged_lights: bool,
    /// Some object is a metal or rough glass, or has a film map: the
    /// core's scalar tracer takes every photon (`kernels::trace_chunks`).
    pub(crate) facets: bool,
}

impl<'a> TraceContext<'a> {
    /// Builds the tables for `scene`.
    pub fn new(scene: &'a PreparedScene) -> Self {
        let mask = |b: bool| f32x8::splat(if b { ON } else { 0.0 });
        let n = scene.bands.len();
        let objects = scene
            .surfaces
            .iter()
            .enumerate()
            .map(|(k, s)| {
                let glass = match s {
                    Surface::Dielectric(g) => Some(g),
                    _ => None,
                };
                let band_ior = (0..n.div_ceil(8))
                    .map(|c| {
                        f32x8::new(core::array::from_fn(|i| {
                            glass.and_then(|g| g.band_ior.get(c * 8 + i).copied()).unwrap_or(1.0)
                        }))
                    })
                    .collect();
                ObjectOptics {
                    id: f32x8::splat(k as f32),
                    diffuse: mask(matches!(s, Surface::Diffuse { .. })),
                    mirror: mask(matches!(s, Surface::Mirror)),
                    dielectric: mask(glass.is_some()),
                    dispersive: mask(glass.is_some_and(|g| g.splits_photons)),
                    absorbing: mask(glass.is_some_and(|g| g.absorption.is_some())),
                    thin: mask(glass.is_some_and(|g| g.thin)),
                    coated: mask(glass.is_some_and(|g| g.film.is_some())),
                    white_ior: f32x8::splat(glass.map_or(1.0, |g| g.white_ior)),
                    band_ior,
                }
            })
            .collect();
        TraceContext {
            scene,
            emitters: Emitters::new(scene),
            objects,
            flux: prismatic_core::photons::trace::photon_flux(scene),
            coloured_lights: scene.light_spectra.iter().any(|s| !s.is_uniform()),
            ranged_lights: scene.emitters.iter().any(|l| l.range().is_some()),
            facets: scene.surfaces.iter().any(|s| match s {
                Surface::Metal(_) => true,
                Surface::Dielectric(g) => g.ggx.is_some(),
                _ => false,
            }) || scene.scene.materials.iter().any(|m| m.film_map.is_some()),
        }
    }

    /// `Path::reach` for the `first` lanes (paths on their first segment,
    /// met a surface at `t`) of photons `emission`: each flux windowed by
    /// its light's range, what the window takes tallied as escaped.
    /// Returns the new flux and the lanes left with nothing.
    pub(crate) fn reach(
        &self,
        sink: &mut Sink,
        first: f32x8,
        emission: u32x8,
        t: f32x8,
        flux: f32x8,
    ) -> (f32x8, f32x8) {
        let (e, t, mut f) = (emission.as_array(), t.to_array(), flux.to_array());
        let mut gone = [0.0f32; 8];
        for i in lanes(first) {
            let light = light_of(self.scene, self.scene.scene.render.seed, e[i]);
            let Some(range) = self.scene.emitters[light].range() else { continue };
            let kept = f[i] * range_window(t[i], Some(range));
            sink.stats.flux_escaped += f64::from(f[i] - kept);
            f[i] = kept;
            if kept <= 0.0 {
                gone[i] = ON;
            }
        }
        (f32x8::new(f), f32x8::new(gone))
    }
}

/// The surface facts of each lane's hit.
pub(crate) struct LaneSurfaces {
    pub(crate) missed: f32x8,
    pub(crate) diffuse: f32x8,
    pub(crate) mirror: f32x8,
    pub(crate) dielectric: f32x8,
    pub(crate) dispersive: f32x8,
    pub(crate) absorbing: f32x8,
    pub(crate) thin: f32x8,
    /// Glass with a film.
    pub(crate) coated: f32x8,
    /// Index of refraction for this lane: white for white packets, the band's for band packets.
    pub(crate) ior: f32x8,
}

impl TraceContext<'_> {
    /// Classifies the hits of a packet. `band_chunk` selects band indices
    /// (band packets) or white indices (`None`).
    #[inline]
    pub(crate) fn classify(&self, hit: &HitX8, band_chunk: Option<usize>) -> LaneSurfaces {
        let mut s = LaneSurfaces {
            missed: lt(hit.object, f32x8::ZERO),
            diffuse: f32x8::ZERO,
            mirror: f32x8::ZERO,
            dielectric: f32x8::ZERO,
            dispersive: f32x8::ZERO,
            absorbing: f32x8::ZERO,
            thin: f32x8::ZERO,
            coated: f32x8::ZERO,
            ior: f32x8::ONE,
        };
        for o in &self.objects {
            let m = hit.object.simd_eq(o.id);
            s.diffuse |= m & o.diffuse;
            s.mirror |= m & o.mirror;
            s.dielectric |= m & o.dielectric;
            s.dispersive |= m & o.dispersive;
            s.absorbing |= m & o.absorbing;
            s.thin |= m & o.thin;
            s.coated |= m & o.coated;
            let ior = match band_chunk {
                Some(c) => o.band_ior[c],
                None => o.white_ior,
            };
            s.ior = (m & o.dielectric).select(ior, s.ior);
        }
        s
    }
}

impl TraceContext<'_> {
    /// `ior` with the lanes of `mask` that carry one band (non-split
    /// sampling) set to their band's index, or their own wavelength's; the
    /// scalar rule of the reference, lane by lane.
    pub(crate) fn band_lanes_ior(
        &self,
        hit: &HitX8,
        mask: f32x8,
        band: u32x8,
        lambda: &[Option<f32>; 8],
        ior: f32x8,
    ) -> f32x8 {
        let mask = mask & bytemuck::cast::<u32x8, f32x8>(!band.simd_eq(u32x8::splat(u32::from(WHITE_BAND))));
        if !mask.any() {
            return ior;
        }
        let mut out = ior.to_array();
        let (objects, bands) = (hit.object.as_array(), band.as_array());
        for i in lanes(mask) {
            if let Surface::Dielectric(glass) = &self.scene.surfaces[objects[i] as usize] {
                out[i] = match lambda[i] {
                    Some(l) => glass.ior_at_wavelength(bands[i] as u16, l, &self.scene.bands),
                    None => glass.ior(bands[i] as u16),
                };
            }
        }
        f32x8::new(out)
    }
}

impl TraceContext<'_> {
    /// Whether white photon `index` leaves a coloured light.
    fn is_coloured(&self, index: u32) -> bool {
        let light = light_of(self.scene, self.scene.scene.render.seed, index);
        !self.scene.light_spectra[light].is_uniform()
    }
}

/// Output of a chunk.
pub(crate) struct Sink {
    pub(crate) out: Vec<Photon>,
    pub(crate) stats: TraceStats,
}

impl Sink {
    /// The photon that lane `i` of a packet (at `point`, along `dir`, its
    /// emission, band and bounces in `ids`, its wavelength in `lambda`)
    /// stores with `flux`, tallied as stored.
    #[inline]
    pub(crate) fn lane_photon(
        &mut self,
        bands: &BandTable,
        i: usize,
        (point, dir): (Vec3x8, Vec3x8),
        flux: f32,
        [emission, band, bounces]: [&[u32; 8]; 3],
        lambda: &[Option<f32>; 8],
    ) -> Photon {
        self.stats.count_stored(flux);
        Photon {
            position: point.lane(i).to_array(),
            flux,
            direction_oct: oct_pack(dir.lane(i)),
            lambda_nm: stored_wavelength(bands, band[i] as u16, lambda[i]),
            emission: emission[i],
            band: band[i] as u16,
            bounces: bounces[i] as u16,
        }
    }

    #[inline]
    pub(crate) fn add_flux(total: &mut f64, mask: f32x8, flux: f32x8) {
        let f = flux.as_array();
        for i in lanes(mask) {
            *total += f64::from(f[i]);
        }
    }
}

/// Traces caustic photons `range` (emission indices) in packets into `out`
/// (cleared first; not yet in canonical order, see [`canonical_order`]) and
/// returns the pass statistics.
pub fn trace_chunk(ctx: &TraceContext<'_>, range: core::ops::Range<u32>, out: &mut Vec<Photon>) -> TraceStats {
    let settings = &ctx.scene.scene.render;
    out.clear();
    let mut sink = Sink { out: core::mem::take(out), stats: TraceStats::default() };
    let mut next = range.start;
    let mut origin = Vec3x8::ZERO;
    let mut dir = Vec3x8::ZERO;
    let mut emission = u32x8::ZERO;
    let mut bounces = u32x8::ZERO;
    let mut active = f32x8::ZERO;
    let mut flux = f32x8::ZERO;
    // Band and wavelength of lanes that continue as one band (non-split sampling).
    let white = u32x8::splat(u32::from(WHITE_BAND));
    let mut band = white;
    let mut lambda = [None::<f32>; 8];
    // White photons that split continue as this many paths (bands or hero wavelengths).
    let split_paths = settings.wavelengths.paths(ctx.scene.bands.len());
    loop {
        // Refill free lanes with the next white photons.
        let free = !active;
        if next < range.end && free.any() {
            let free_bits = free.to_bitmask();
            let mut indices = [0u32; 8];
            let mut fresh = [0.0f32; 8];
            for (i, (index, on)) in indices.iter_mut().zip(&mut fresh).enumerate() {
                // A coloured light's photons start as several paths at their
                // light: the core's scalar tracer takes them, in its order.
                while ctx.coloured_lights && next < range.end && ctx.is_coloured(next) {
                    trace_emitted(ctx.scene, next, ctx.flux, &mut sink.out, &mut sink.stats);
                    next += 1;
                }
                if free_bits & (1 << i) != 0 && next < range.end {
                    *index = next;
                    *on = ON;
                    next += 1;
                }
            }
            let fresh = f32x8::new(fresh);
            let (o, d, weight) = ctx.emitters.emit(u32x8::new(indices));
            sink.stats.emitted += u64::from(fresh.to_bitmask().count_ones());
            // Projection-map samples outside their light (weight 0) are not traced.
            let fresh = fresh & weight.simd_ne(f32x8::ZERO);
            origin = Vec3x8::select(fresh, o, origin);
            dir = Vec3x8::select(fresh, d, dir);
            flux = fresh.select(f32x8::splat(ctx.flux) * weight, flux);
            let fresh_u = bytemuck::cast::<f32x8, u32x8>(fresh);
            emission = fresh_u.select(u32x8::new(indices), emission);
            bounces = fresh_u.select(u32x8::ZERO, bounces);
            band = fresh_u.select(white, band);
            active |= fresh;
            sink.stats.paths += u64::from(fresh.to_bitmask().count_ones());
            Sink::add_flux(&mut sink.stats.flux_emitted, fresh, flux);
        }
        if !active.any() {
            break;
        }
        let ray = RayX8 { origin, dir };
        let hit = intersect_scene(ctx.scene, &ray, limit_where(active, f32x8::splat(f32::INFINITY)));
        let mut s = ctx.classify(&hit, None);
        let point = ray.at(hit.t);
        if ctx.ranged_lights {
            // A path the range leaves nothing has still travelled its segment.
            let first = active & !s.missed & bytemuck::cast::<u32x8, f32x8>(bounces.simd_eq(u32x8::ZERO));
            let gone;
            (flux, gone) = ctx.reach(&mut sink, first, emission, hit.t, flux);
            sink.stats.segments += u64::from(gone.to_bitmask().count_ones());
            active &= !gone;
        }
        let ended = end_paths(ctx, &mut sink, active, &s, point, dir, flux, emission, (band, &lambda), bounces, None);
        let mut go_on = active & !ended;
        go_on &= !absorb_lanes(ctx, &mut sink, go_on & s.absorbing, &hit, dir, flux, [emission, band, bounces]);
        let split = go_on & s.dispersive & bytemuck::cast::<u32x8, f32x8>(band.simd_eq(white));
        if split_paths > 1 {
            // White photons at dispersive glass: their bands leave from here, in band packets.
            for i in lanes(split) {
                sink.stats.paths += u64::from(split_paths) - 1;
                let white = (emission.as_array()[i], bounces.as_array()[i], flux.as_array()[i]);
                trace_bands(ctx, &mut sink, i, &hit, point, dir, white, split_paths);
            }
            go_on &= !split;
        } else {
            // Each white photon continues as one band in its own lane.
            let mut bands = band.to_array();
            for i in lanes(split) {
                let (b, l) = sample_band(ctx.scene, emission.as_array()[i]);
                bands[i] = u32::from(b);
                lambda[i] = l;
            }
            band = u32x8::new(bands);
            s.ior = ctx.band_lanes_ior(&hit, go_on & s.dielectric, band, &lambda, s.ior);
        }
        let u = random_f32(settings.seed, emission, scatter_dims(band, bounces));
        let before = dir;
        let ids = LaneIds { object: hit.object, band, lambda: &lambda };
        let normal = scattering_normals(ctx.scene, &hit, point, dir, go_on);
        (origin, dir) = scatter(ctx, ids, point, dir, normal, &s, u, origin, go_on, dir);
        let sheets = go_on & s.thin & s.absorbing;
        go_on &= !absorb_crossing_lanes(ctx, &mut sink, sheets, &hit, (before, dir), flux, [emission, band, bounces]);
        bounces += bytemuck::cast::<f32x8, u32x8>(go_on) & u32x8::ONE;
        active = go_on;
    }
    *out = sink.out;
    sink.stats
}

/// Traces the paths a white photon splits into (lane `lane` of `hit`; its
/// emission index, bounces and flux in `white`) from the dispersive surface
/// it has just met, eight per packet: its `paths` bands
/// ([`prismatic_core::photons::wavelengths::split_bands`]: every band, each with the
/// glass's band table, or the hero wavelengths, each at its own wavelength).
#[expect(clippy::too_many_arguments, reason = "one lane's state at the split")]
fn trace_bands(
    ctx: &TraceContext<'_>,
    sink: &mut Sink,
    lane: usize,
    hit: &HitX8,
    point: Vec3x8,
    dir: Vec3x8,
    (emission, white_bounces, white_flux): (u32, u32, f32),
    paths: u32,
) {
    let seed = ctx.scene.scene.render.seed;
    let split = ctx.scene.scene.render.wavelengths == WavelengthSampling::Split;
    let flux = f32x8::splat(white_flux / paths as f32);
    let emission_v = u32x8::splat(emission);
    let object = hit.object.as_array()[lane] as usize;
    let (p, d) = (point.lane(lane), dir.lane(lane));
    let triangle = hit.triangle.as_array()[lane] as u32;
    let n = ctx.scene.scattering_normal_at(object, triangle, p, hit.normal.lane(lane), d);
    let (p0, d0, n0) = (Vec3x8::splat(p), Vec3x8::splat(d), Vec3x8::splat(n));
    let mut bands = split_bands(ctx.scene, emission);
    for chunk in 0..paths.div_ceil(8) {
        let children: [(u16, Option<f32>); 8] = core::array::from_fn(|_| bands.next().unwrap_or((WHITE_BAND, None)));
        let band = u32x8::new(children.map(|(b, _)| u32::from(b)));
        let lambda = children.map(|(_, l)| l);
        let mut active = bytemuck::cast::<u32x8, f32x8>(band.simd_ne(u32x8::splat(u32::from(WHITE_BAND))));
        // Split bands load their indices from the glass's table, eight at a
        // time; hero wavelengths take their own, lane by lane.
        let table = split.then_some(chunk as usize);
        let lane_ior = |hit: &HitX8, mask: f32x8, ior: f32x8| match table {
            Some(_) => ior,
            None => ctx.band_lanes_ior(hit, mask, band, &lambda, ior),
        };
        let mut bounces = u32x8::splat(white_bounces);
        // First, every band scatters at the glass with its own index.
        let ior = match table {
            Some(c) => ctx.objects[object].band_ior[c],
            None => lane_ior(&HitX8 { object: f32x8::splat(object as f32), ..*hit }, active, f32x8::ONE),
        };
        let glass = &ctx.objects[object];
        let start = LaneSurfaces {
            missed: f32x8::ZERO,
            diffuse: f32x8::ZERO,
            mirror: f32x8::ZERO,
            dielectric: f32x8::splat(ON),
            dispersive: f32x8::ZERO,
            absorbing: glass.absorbing,
            // A tinted sheet splits white light too (by its colour, not its index).
            thin: glass.thin,
            coated: glass.coated,
            ior,
        };
        let u = random_f32(seed, emission_v, scatter_dims(band, bounces));
        let ids = LaneIds { object: f32x8::splat(object as f32), band, lambda: &lambda };
        let (mut origin, mut dir) = scatter(ctx, ids, p0, d0, n0, &start, u, p0, active, d0);
        let at_glass = HitX8 { object: f32x8::splat(object as f32), ..*hit };
        let sheets = active & start.thin & start.absorbing;
        active &= !absorb_crossing_lanes(ctx, sink, sheets, &at_glass, (d0, dir), flux, [emission_v, band, bounces]);
        bounces += u32x8::ONE;
        // Each band stores at most once; kept by lane so that they leave in band order.
        let mut stored: [Option<Photon>; 8] = [None; 8];
        while active.any() {
            let ray = RayX8 { origin, dir };
            let hit = intersect_scene(ctx.scene, &ray, limit_where(active, f32x8::splat(f32::INFINITY)));
            let mut s = ctx.classify(&hit, table);
            s.ior = lane_ior(&hit, active & s.dielectric, s.ior);
            let point = ray.at(hit.t);
            let ended = end_paths(
                ctx,
                sink,
                active,
                &s,
                point,
                dir,
                flux,
                emission_v,
                (band, &lambda),
                bounces,
                Some(&mut stored),
            );
            active &= !ended;
            active &= !absorb_lanes(ctx, sink, active & s.absorbing, &hit, dir, flux, [emission_v, band, bounces]);
            let u = random_f32(seed, emission_v, scatter_dims(band, bounces));
            let before = dir;
            let ids = LaneIds { object: hit.object, band, lambda: &lambda };
            let normal = scattering_normals(ctx.scene, &hit, point, dir, active);
            (origin, dir) = scatter(ctx, ids, point, dir, normal, &s, u, origin, active, dir);
            let sheets = active & s.thin & s.absorbing;
            active &= !absorb_crossing_lanes(ctx, sink, sheets, &hit, (before, dir), flux, [emission_v, band, bounces]);
            bounces += bytemuck::cast::<f32x8, u32x8>(active) & u32x8::ONE;
        }
        sink.out.extend(stored.into_iter().flatten());
    }
}

/// Ends the paths that stop at this hit (escape, diffuse surface, depth
/// limit), storing caustic photons (into `lane_slots` by lane when given,
/// else at the end of the output); returns the lanes that ended.
#[expect(clippy::too_many_arguments, reason = "one packet's state, passed in registers")]
#[inline]
fn end_paths(
    ctx: &TraceContext<'_>,
    sink: &mut Sink,
    active: f32x8,
    s: &LaneSurfaces,
    point: Vec3x8,
    dir: Vec3x8,
    flux: f32x8,
    emission: u32x8,
    (band, lambda): (u32x8, &[Option<f32>; 8]),
    bounces: u32x8,
    mut lane_slots: Option<&mut [Option<Photon>; 8]>,
) -> f32x8 {
    sink.stats.segments += u64::from(active.to_bitmask().count_ones());
    let missed = active & s.missed;
    let first = bytemuck::cast::<u32x8, f32x8>(bounces.simd_eq(u32x8::ZERO));
    let diffuse = active & s.diffuse;
    let specular = active & (s.mirror | s.dielectric);
    let deep = bytemuck::cast::<u32x8, f32x8>(bounces.simd_ge(u32x8::splat(ctx.scene.plan.max_depth)));
    let too_deep = specular & deep;
    Sink::add_flux(&mut sink.stats.flux_escaped, missed, flux);
    Sink::add_flux(&mut sink.stats.flux_direct, diffuse & first, flux);
    Sink::add_flux(&mut sink.stats.flux_depth_limited, too_deep, flux);
    sink.stats.specular_paths += u64::from((specular & !too_deep & first).to_bitmask().count_ones());
    let store = diffuse & !first;
    if store.any() {
        let (f, e, b, k) = (flux.as_array(), emission.as_array(), band.as_array(), bounces.as_array());
        for i in lanes(store) {
            let photon = sink.lane_photon(&ctx.scene.bands, i, (point, dir), f[i], [e, b, k], lambda);
            match lane_slots.as_deref_mut() {
                Some(slots) => slots[i] = Some(photon),
                None => sink.out.push(photon),
            }
        }
    }
    missed | diffuse | too_deep
}

/// The lanes of `at_glass` (hits on coloured glass) whose path the glass
/// absorbs on the segment just ended: the reference's
/// [`absorbed`](prismatic_core::photons::path::absorbed), lane by lane with the
/// core's own `exp`, so the same paths survive. Their flux is tallied.
pub(crate) fn absorb_lanes(
    ctx: &TraceContext<'_>,
    sink: &mut Sink,
    at_glass: f32x8,
    hit: &HitX8,
    dir: Vec3x8,
    flux: f32x8,
    ids: [u32x8; 3],
) -> f32x8 {
    let t = hit.t.as_array();
    roulette_lanes(ctx, sink, at_glass, hit.object, flux, ids, |i, glass, band, u| {
        absorbed(glass, dir.lane(i), hit.normal.lane(i), t[i], band, u)
    })
}

/// The lanes of `at_sheet` (hits on tinted thin sheets, just scattered
/// from `before` to `after`) whose path crossed the sheet and was absorbed
/// there: the reference's
/// [`absorbed_crossing`](prismatic_core::photons::path::absorbed_crossing),
/// lane by lane. Their flux is tallied.
pub(crate) fn absorb_crossing_lanes(
    ctx: &TraceContext<'_>,
    sink: &mut Sink,
    at_sheet: f32x8,
    hit: &HitX8,
    (before, after): (Vec3x8, Vec3x8),
    flux: f32x8,
    ids: [u32x8; 3],
) -> f32x8 {
    roulette_lanes(ctx, sink, at_sheet, hit.object, flux, ids, |i, glass, band, u| {
        absorbed_crossing(glass, before.lane(i) == after.lane(i), band, u)
    })
}

/// The lanes of `mask` (hits on glass `objects`) that `absorbs` (lane, the
/// glass, the path's band, its [`dim::absorb`] number) ends: the core's
/// Russian roulette lane by lane, each lane's absorbed flux tallied.
fn roulette_lanes(
    ctx: &TraceContext<'_>,
    sink: &mut Sink,
    mask: f32x8,
    objects: f32x8,
    flux: f32x8,
    [emission, band, bounces]: [u32x8; 3],
    absorbs: impl Fn(usize, &DielectricOptics, u16, &dyn Fn() -> f32) -> bool,
) -> f32x8 {
    if !mask.any() {
        return f32x8::ZERO;
    }
    let seed = ctx.scene.scene.render.seed;
    let (objects, f) = (objects.as_array(), flux.as_array());
    let (e, b, k) = (emission.as_array(), band.as_array(), bounces.as_array());
    let mut out = [0.0f32; 8];
    for i in lanes(mask) {
        let Surface::Dielectric(glass) = &ctx.scene.surfaces[objects[i] as usize] else { continue };
        let band = b[i] as u16;
        let u = || prismatic_core::util::rng::random_f32(seed, e[i], dim::absorb(band, k[i]));
        if absorbs(i, glass, band, &u) {
            out[i] = ON;
            sink.stats.flux_absorbed += f64::from(f[i]);
        }
    }
    f32x8::new(out)
}

/// Which object each lane met, and its band and wavelength: what the
/// lanes at coated glass need to scatter by the core's scalar rule.
pub(crate) struct LaneIds<'a> {
    pub(crate) object: f32x8,
    pub(crate) band: u32x8,
    pub(crate) lambda: &'a [Option<f32>; 8],
}

/// New origins and directions of the lanes in `go_on` (mirror reflection or
/// Fresnel scattering); other lanes keep `origin`/`dir`.
#[expect(clippy::too_many_arguments, reason = "one packet's state, passed in registers")]
#[inline]
pub(crate) fn scatter(
    ctx: &TraceContext<'_>,
    ids: LaneIds<'_>,
    point: Vec3x8,
    d: Vec3x8,
    normal: Vec3x8,
    s: &LaneSurfaces,
    u: f32x8,
    origin: Vec3x8,
    go_on: f32x8,
    dir: Vec3x8,
) -> (Vec3x8, Vec3x8) {
    if !go_on.any() {
        return (origin, dir);
    }
    let (n_glass, mut dir_glass) = scatter_dielectric(d, normal, s.ior, s.thin, u);
    let coated = go_on & s.coated;
    if coated.any() {
        dir_glass = coated_directions(ctx, &ids, (point, d, normal), u, coated, dir_glass);
    }
    let n_face = Vec3x8::select(s.mirror, normal, n_glass);
    let new_dir = Vec3x8::select(s.mirror, reflect(d, normal), dir_glass);
    (Vec3x8::select(go_on, offset_origin(point, n_face, new_dir), origin), Vec3x8::select(go_on, new_dir, dir))
}

/// `dir` with the lanes of `mask` (at glass with a film) sent where the
/// core's scalar `scatter_dielectric` sends them: a film's reflectance is a
/// complex sum per lane's wavelength, so those lanes take the scalar rule
/// (the facing normal, and so the origin's offset, is the packet's).
fn coated_directions(
    ctx: &TraceContext<'_>,
    ids: &LaneIds<'_>,
    (point, d, normal): (Vec3x8, Vec3x8, Vec3x8),
    u: f32x8,
    mask: f32x8,
    dir: Vec3x8,
) -> Vec3x8 {
    let mut out: [Vec3; 8] = core::array::from_fn(|i| dir.lane(i));
    let (objects, bands, us) = (ids.object.as_array(), ids.band.as_array(), u.as_array());
    for i in lanes(mask) {
        let Surface::Dielectric(glass) = &ctx.scene.surfaces[objects[i] as usize] else { continue };
        let face = glass.face(bands[i] as u16, ids.lambda[i], &ctx.scene.bands);
        out[i] = scalar_scatter(d.lane(i), point.lane(i), normal.lane(i), face, us[i]).direction;
    }
    Vec3x8::from_lanes(&out)
}

/// Writes a chunk's photons (emissions `start..start + len`) into `dest` in
/// canonical (emission, band, bounces) order: a stable counting sort by emission.
/// Within one emission a caustic photon's are already in band order (band
/// packets run in band order and flush by lane; an emission stores either
/// one white photon or band photons, never both); an indirect photon's come
/// in path order (bounce by bounce, a photon per wavelength) and are sorted
/// by band there. `offsets` is scratch space.
pub fn canonical_order(unsorted: &[Photon], start: u32, len: usize, offsets: &mut Vec<u32>, dest: &mut [Photon]) {
    offsets.clear();
    offsets.resize(len + 1, 0);
    for p in unsorted {
        offsets[(p.emission - start) as usize + 1] += 1;
    }
    for i in 0..len {
        offsets[i + 1] += offsets[i];
    }
    for p in unsorted {
        let slot = &mut offsets[(p.emission - start) as usize];
        dest[*slot as usize] = *p;
        *slot += 1;
    }
    for emission in dest[..unsorted.len()].chunk_by_mut(|a, b| a.emission == b.emission) {
        if !emission.is_sorted_by_key(Photon::key) {
            emission.sort_by_key(Photon::key);
        }
    }
}

/// Indices of the lanes set in `mask`.
#[inline]
pub(crate) fn lanes(mask: f32x8) -> impl Iterator<Item = usize> {
    let bits = mask.to_bitmask();
    (0..8).filter(move |i| bits & (1 << i) != 0)
}

/// `dim::scatter(band, bounce)` per lane (`band` as u32, WHITE_BAND = 0xFFFF).
#[inline]
pub(crate) fn scatter_dims(band: u32x8, bounces: u32x8) -> u32x8 {
    let slot = (band + u32x8::ONE) & u32x8::splat(0xFFFF);
    u32x8::splat(dim::PATH) + slot * u32x8::splat(dim::PER_BAND) + bounces
}
