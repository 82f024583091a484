//! A light's spectrum as the distribution its photons' wavelengths are
//! drawn from: an inverse cumulative table over the visible range, 1 nm
//! bins for a continuous spectrum (uniform inside each bin) and one entry
//! of zero width per line for a lamp, so that a lamp's photons sit on its
//! lines and none fall between them.
//!
//! A photon whose wavelength λ is drawn with density p(λ) = S(λ)/∫S
//! carries its share of the light's flux, and its colour is the colour of
//! λ: the estimate of ∫ S(λ)·colour(λ) dλ is unbiased for any S. The
//! equal-energy spectrum keeps the uniform draw λ = 380 + 400·v exactly.

use crate::model::bands::BandTable;
use crate::model::cie::VISIBLE_NM;
use crate::model::reflectance::ReflectancePrimaries;
use crate::model::spectrum::Spectrum;
use crate::model::wavelength_rgb::WavelengthRgb;
use alloc::vec::Vec;
use glam::{DMat3, DVec3, Mat3, Vec3};

/// The wavelength distribution of one light.
#[derive(Clone, Debug, PartialEq)]
pub struct LightSpectrum {
    /// Cumulative probability at the end of each entry (the last is 1);
    /// empty for the equal-energy spectrum (uniform).
    cdf: Vec<f32>,
    /// Where each entry starts, in nm.
    start_nm: Vec<f32>,
    /// Each entry's width in nm (0 for a line).
    width_nm: Vec<f32>,
    /// Linear RGB of unit flux: the mean colour of the light's wavelengths
    /// ((1, 1, 1) for the equal-energy spectrum).
    pub rgb: Vec3,
    /// The colour a diffuse surface reflects of this light per unit of
    /// irradiance, as a matrix over its RGB albedo: column c is the light's
    /// colour reflected by the albedo's primary spectrum c
    /// ([`crate::model::reflectance`]); the identity for the equal-energy
    /// spectrum, and `rgb` for a white albedo.
    pub reflected: Mat3,
    /// Each band's share of the light's power (1/N each for equal energy).
    pub band_shares: Vec<f32>,
}

impl LightSpectrum {
    /// The distribution of `spectrum` over the visible range, its colour
    /// and its shares of `bands`. A spectrum with no power there
    /// (validation refuses it) is uniform.
    pub fn new(spectrum: &Spectrum, bands: &BandTable) -> Self {
        let mut s = Self::table(spectrum);
        s.band_shares = s.shares_of(bands);
        s
    }

    /// The uniform distribution of the equal-energy spectrum (no shares yet).
    fn uniform() -> Self {
        LightSpectrum {
            cdf: Vec::new(),
            start_nm: Vec::new(),
            width_nm: Vec::new(),
            rgb: Vec3::ONE,
            reflected: Mat3::IDENTITY,
            band_shares: Vec::new(),
        }
    }

    /// The table and colour of `spectrum` (no shares yet).
    fn table(spectrum: &Spectrum) -> Self {
        if spectrum.is_equal_energy() {
            return Self::uniform();
        }
        let (colours, primaries) = (WavelengthRgb::new(), ReflectancePrimaries::new());
        let (lo, hi) = VISIBLE_NM;
        let entries: Vec<(f32, f32, f64)> = match spectrum.lines() {
            Some(lines) => lines
                .iter()
                .filter(|(nm, _)| (lo..hi).contains(nm))
                .map(|&(nm, power)| (nm, 0.0, f64::from(power)))
                .collect(),
            None => (0..(hi - lo) as u32)
                .map(|k| {
                    let a = f64::from(lo) + f64::from(k);
                    let power = 0.5 * (spectrum.power_at(a) + spectrum.power_at(a + 1.0));
                    (a as f32, 1.0, power.max(0.0))
                })
                .collect(),
        };
        let total: f64 = entries.iter().map(|e| e.2).sum();
        if total.is_nan() || total <= 0.0 {
            return Self::uniform();
        }
        let mut acc = 0.0;
        let (mut rgb, mut reflected) = (DVec3::ZERO, DMat3::ZERO);
        let mut cdf = Vec::with_capacity(entries.len());
        for &(start, width, power) in &entries {
            acc += power / total;
            cdf.push(acc as f32);
            let nm = start + 0.5 * width;
            let colour = colours.at(nm).as_dvec3() * (power / total);
            let p = primaries.at(nm).as_dvec3();
            rgb += colour;
            reflected += DMat3::from_cols(colour * p.x, colour * p.y, colour * p.z);
        }
        if let Some(last) = cdf.last_mut() {
            *last = 1.0;
        }
        LightSpectrum {
            cdf,
            start_nm: entries.iter().map(|e| e.0).collect(),
            width_nm: entries.iter().map(|e| e.1).collect(),
            rgb: rgb.as_vec3(),
            reflected: reflected.as_mat3(),
            band_shares: Vec::new(),
        }
    }

    /// True for the equal-energy spectrum.
    pub fn is_uniform(&self) -> bool {
        self.cdf.is_empty()
    }

