//! The scalar reference photon tracer: the specification every backend's
//! photon pass is compared with.
//!
//! White photons leave the lights (a sun's from its beam, see
//! [`PreparedScene::emitters`]); at the first dispersive or coloured
//! dielectric a white photon splits into one photon per band (each with 1/N
//! of the flux) and each band continues with its own index of refraction
//! and absorption; clear non-dispersive glass and mirrors never split. With
//! [`WavelengthSampling::Hero`] it splits into M hero wavelengths instead
//! (see [`split_bands`]); with [`WavelengthSampling::RandomBand`] or
//! `Continuous` it does not split but continues as one random band with all
//! its flux (see [`sample_band`]). A photon that reaches a diffuse surface
//! after at least one specular interaction is stored (the dispersion caustic
//! map, L S+ D paths); one that reaches it directly is direct light, which
//! the renderer ray traces instead. Inside coloured glass a path survives
//! each segment with its band's Beer–Lambert transmittance (see
//! [`absorbed`]). A coloured light's photons (a spectrum other than
//! equal energy) are never white: they start as their bands or
//! wavelengths at the light (see [`emission_paths`]). Fresnel chooses
//! reflection or refraction with a counter-based random number, so the
//! result is a pure function of the scene and the seed. A pass's indirect
//! photons follow its caustic ones ([`crate::photons::indirect`]).

use crate::geometry::primitive::Ray;
use crate::model::bands::BandTable;
use crate::model::photon::{Photon, PhotonMap, TraceStats, WHITE_BAND, oct_pack};
use crate::model::scene::WavelengthSampling;
use crate::optics::fresnel::reflect;
use crate::optics::scatter::{offset_origin, scatter_dielectric};
use crate::optics::surface::{DielectricOptics, Surface};
use crate::photons::emit::emit;
use crate::photons::indirect;
use crate::plan::prepared::Hit;
use crate::plan::prepared::PreparedScene;
use crate::sampling::light_spectrum::LightSpectrum;
use crate::sampling::sobol::photon_f32;
use crate::util::progress::{Progress, Stage};
use crate::util::rng::{dim, random_f32};
use alloc::vec::Vec;
use glam::Vec3;

/// Traces every white photon of the scene's render settings, reporting
/// progress about a hundred times.
pub fn trace_photons(scene: &PreparedScene, progress: &mut dyn Progress) -> PhotonMap {
    let total = scene.traced_photons();
    let chunk = (total / 100).max(1024);
    let mut map = PhotonMap::default();
    let mut start = 0;
    while start < total {
        let end = start.saturating_add(chunk).min(total);
        trace_range(scene, start..end, &mut map.photons, &mut map.stats);
        progress.advance(Stage::Photons, u64::from(end), u64::from(total));
        start = end;
    }
    map
}

/// Flux of one emitted white photon.
pub fn photon_flux(scene: &PreparedScene) -> f32 {
    match scene.scene.render.photons {
        0 => 0.0,
        n => scene.total_power / n as f32,
    }
}

/// Traces photons `range` (emission indices: caustic, then indirect),
/// appending stored photons in canonical order. Backends use it for chunks
/// and scalar tails.
pub fn trace_range(scene: &PreparedScene, range: core::ops::Range<u32>, out: &mut Vec<Photon>, stats: &mut TraceStats) {
    let (flux, caustic) = (photon_flux(scene), scene.caustic_photons());
    for index in range {
        if index < caustic {
            trace_emitted(scene, index, flux, out, stats);
        } else {
            indirect::trace_indirect(scene, index, out, stats);
        }
    }
}

/// One photon path in flight.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Path {
    pub(crate) ray: Ray,
    pub(crate) flux: f32,
    pub(crate) band: u16,
    /// The wavelength a continuous-spectrum photon is traced at.
    pub(crate) lambda_nm: Option<f32>,
    pub(crate) bounces: u32,
}

impl Path {
    /// The photon this path stores where it meets a diffuse surface at `point`.
    pub(crate) fn photon(&self, scene: &PreparedScene, point: Vec3, index: u32) -> Photon {
        Photon {
            position: point.to_array(),
            flux: self.flux,
            direction_oct: oct_pack(self.ray.direction),
            lambda_nm: stored_wavelength(&scene.bands, self.band, self.lambda_nm),
            emission: index,
            band: self.band,
            bounces: self.bounces as u16,
        }
    }
}

