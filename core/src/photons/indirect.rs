//! Indirect light: photons that bounce off diffuse surfaces (global
//! illumination), the scalar reference every backend's twin follows.
//!
//! Besides its caustic photons a pass traces `render.indirect_photons`
//! photons, with the emission indices after the caustic ones
//! ([`PreparedScene::caustic_photons`]). Each leaves its light over
//! the light's whole distribution (no projection map: light bounced by any
//! diffuse surface counts, [`emit_unaimed`]) carrying up to four
//! wavelengths with their fractions of its flux ([`IndirectWavelengths`]:
//! a diffuse bounce sends them all one way, and a hit stores a photon for
//! each, so bounced light is not speckled with colour). Through mirrors and
//! clear glass they go together; at glass that disperses or tints light,
//! and at a coloured metal, the path goes on as one of them, as a band
//! photon does. At a diffuse surface (or a blended metal's diffuse part,
//! taken where it does not go on as its specular part or where that
//! part's layer passes it to the base, [`crate::optics::metal`]; the
//! photon is stored before the choice)
//! it is stored if it has bounced off a diffuse surface before, then
//! survives with the probability Σ fⱼ ρ(λⱼ) that the surface reflects
//! ([`crate::model::bands::BandTable::bounce_reflectance`]; Russian
//! roulette, so the path keeps its flux and its fractions become
//! fⱼ ρ(λⱼ) / Σ) and leaves in a cosine-distributed direction
//! ([`scatter_diffuse`]). Every bounce counts toward `max_depth`.
//!
//! The stored photons are the paths L (S|D)* D (S|D)* D, with at least one
//! diffuse vertex before the last: the caustic map holds L S+ D and the
//! view pass ray traces direct light L D, so each path is counted once and
//! the gather or light tracing estimates the rest (the furnace test: a
//! closed box of albedo a glowing L_e shows L_e / (1 − a)).
//!
//! Statistics: a photon the roulette ends counts as absorbed, and a stored
//! photon may go on, so `flux_stored` is not part of the energy balance of
//! indirect light (emitted = escaped + absorbed + depth limited).

use crate::geometry::primitive::Ray;
use crate::model::photon::{Photon, TraceStats};
use crate::optics::scatter::scatter_diffuse;
use crate::optics::surface::Surface;
use crate::photons::emit::emit_unaimed;
use crate::photons::path::{Crossing, Path, arrives_at_specular, cross_specular, goes_on_as_metal};
use crate::photons::wavelengths::IndirectWavelengths;
use crate::plan::prepared::PreparedScene;
use crate::util::rng::{dim, random_f32};
use alloc::vec::Vec;

/// Flux of one indirect photon: the lights' power shared by all of them.
pub fn indirect_flux(scene: &PreparedScene) -> f32 {
    match scene.scene.render.indirect_photons {
        0 => 0.0,
        n => scene.total_power / n as f32,
    }
}

/// Traces indirect photon `index` (an emission index at or after the
/// caustic photons'), appending what it stores in canonical (band,
/// bounces) order.
pub fn trace_indirect(scene: &PreparedScene, index: u32, out: &mut Vec<Photon>, stats: &mut TraceStats) {
    debug_assert!(index >= scene.caustic_photons(), "indirect photons follow the caustic ones");
    let seed = scene.scene.render.seed;
    let e = emit_unaimed(scene, seed, index);
    let (mut lanes, share) = IndirectWavelengths::at_light(scene, e.light, index);
    let flux = indirect_flux(scene) * share;
    stats.emitted += 1;
    stats.paths += 1;
    stats.flux_emitted += f64::from(flux);
    if lanes.count == 0 {
        return; // a coloured light with no power where its photon's strata fell
    }
    let ray = Ray { origin: e.origin, direction: e.direction };
    let mut p = Path { ray, flux, band: lanes.path_band(), lambda_nm: lanes.path_lambda(), bounces: 0 };
    let mut bounced_diffusely = false;
    let first = out.len();
    loop {
        stats.segments += 1;
        let Some(hit) = scene.intersect(&p.ray, f32::INFINITY) else {
            stats.flux_escaped += f64::from(p.flux);
            break;
        };
        if !p.reach(scene.emitters[e.light].range(), hit.t, stats) {
            break;
        }
        let surface = &scene.surfaces[hit.object];
        if surface.stores_photons() && bounced_diffusely {
            let stored = lanes.photons(&scene.bands, (hit.point, p.ray.direction), p.flux, index, p.bounces);
            for photon in stored {
                stats.count_stored(photon.flux);
                out.push(photon);
            }
        }
        // A blended metal: its diffuse part, unless the path goes on as its
        // specular part (whose layer may still pass it to the base).
        let diffuse = match surface {
            Surface::Diffuse { .. } => true,
            _ => surface.stores_photons() && !goes_on_as_metal(scene, index, &p, &hit),
        };
        // The base's survival number and the dimensions of its bounce's direction.
        let mut base =
            diffuse.then(|| (random_f32(seed, index, dim::scatter(p.band, p.bounces)), dim::bounce(p.band, p.bounces)));
        if !diffuse {
            let colours = || match surface {
                Surface::Dielectric(glass) => glass.splits_photons,
                Surface::Metal(metal) => scene.metal_is_chromatic_at(metal, &hit),
                _ => false,
            };
            if lanes.several() && colours() {
                lanes = lanes.choose(random_f32(seed, index, dim::choose(p.bounces)));
                (p.band, p.lambda_nm) = (lanes.path_band(), lanes.path_lambda());
            }
            if !arrives_at_specular(scene, index, &p, &hit, stats) {
                break;
            }
            if p.bounces == 0 {
                stats.specular_paths += 1;
            }
            match cross_specular(scene, index, &mut p, &hit, stats) {
                Crossing::On => {}
                Crossing::Ended => break,
                Crossing::ToBase(u) => base = Some((u, dim::base_bounce(p.band, p.bounces))),
            }
        }
        if let Some((u, [d1, d2])) = base {
            if p.bounces >= scene.plan.max_depth {
                stats.flux_depth_limited += f64::from(p.flux);
                break;
            }
            let facing = if p.ray.direction.dot(hit.normal) < 0.0 { hit.normal } else { -hit.normal };
            let albedo = scene.albedo_at(hit.object, hit.triangle, hit.point, facing);
            let (survives, after) =
                lanes.bounce(&scene.bands, |band, lambda_nm| scene.bands.bounce_reflectance(albedo, band, lambda_nm));
            if u >= survives {
                stats.flux_absorbed += f64::from(p.flux);
                break;
            }
            lanes = after;
            let (u1, u2) = (random_f32(seed, index, d1), random_f32(seed, index, d2));
            p.ray = scatter_diffuse(p.ray.direction, hit.point, hit.normal, u1, u2);
            bounced_diffusely = true;
        }
        p.bounces += 1;
    }
    // Stored wavelength by wavelength, bounce by bounce: (band, bounces) order.
    out[first..].sort_by_key(|photon| photon.band);
}