    /// The wavelength at cumulative probability `v` in [0, 1).
    #[inline]
    pub fn wavelength(&self, v: f32) -> f32 {
        if self.is_uniform() {
            return VISIBLE_NM.0 + (VISIBLE_NM.1 - VISIBLE_NM.0) * v;
        }
        let k = self.cdf.partition_point(|&c| c <= v).min(self.cdf.len() - 1);
        let before = if k == 0 { 0.0 } else { self.cdf[k - 1] };
        let p = self.cdf[k] - before;
        let f = if p > 0.0 { ((v - before) / p).clamp(0.0, 1.0) } else { 0.0 };
        self.start_nm[k] + self.width_nm[k] * f
    }

    /// The fraction of the light's power in `lo_nm..hi_nm` (a line at
    /// `lo_nm` counts, one at `hi_nm` does not).
    pub fn share(&self, lo_nm: f32, hi_nm: f32) -> f32 {
        self.below(hi_nm) - self.below(lo_nm)
    }

    /// The fraction of the power below `nm`.
    fn below(&self, nm: f32) -> f32 {
        if self.is_uniform() {
            let (lo, hi) = VISIBLE_NM;
            return ((nm - lo) / (hi - lo)).clamp(0.0, 1.0);
        }
        let mut before = 0.0;
        let mut sum = 0.0;
        for k in 0..self.cdf.len() {
            let p = self.cdf[k] - before;
            before = self.cdf[k];
            let (start, width) = (self.start_nm[k], self.width_nm[k]);
            if start >= nm {
                break;
            }
            sum += if width > 0.0 { p * ((nm - start) / width).min(1.0) } else { p };
        }
        sum
    }

    /// Each band's share of the light's power (uniform: 1/N each).
    fn shares_of(&self, bands: &BandTable) -> Vec<f32> {
        let n = bands.len();
        if self.is_uniform() {
            return alloc::vec![1.0 / n as f32; n];
        }
        let shares: Vec<f32> = bands.bands().iter().map(|b| self.share(b.interval_nm.0, b.interval_nm.1)).collect();
        let total: f32 = shares.iter().sum();
        shares.iter().map(|s| if total > 0.0 { s / total } else { 0.0 }).collect()
    }

    /// The table, for backends that draw from it themselves: each entry's
    /// cumulative probability, start and width.
    pub fn entries(&self) -> (&[f32], &[f32], &[f32]) {
        (&self.cdf, &self.start_nm, &self.width_nm)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::bands::BandSpec;
    use crate::model::spectrum::Lamp;

    #[test]
    fn a_lamps_wavelengths_are_its_lines() {
        let s = LightSpectrum::new(&Spectrum::Lamp(Lamp::Mercury), &BandTable::new(BandSpec::Physical(16)));
        let lines: Vec<f32> = Lamp::Mercury.lines().iter().map(|l| l.0).collect();
        let mut count = [0u32; 6];
        for i in 0..10_000 {
            let lambda = s.wavelength((i as f32 + 0.5) / 10_000.0);
            let k = lines.iter().position(|&l| l == lambda).unwrap_or_else(|| panic!("{lambda} nm is not a line"));
            count[k] += 1;
        }
        // In proportion to the lines' powers (7570 in all).
        let powers: Vec<f32> = Lamp::Mercury.lines().iter().map(|l| l.1).collect();
        for (c, p) in count.iter().zip(&powers) {
            assert!((*c as f32 / 10_000.0 - p / 7570.0).abs() < 2e-4, "{count:?}");
        }
    }

    #[test]
    fn the_uniform_draw_and_its_shares() {
        let s = LightSpectrum::new(&Spectrum::EqualEnergy, &BandTable::new(BandSpec::Physical(8)));
        assert_eq!(s.wavelength(0.5), 580.0);
        assert!((s.share(380.0, 480.0) - 0.25).abs() < 1e-6);
        assert_eq!(s.rgb, Vec3::ONE);
        assert_eq!(s.band_shares, [0.125; 8]);
    }

    #[test]
    fn a_continuous_draw_follows_its_spectrum() {
        // A blackbody at 2000 K has far more power at 700 nm than at 420 nm:
        // the density of draws near each is in the ratio of the powers.
        let spectrum = Spectrum::Blackbody { kelvin: 2000.0 };
        let s = LightSpectrum::new(&spectrum, &BandTable::new(BandSpec::Physical(16)));
        // The bands' shares are the spectrum's, and add up to 1.
        assert!((s.band_shares[0] - s.share(380.0, 405.0)).abs() < 1e-5);
        assert!((s.band_shares.iter().sum::<f32>() - 1.0).abs() < 1e-5);
        let n = 200_000;
        let near = |at: f32| (0..n).filter(|i| (s.wavelength((*i as f32 + 0.5) / n as f32) - at).abs() < 2.0).count();
        let ratio = near(700.0) as f64 / near(420.0) as f64;
        let expected = spectrum.power_at(700.0) / spectrum.power_at(420.0);
        assert!((ratio / expected - 1.0).abs() < 0.02, "{ratio} vs {expected}");
        // Shares of a spectrum add up, and a draw below a wavelength is its share.
        assert!((s.share(380.0, 780.0) - 1.0).abs() < 1e-5);
        let below_550 = (0..n).filter(|i| s.wavelength((*i as f32 + 0.5) / n as f32) < 550.0).count();
        assert!((below_550 as f32 / n as f32 - s.share(380.0, 550.0)).abs() < 1e-4);
    }
}
