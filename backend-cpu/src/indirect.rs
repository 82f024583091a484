//! Indirect light's photons in packets: the core's
//! `prismatic_core::photons::indirect`, eight paths per packet,
//! lane-parallel with masks, operation for operation, so that the photon
//! map is the reference's bit for bit.
//!
//! Each lane carries one photon from its light to its end: it takes its
//! wavelengths as it leaves, crosses mirrors and glass as a band photon
//! does (the caustic packets' scattering and absorption; at glass that
//! disperses it goes on as one wavelength), and at a diffuse surface is
//! stored (after its first diffuse hit, a photon per wavelength), survives
//! with the surface's reflectance and bounces in a cosine-distributed
//! direction. A lane whose path ends is refilled with the range's next
//! photon; a lane's photons leave in path order, which the chunk's sort
//! puts into canonical order.

use crate::intersect::{intersect_scene, scattering_normals};
use crate::optics::scatter_diffuse;
use crate::ray::{RayX8, limit_where};
use crate::simd::{Vec3x8, random_f32};
use crate::trace::{
    LaneIds, ON, Sink, TraceContext, absorb_crossing_lanes, absorb_lanes, lanes, scatter, scatter_dims,
};
use prismatic_core::model::photon::{Photon, TraceStats};
use prismatic_core::photons::emit::light_of;
use prismatic_core::photons::indirect::indirect_flux;
use prismatic_core::photons::wavelengths::IndirectWavelengths;
use prismatic_core::util::rng::dim;
use wide::{f32x8, u32x8};

/// Traces indirect photons `range` (emission indices) in packets, adding
/// what they store to `out` and what they did to `stats`.
pub(crate) fn trace_indirect_packets(
    ctx: &TraceContext<'_>,
    range: core::ops::Range<u32>,
    out: &mut Vec<Photon>,
    stats: &mut TraceStats,
) {
    let mut sink = Sink { out: core::mem::take(out), stats: TraceStats::default() };
    trace_packets(ctx, range, &mut sink);
    *out = sink.out;
    stats.merge(&sink.stats);
}

fn trace_packets(ctx: &TraceContext<'_>, range: core::ops::Range<u32>, sink: &mut Sink) {
    let scene = ctx.scene;
    let seed = scene.scene.render.seed;
    let max_depth = u32x8::splat(scene.plan.max_depth);
    let photon_flux = indirect_flux(scene);
    let mut next = range.start;
    let (mut origin, mut dir) = (Vec3x8::ZERO, Vec3x8::ZERO);
    let (mut emission, mut band, mut bounces) = (u32x8::ZERO, u32x8::ZERO, u32x8::ZERO);
    let mut flux = f32x8::ZERO;
    let mut lambda = [None::<f32>; 8];
    let mut carried = [IndirectWavelengths::NONE; 8];
    // Lanes in flight, and those that have bounced off a diffuse surface.
    let (mut active, mut bounced) = (f32x8::ZERO, f32x8::ZERO);
    loop {
        let free = !active;
        if next < range.end && free.any() {
            let free_bits = free.to_bitmask();
            let (mut indices, mut fresh, mut bands, mut fluxes) =
                ([0u32; 8], [0.0f32; 8], band.to_array(), flux.to_array());
            for i in 0..8 {
                while free_bits & (1 << i) != 0 && next < range.end && fresh[i] == 0.0 {
                    let (wavelengths, share) = IndirectWavelengths::at_light(scene, light_of(scene, seed, next), next);
                    let lane_flux = photon_flux * share;
                    (sink.stats.emitted, sink.stats.paths) = (sink.stats.emitted + 1, sink.stats.paths + 1);
                    sink.stats.flux_emitted += f64::from(lane_flux);
                    if wavelengths.count > 0 {
                        (indices[i], fresh[i], fluxes[i], carried[i]) = (next, ON, lane_flux, wavelengths);
                        (bands[i], lambda[i]) = (u32::from(wavelengths.path_band()), wavelengths.path_lambda());
                    }
                    next += 1;
                }
            }
            let fresh = f32x8::new(fresh);
            let fresh_u = bytemuck::cast::<f32x8, u32x8>(fresh);
            let (o, d) = ctx.emitters.emit_unaimed(u32x8::new(indices));
            origin = Vec3x8::select(fresh, o, origin);
            dir = Vec3x8::select(fresh, d, dir);
            emission = fresh_u.select(u32x8::new(indices), emission);
            band = u32x8::new(bands);
            flux = f32x8::new(fluxes);
            bounces = fresh_u.select(u32x8::ZERO, bounces);
            bounced &= !fresh;
            active |= fresh;
        }
        if !active.any() {
            break;
        }
        let ray = RayX8 { origin, dir };
        let hit = intersect_scene(scene, &ray, limit_where(active, f32x8::splat(f32::INFINITY)));
        let mut s = ctx.classify(&hit, None);
        choose_at_dispersive_glass(
            ctx,
            active & s.dispersive,
            [emission, bounces],
            &mut band,
            &mut lambda,
            &mut carried,
        );
        s.ior = ctx.band_lanes_ior(&hit, active & s.dielectric, band, &lambda, s.ior);
        let point = ray.at(hit.t);
        sink.stats.segments += u64::from(active.to_bitmask().count_ones());
        let first = bytemuck::cast::<u32x8, f32x8>(bounces.simd_eq(u32x8::ZERO));
        if ctx.ranged_lights {
            let gone;
            (flux, gone) = ctx.reach(sink, active & first & !s.missed, emission, hit.t, flux);
            active &= !gone;
        }
        let missed = active & s.missed;
        Sink::add_flux(&mut sink.stats.flux_escaped, missed, flux);
        let deep = bytemuck::cast::<u32x8, f32x8>(bounces.simd_ge(max_depth));
        let diffuse = active & s.diffuse;
        let specular = active & (s.mirror | s.dielectric);
        // Diffuse hits: stored after the first, then the depth limit, then the roulette.
        store(ctx, sink, diffuse & bounced, (point, dir), flux, [emission, bounces], &carried);
        Sink::add_flux(&mut sink.stats.flux_depth_limited, (diffuse | specular) & deep, flux);
        let reflecting = diffuse & !deep;
        let survives =
            roulette(ctx, sink, reflecting, (&hit, point, dir), flux, [emission, band, bounces], &mut carried);
        let [d1, d2] = [0, 1].map(|k| bounce_dims(band, bounces) + u32x8::splat(k * dim::ABSORB));
        let (u1, u2) = (random_f32(seed, emission, d1), random_f32(seed, emission, d2));
        let (o, d) = scatter_diffuse(dir, point, hit.normal, u1, u2);
        // Mirror and glass: the caustic packets' steps.
        let mut crossing = specular & !deep;
        crossing &= !absorb_lanes(ctx, sink, crossing & s.absorbing, &hit, dir, flux, [emission, band, bounces]);
        sink.stats.specular_paths += u64::from((crossing & first).to_bitmask().count_ones());
        let u = random_f32(seed, emission, scatter_dims(band, bounces));
        let before = dir;
        let ids = LaneIds { object: hit.object, band, lambda: &lambda };
        let normal = scattering_normals(ctx.scene, &hit, point, dir, crossing);
        let (so, sd) = scatter(ctx, ids, point, dir, normal, &s, u, origin, crossing, dir);
        let sheets = crossing & s.thin & s.absorbing;
        crossing &= !absorb_crossing_lanes(ctx, sink, sheets, &hit, (before, sd), flux, [emission, band, bounces]);
        origin = Vec3x8::select(survives, o, so);
        dir = Vec3x8::select(survives, d, sd);
        bounced |= survives;
        active = survives | crossing;
        bounces += bytemuck::cast::<f32x8, u32x8>(active) & u32x8::ONE;
    }
}

