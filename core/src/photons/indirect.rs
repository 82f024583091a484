//! Indirect light: photons that bounce off diffuse surfaces (global
//! illumination), the scalar reference every backend's twin follows.
//!
//! Besides its caustic photons a pass traces `render.indirect_photons`
//! photons, with the emission indices after the caustic ones
//! ([`PreparedScene::caustic_photons`]). Each leaves its light over
//! the light's whole distribution (no projection map: light bounced by any
//! diffuse surface counts, [`emit_unaimed`]) and takes one wavelength there
//! with all its flux ([`indirect_wavelength`]), so a bounce can weigh it by
//! the surface's reflectance at that wavelength. Through mirrors and glass
//! it goes as a band photon does. At a diffuse surface it is stored if it
//! has bounced off a diffuse surface before, then survives with the
//! probability ρ(λ) that the surface reflects
//! ([`crate::model::bands::BandTable::bounce_reflectance`]; Russian
//! roulette, so survivors keep their flux) and leaves in a
//! cosine-distributed direction ([`scatter_diffuse`]). Every bounce counts
//! toward `max_depth`.
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
use crate::photons::path::{Path, arrives_at_specular, cross_specular, stored_wavelength};
use crate::photons::wavelengths::{band_by_power, sample_band, spectrum_number, spectrum_share_of};
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

/// The band and wavelength indirect photon `index` of `light` is traced
/// at, from its spectrum number ([`dim::SPECTRUM`]): a band uniform over the
/// table (and a wavelength uniform in it when continuous) for an
/// equal-energy light, else a band drawn by the light's power or, when
/// continuous, a wavelength drawn from its spectrum.
pub fn indirect_wavelength(scene: &PreparedScene, light: usize, index: u32) -> (u16, Option<f32>) {
    let spectrum = &scene.light_spectra[light];
    if spectrum.is_uniform() {
        return sample_band(scene, index);
    }
    let u = spectrum_number(scene, index);
    if scene.scene.render.wavelengths.continuous() {
        spectrum_share_of(scene, Some(spectrum), u, 0, 1)
    } else {
        (band_by_power(&spectrum.band_shares, u), None)
    }
}

/// Traces indirect photon `index` (an emission index at or after the
/// caustic photons'), appending what it stores in path order.
pub fn trace_indirect(scene: &PreparedScene, index: u32, out: &mut Vec<Photon>, stats: &mut TraceStats) {
    debug_assert!(index >= scene.caustic_photons(), "indirect photons follow the caustic ones");
    let seed = scene.scene.render.seed;
    let e = emit_unaimed(scene, seed, index);
    let flux = indirect_flux(scene);
    stats.emitted += 1;
    stats.paths += 1;
    stats.flux_emitted += f64::from(flux);
    let (band, lambda_nm) = indirect_wavelength(scene, e.light, index);
    let ray = Ray { origin: e.origin, direction: e.direction };
    let mut p = Path { ray, flux, band, lambda_nm, bounces: 0 };
    let mut bounced_diffusely = false;
    loop {
        stats.segments += 1;
        let Some(hit) = scene.intersect(&p.ray, f32::INFINITY) else {
            stats.flux_escaped += f64::from(p.flux);
            return;
        };
        if let Surface::Diffuse { .. } = scene.surfaces[hit.object] {
            if bounced_diffusely {
                stats.stored += 1;
                stats.flux_stored += f64::from(p.flux);
                out.push(p.photon(scene, hit.point, index));
            }
            if p.bounces >= scene.plan.max_depth {
                stats.flux_depth_limited += f64::from(p.flux);
                return;
            }
            let facing = if p.ray.direction.dot(hit.normal) < 0.0 { hit.normal } else { -hit.normal };
            let albedo = scene.albedo_at(hit.object, hit.triangle, hit.point, facing);
            let lambda_nm = stored_wavelength(&scene.bands, p.band, p.lambda_nm);
            let survives = scene.bands.bounce_reflectance(albedo, p.band, lambda_nm);
            if random_f32(seed, index, dim::scatter(p.band, p.bounces)) >= survives {
                stats.flux_absorbed += f64::from(p.flux);
                return;
            }
            let [d1, d2] = dim::bounce(p.band, p.bounces);
            let (u1, u2) = (random_f32(seed, index, d1), random_f32(seed, index, d2));
            p.ray = scatter_diffuse(p.ray.direction, hit.point, hit.normal, u1, u2);
            bounced_diffusely = true;
        } else {
            if !arrives_at_specular(scene, index, &p, &hit, stats) {
                return;
            }
            if p.bounces == 0 {
                stats.specular_paths += 1;
            }
            if !cross_specular(scene, index, &mut p, &hit, stats) {
                return;
            }
        }
        p.bounces += 1;
    }
}