/// Traces white photon `index` and all the band photons it splits into.
pub fn trace_emitted(scene: &PreparedScene, index: u32, flux: f32, out: &mut Vec<Photon>, stats: &mut TraceStats) {
    let e = emit(scene, scene.scene.render.seed, index);
    stats.emitted += 1;
    let flux = flux * e.weight;
    if e.weight == 0.0 {
        return; // a projection-map sample outside its light: nothing to trace
    }
    stats.paths += 1;
    stats.flux_emitted += f64::from(flux);
    if !scene.light_spectra[e.light].is_uniform() {
        // A coloured light's photon takes its wavelengths as it leaves.
        let paths = emission_paths(scene, e.light, index);
        stats.paths += paths.len() as u64 - 1;
        for (band, lambda_nm, share) in paths {
            let ray = Ray { origin: e.origin, direction: e.direction };
            trace_path(scene, index, Path { ray, flux: flux * share, band, lambda_nm, bounces: 0 }, out, stats);
        }
        return;
    }
    let path = Path {
        ray: Ray { origin: e.origin, direction: e.direction },
        flux,
        band: WHITE_BAND,
        lambda_nm: None,
        bounces: 0,
    };
    trace_path(scene, index, path, out, stats);
}

fn trace_path(scene: &PreparedScene, index: u32, mut p: Path, out: &mut Vec<Photon>, stats: &mut TraceStats) {
    let settings = &scene.scene.render;
    loop {
        stats.segments += 1;
        let Some(hit) = scene.intersect(&p.ray, f32::INFINITY) else {
            stats.flux_escaped += f64::from(p.flux);
            return;
        };
        let surface = &scene.surfaces[hit.object];
        if let Surface::Diffuse { .. } = surface {
            if p.bounces == 0 {
                stats.flux_direct += f64::from(p.flux);
            } else {
                stats.stored += 1;
                stats.flux_stored += f64::from(p.flux);
                out.push(p.photon(scene, hit.point, index));
            }
            return;
        }
        if !arrives_at_specular(scene, index, &p, &hit, stats) {
            return;
        }
        if p.bounces == 0 {
            stats.specular_paths += 1;
        }
        match surface {
            Surface::Dielectric(glass) if p.band == WHITE_BAND && glass.splits_photons => {
                let paths = settings.wavelengths.paths(scene.bands.len());
                let before = p.ray.direction;
                let tinted = |band: u16, after: Vec3, bounces: u32| {
                    absorbed_crossing(glass, before, after, band, || {
                        random_f32(settings.seed, index, dim::absorb(band, bounces))
                    })
                };
                if paths == 1 {
                    let (band, lambda_nm) = sample_band(scene, index);
                    p.band = band;
                    p.lambda_nm = lambda_nm;
                    let u = random_f32(settings.seed, index, dim::scatter(band, p.bounces));
                    let ior = glass.path_ior(band, lambda_nm, &scene.bands);
                    p.ray = scatter_dielectric(before, hit.point, hit.normal, ior, glass.thin, u);
                    if tinted(band, p.ray.direction, p.bounces) {
                        stats.flux_absorbed += f64::from(p.flux);
                        return;
                    }
                    p.bounces += 1;
                    continue;
                }
                stats.paths += u64::from(paths) - 1;
                for (band, lambda_nm) in split_bands(scene, index) {
                    let u = random_f32(settings.seed, index, dim::scatter(band, p.bounces));
                    let ior = glass.path_ior(band, lambda_nm, &scene.bands);
                    let ray = scatter_dielectric(before, hit.point, hit.normal, ior, glass.thin, u);
                    let child = Path { ray, flux: p.flux / paths as f32, band, lambda_nm, bounces: p.bounces + 1 };
                    if tinted(band, ray.direction, p.bounces) {
                        stats.flux_absorbed += f64::from(child.flux);
                        continue;
                    }
                    trace_path(scene, index, child, out, stats);
                }
                return;
            }
            _ => {
                if !cross_specular(scene, index, &mut p, &hit, stats) {
                    return;
                }
            }
        }
        p.bounces += 1;
    }
}