/// The lanes of `mask` (at glass that disperses or tints light) that carry
/// several wavelengths go on as one ([`IndirectWavelengths::choose`]).
fn choose_at_dispersive_glass(
    ctx: &TraceContext<'_>,
    mask: f32x8,
    [emission, bounces]: [u32x8; 2],
    band: &mut u32x8,
    lambda: &mut [Option<f32>; 8],
    carried: &mut [IndirectWavelengths; 8],
) {
    if !mask.any() {
        return;
    }
    let seed = ctx.scene.scene.render.seed;
    let (emission, bounces, mut bands) = (emission.as_array(), bounces.as_array(), band.to_array());
    for i in lanes(mask) {
        if !carried[i].several() {
            continue;
        }
        carried[i] =
            carried[i].choose(prismatic_core::util::rng::random_f32(seed, emission[i], dim::choose(bounces[i])));
        (bands[i], lambda[i]) = (u32::from(carried[i].path_band()), carried[i].path_lambda());
    }
    *band = u32x8::new(bands);
}

/// Stores the photons of the lanes of `mask` at `point`, one per
/// wavelength each carries.
fn store(
    ctx: &TraceContext<'_>,
    sink: &mut Sink,
    mask: f32x8,
    (point, dir): (Vec3x8, Vec3x8),
    flux: f32x8,
    [emission, bounces]: [u32x8; 2],
    carried: &[IndirectWavelengths; 8],
) {
    let (flux, emission, bounces) = (flux.as_array(), emission.as_array(), bounces.as_array());
    for i in lanes(mask) {
        let at = (point.lane(i), dir.lane(i));
        for photon in carried[i].photons(&ctx.scene.bands, at, flux[i], emission[i], bounces[i]) {
            sink.stats.count_stored(photon.flux);
            sink.out.push(photon);
        }
    }
}

/// The lanes of `mask` (diffuse hits) whose photon survives the surface's
/// reflectance at its wavelengths (the core's roulette, lane by lane with
/// the core's albedo and reflectance; survivors go on with the fractions
/// it leaves them); the others' flux is tallied as absorbed.
fn roulette(
    ctx: &TraceContext<'_>,
    sink: &mut Sink,
    mask: f32x8,
    (hit, point, dir): (&crate::intersect::HitX8, Vec3x8, Vec3x8),
    flux: f32x8,
    [emission, band, bounces]: [u32x8; 3],
    carried: &mut [IndirectWavelengths; 8],
) -> f32x8 {
    if !mask.any() {
        return f32x8::ZERO;
    }
    let scene = ctx.scene;
    let u = random_f32(scene.scene.render.seed, emission, scatter_dims(band, bounces)).to_array();
    let (objects, triangles, flux) = (hit.object.as_array(), hit.triangle.as_array(), flux.as_array());
    let mut out = [0.0f32; 8];
    for i in lanes(mask) {
        let (d, n) = (dir.lane(i), hit.normal.lane(i));
        let facing = if d.dot(n) < 0.0 { n } else { -n };
        let albedo = scene.albedo_at(objects[i] as usize, triangles[i] as u32, point.lane(i), facing);
        let (survives, after) =
            carried[i].bounce(&scene.bands, |band, lambda_nm| scene.bands.bounce_reflectance(albedo, band, lambda_nm));
        if u[i] < survives {
            (out[i], carried[i]) = (ON, after);
        } else {
            sink.stats.flux_absorbed += f64::from(flux[i]);
        }
    }
    f32x8::new(out)
}

/// `dim::bounce(band, bounce)[0]` per lane.
#[inline]
fn bounce_dims(band: u32x8, bounces: u32x8) -> u32x8 {
    scatter_dims(band, bounces) + u32x8::splat(dim::BOUNCE)
}
