//! The wavelengths a photon path is traced at: the band a white photon
//! continues as, the bands or hero wavelengths it splits into, and the
//! paths a coloured light's photon starts as, all from the photon's one
//! spectrum number.

use crate::model::scene::WavelengthSampling;
use crate::plan::prepared::PreparedScene;
use crate::sampling::light_spectrum::LightSpectrum;
use crate::sampling::sobol::photon_f32;
use crate::util::rng::dim;
use alloc::vec::Vec;

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