/// Whether path `p` goes on at the mirror or glass it has reached at `hit`:
/// not past the depth limit, not absorbed on the segment inside coloured
/// glass that ends here ([`absorbed`]). An ended path's flux is tallied.
pub(crate) fn arrives_at_specular(
    scene: &PreparedScene,
    index: u32,
    p: &Path,
    hit: &Hit,
    stats: &mut TraceStats,
) -> bool {
    if p.bounces >= scene.plan.max_depth {
        stats.flux_depth_limited += f64::from(p.flux);
        return false;
    }
    if let Surface::Dielectric(glass) = &scene.surfaces[hit.object]
        && absorbed(glass, p.ray.direction, hit.normal, hit.t, p.band, || {
            random_f32(scene.scene.render.seed, index, dim::absorb(p.band, p.bounces))
        })
    {
        stats.flux_absorbed += f64::from(p.flux);
        return false;
    }
    true
}

/// Takes path `p` (one that does not split here) across the mirror or
/// glass at `hit`: reflected, or Fresnel's choice between reflection and
/// refraction at the path's own index; false when a tinted sheet absorbed
/// it on the way ([`absorbed_crossing`], its flux tallied). The bounce is
/// the caller's to count.
pub(crate) fn cross_specular(
    scene: &PreparedScene,
    index: u32,
    p: &mut Path,
    hit: &Hit,
    stats: &mut TraceStats,
) -> bool {
    let seed = scene.scene.render.seed;
    match &scene.surfaces[hit.object] {
        Surface::Mirror => {
            let d = reflect(p.ray.direction, hit.normal);
            p.ray = Ray { origin: offset_origin(hit.point, hit.normal, d), direction: d };
            true
        }
        Surface::Dielectric(glass) => {
            let u = random_f32(seed, index, dim::scatter(p.band, p.bounces));
            let ior = glass.path_ior(p.band, p.lambda_nm, &scene.bands);
            let before = p.ray.direction;
            p.ray = scatter_dielectric(before, hit.point, hit.normal, ior, glass.thin, u);
            let absorbed = absorbed_crossing(glass, before, p.ray.direction, p.band, || {
                random_f32(seed, index, dim::absorb(p.band, p.bounces))
            });
            if absorbed {
                stats.flux_absorbed += f64::from(p.flux);
            }
            !absorbed
        }
        Surface::Diffuse { .. } => unreachable!("a diffuse surface is not crossed"),
    }
}

/// The wavelength a photon of `band` traced at `lambda_nm` (`None`: the
/// band's own) stores: the one it was traced at, 0 for white light.
#[inline]
pub fn stored_wavelength(bands: &BandTable, band: u16, lambda_nm: Option<f32>) -> f32 {
    match bands.bands().get(usize::from(band)) {
        Some(b) => lambda_nm.unwrap_or(b.lambda_nm),
        None => 0.0,
    }
}

/// Whether coloured `glass` absorbs the photon path of `band` on a segment
/// of length `t` along `dir` that ends on it (outward `normal` there). Only
/// a segment that ran inside (it meets the glass from within) can be
/// absorbed, with probability 1 − e^(−σt) against the uniform number `u`
/// ([`dim::absorb`]): Russian roulette, so survivors keep their flux and
/// both estimators (counts and flux) stay unbiased.
pub fn absorbed(glass: &DielectricOptics, dir: Vec3, normal: Vec3, t: f32, band: u16, u: impl FnOnce() -> f32) -> bool {
    let Some(absorption) = glass.absorption.as_ref().filter(|_| !glass.thin) else { return false };
    dir.dot(normal) > 0.0 && u() >= absorption.transmittance(band, t)
}

/// Whether a tinted thin sheet absorbs the photon path of `band` that
/// crossed it (it left along `after` as it came along `before`): with
/// probability 1 − its crossing's transmittance
/// ([`DielectricOptics::sheet_crossing`]) against the uniform number `u`
/// ([`dim::absorb`], unused at a sheet by [`absorbed`]), as Russian roulette.
pub fn absorbed_crossing(
    glass: &DielectricOptics,
    before: Vec3,
    after: Vec3,
    band: u16,
    u: impl FnOnce() -> f32,
) -> bool {
    glass.thin && glass.absorption.is_some() && before == after && u() >= glass.sheet_crossing(band)
}

/// The band a white photon continues as when it does not split
/// ([`WavelengthSampling::RandomBand`] and `Continuous`): uniform over the
/// bands, and for `Continuous` a wavelength uniform over the band's interval.
/// Both come from one number u ([`dim::SPECTRUM`]): the band is ⌊u·N⌋ and
/// the wavelength sits at the fraction u·N − ⌊u·N⌋ of its interval, so
/// stratified numbers stratify the whole spectrum.
pub fn sample_band(scene: &PreparedScene, index: u32) -> (u16, Option<f32>) {
    spectrum_share(scene, spectrum_number(scene, index), 0, 1)
}

