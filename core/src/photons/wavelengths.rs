//! The wavelengths a photon path is traced at: the band a white photon
//! continues as, the bands or hero wavelengths it splits into, the paths a
//! coloured light's photon starts as and the wavelengths an indirect
//! photon carries, all from the photon's one spectrum number.

use crate::model::bands::BandTable;
use crate::model::photon::{Photon, WHITE_BAND, oct_pack};
use crate::model::scene::{HERO_WAVELENGTHS, WavelengthSampling};
use crate::photons::path::stored_wavelength;
use crate::plan::prepared::PreparedScene;
use crate::sampling::light_spectrum::LightSpectrum;
use crate::sampling::sobol::photon_f32;
use crate::util::rng::dim;
use alloc::vec::Vec;
use glam::Vec3;

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

/// The wavelengths an indirect photon carries together (hero wavelengths,
/// Wilkie et al. 2014): a diffuse bounce sends every wavelength the same
/// way, so one path carries up to [`HERO_WAVELENGTHS`] of them, each
/// with its fraction of the path's flux, until glass that disperses
/// (or tints) light, where it goes on as one of them
/// ([`IndirectWavelengths::choose`]). Its bands are distinct and
/// increasing, so what it stores has distinct canonical keys.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IndirectWavelengths {
    /// How many wavelengths the path carries (0: its light gives it none).
    pub count: usize,
    /// Each one's band.
    pub band: [u16; HERO_WAVELENGTHS as usize],
    /// The wavelength each is traced at (continuous sampling).
    pub lambda_nm: [Option<f32>; HERO_WAVELENGTHS as usize],
    /// Each one's fraction of the path's flux (they sum to 1).
    pub fraction: [f32; HERO_WAVELENGTHS as usize],
}

impl IndirectWavelengths {
    /// No wavelengths (a lane not in flight).
    pub const NONE: Self = Self { count: 0, band: [0; 4], lambda_nm: [None; 4], fraction: [0.0; 4] };

    /// The wavelengths indirect photon `index` of `light` leaves with, and
    /// the factor its flux takes (1 for an equal-energy light), from its
    /// spectrum number ([`dim::SPECTRUM`]). M = min(the sampling's paths,
    /// [`HERO_WAVELENGTHS`]) of them: the spectrum's M stratified shares
    /// ([`spectrum_share`], every band when M = N with split sampling),
    /// each 1/M of the flux; for a coloured light its spectrum's shares
    /// when continuous, one band by power for random-band sampling, and
    /// otherwise stratified bands weighted by the light's band shares ×
    /// N/M (bands without power left out).
    pub fn at_light(scene: &PreparedScene, light: usize, index: u32) -> (Self, f32) {
        let sampling = scene.scene.render.wavelengths;
        let n = scene.bands.len();
        let m = Self::most(scene);
        let spectrum = &scene.light_spectra[light];
        let u = spectrum_number(scene, index);
        let mut lanes = Self::NONE;
        let mut total = 0.0;
        for i in 0..m {
            let (band, lambda_nm, share) = if spectrum.is_uniform() || sampling == WavelengthSampling::Split {
                let (band, lambda_nm) = match sampling {
                    WavelengthSampling::Split if m as usize == n => (i as u16, None),
                    _ => spectrum_share(scene, u, i, m),
                };
                let share = match spectrum.is_uniform() {
                    true => 1.0 / m as f32,
                    false => spectrum.band_shares[usize::from(band)] * n as f32 / m as f32,
                };
                (band, lambda_nm, share)
            } else if sampling == WavelengthSampling::RandomBand {
                (band_by_power(&spectrum.band_shares, u), None, 1.0)
            } else {
                let (band, lambda_nm) = spectrum_share_of(scene, Some(spectrum), u, i, m);
                (band, lambda_nm, 1.0 / m as f32)
            };
            if share > 0.0 {
                let k = lanes.count;
                (lanes.band[k], lanes.lambda_nm[k], lanes.fraction[k]) = (band, lambda_nm, share);
                lanes.count += 1;
                total += share;
            }
        }
        for f in &mut lanes.fraction[..lanes.count] {
            *f /= total;
        }
        (lanes, total)
    }