/// The bands and wavelengths white photon `index` splits into, in band
/// order: every band at the band's own index ([`WavelengthSampling::Split`]),
/// or its hero wavelengths ([`WavelengthSampling::Hero`]), all from the
/// photon's one spectrum number.
pub fn split_bands(scene: &PreparedScene, index: u32) -> impl Iterator<Item = (u16, Option<f32>)> + '_ {
    let paths = scene.scene.render.wavelengths.paths(scene.bands.len());
    let u = (scene.scene.render.wavelengths != WavelengthSampling::Split).then(|| spectrum_number(scene, index));
    (0..paths).map(move |path| match u {
        Some(u) => spectrum_share(scene, u, path, paths),
        None => (path as u16, None),
    })
}

/// White photon `index`'s spectrum number u ([`dim::SPECTRUM`]), shared by
/// every path it splits into.
pub fn spectrum_number(scene: &PreparedScene, index: u32) -> f32 {
    let r = &scene.scene.render;
    photon_f32(r.photon_sequence, r.seed, index, dim::SPECTRUM)
}

/// The spectrum sample in share `share` of `shares` equal shares of the
/// spectrum, all shifted by the photon's spectrum number `u`:
/// v = (share + u)/shares, the band ⌊v·N⌋ and (with continuous
/// wavelengths) the wavelength at the fraction v·N − ⌊v·N⌋ of its
/// interval. The shares' bands differ when shares ≤ N.
pub fn spectrum_share(scene: &PreparedScene, u: f32, share: u32, shares: u32) -> (u16, Option<f32>) {
    spectrum_share_of(scene, None, u, share, shares)
}

/// [`spectrum_share`] of a light's spectrum (`None`: equal energy): the
/// band is still ⌊v·N⌋ (the stratum, which keeps a photon's paths'
/// bands distinct), the wavelength the spectrum's at cumulative
/// probability v ([`LightSpectrum::wavelength`]).
pub fn spectrum_share_of(
    scene: &PreparedScene,
    spectrum: Option<&LightSpectrum>,
    u: f32,
    share: u32,
    shares: u32,
) -> (u16, Option<f32>) {
    let n = scene.bands.len();
    let scaled = (share as f32 + u) / shares as f32 * n as f32;
    let band = (scaled as usize).min(n - 1);
    let lambda_nm = scene.scene.render.wavelengths.continuous().then(|| match spectrum {
        Some(s) if !s.is_uniform() => s.wavelength((share as f32 + u) / shares as f32),
        _ => {
            let (lo, hi) = scene.bands.band(band).interval_nm;
            lo + (hi - lo) * (scaled - band as f32)
        }
    });
    (band as u16, lambda_nm)
}

/// The band at cumulative share `u` of a light's band `shares` (a band
/// drawn by power; the last band with power when rounding leaves `u` past
/// the sum).
pub fn band_by_power(shares: &[f32], u: f32) -> u16 {
    let mut acc = 0.0;
    let band = shares.iter().position(|s| {
        acc += s;
        u < acc
    });
    band.unwrap_or_else(|| shares.iter().rposition(|s| *s > 0.0).unwrap_or(0)) as u16
}

/// The paths a photon of a coloured light (one whose spectrum is not
/// equal energy) starts as, at its light, each with its band, wavelength
/// and share of the photon's flux: every band with its share of the
/// light's power (`split`, bands without power left out), one band drawn
/// by power (`random_band`), one wavelength drawn from the spectrum
/// (`continuous`), or M hero wavelengths each with 1/M (`hero`).
pub fn emission_paths(scene: &PreparedScene, light: usize, index: u32) -> Vec<(u16, Option<f32>, f32)> {
    let spectrum = &scene.light_spectra[light];
    let shares = &spectrum.band_shares;
    let u = spectrum_number(scene, index);
    match scene.scene.render.wavelengths {
        WavelengthSampling::Split => {
            shares.iter().enumerate().filter(|(_, s)| **s > 0.0).map(|(band, s)| (band as u16, None, *s)).collect()
        }
        WavelengthSampling::RandomBand => alloc::vec![(band_by_power(shares, u), None, 1.0)],
        sampling => {
            let m = sampling.paths(scene.bands.len());
            (0..m)
                .map(|i| {
                    let (band, lambda) = spectrum_share_of(scene, Some(spectrum), u, i, m);
                    (band, lambda, 1.0 / m as f32)
                })
                .collect()
        }
    }
}