    /// The most wavelengths a path of `scene` carries: M = min(the
    /// sampling's paths, [`HERO_WAVELENGTHS`]).
    pub fn most(scene: &PreparedScene) -> u32 {
        scene.scene.render.wavelengths.paths(scene.bands.len()).min(HERO_WAVELENGTHS)
    }

    /// The largest factor [`IndirectWavelengths::at_light`] gives a
    /// path's flux: N/M (a coloured light's M stratified bands, each
    /// weighted by its share × N/M, shares summing to at most 1), at least 1.
    pub fn largest_share(scene: &PreparedScene) -> f32 {
        (scene.bands.len() as f32 / Self::most(scene) as f32).max(1.0)
    }

    /// The band the path's random numbers are drawn for: its one
    /// wavelength's, or [`WHITE_BAND`] while it carries several.
    pub fn path_band(&self) -> u16 {
        if self.count == 1 { self.band[0] } else { WHITE_BAND }
    }

    /// The wavelength a path of one wavelength is traced at.
    pub fn path_lambda(&self) -> Option<f32> {
        if self.count == 1 { self.lambda_nm[0] } else { None }
    }

    /// Whether the path carries several wavelengths.
    pub fn several(&self) -> bool {
        self.count > 1
    }

    /// A diffuse bounce off a surface that reflects `reflectance(band,
    /// wavelength)`: the probability p = Σ fⱼ ρⱼ that the path survives
    /// (Russian roulette, so its flux stays), and the fractions fⱼ ρⱼ / p
    /// it goes on with. With one wavelength p = ρ and the fraction stays 1.
    pub fn bounce(&self, bands: &BandTable, reflectance: impl Fn(u16, f32) -> f32) -> (f32, Self) {
        let n = self.count;
        let mut rho = [0.0f32; 4];
        let mut p = 0.0;
        for (j, r) in rho[..n].iter_mut().enumerate() {
            *r = reflectance(self.band[j], stored_wavelength(bands, self.band[j], self.lambda_nm[j]));
            p += self.fraction[j] * *r;
        }
        let mut after = *self;
        if p > 0.0 {
            for (f, r) in after.fraction[..n].iter_mut().zip(rho) {
                *f = *f * r / p;
            }
        }
        (p, after)
    }

    /// The one wavelength the path goes on as at glass that disperses or
    /// tints light: wavelength j with probability fⱼ against the uniform
    /// number `u` ([`dim::choose`]), carrying the path's whole flux (an
    /// unbiased choice: fⱼ·1/fⱼ).
    pub fn choose(&self, u: f32) -> Self {
        let mut acc = 0.0;
        let mut j = self.count - 1;
        for k in 0..self.count {
            acc += self.fraction[k];
            if u < acc {
                j = k;
                break;
            }
        }
        let mut one = *self;
        one.count = 1;
        (one.band[0], one.lambda_nm[0], one.fraction[0]) = (self.band[j], self.lambda_nm[j], 1.0);
        one
    }

    /// The photons a path of `flux` stores at `point` (arriving along
    /// `direction`, after `bounces`), one per wavelength in band order.
    pub fn photons<'a>(
        &'a self,
        bands: &'a BandTable,
        (point, direction): (Vec3, Vec3),
        flux: f32,
        emission: u32,
        bounces: u32,
    ) -> impl Iterator<Item = Photon> + 'a {
        let direction_oct = oct_pack(direction);
        (0..self.count).map(move |j| Photon {
            position: point.to_array(),
            flux: flux * self.fraction[j],
            direction_oct,
            lambda_nm: stored_wavelength(bands, self.band[j], self.lambda_nm[j]),
            emission,
            band: self.band[j],
            bounces: bounces as u16,
        })
    }
}
