//! Spectral band tables: N bands, each with a wavelength and an RGB weight,
//! and the colour of the paths traced in them.
//!
//! The weights of every table sum to white, (1, 1, 1), so that a white photon
//! split into all bands is white again. Presets `paper3` and `paper7`
//! reproduce Gwak & Ryou's Tables 1 and 3; `physical(N)` cuts 380–780 nm into
//! N equal intervals and weights each by the CIE 1931 colour-matching
//! functions integrated over it, converted to linear sRGB and normalised per
//! channel. Such weights may be negative (spectral colours lie outside sRGB).
//!
//! A path traced at its own wavelength within a physically based band
//! (continuous and hero sampling, see [`BandTable::colour_by_wavelength`])
//! is coloured by that wavelength ([`WavelengthRgb`]), not by its band's
//! weight: the band count then stratifies the spectrum without quantising
//! its colour. Paths at a band's own wavelength (split and random-band
//! sampling), and every path of the paper's presets, keep the band's weight.
//!
//! A path coloured by its wavelength is reflected by a diffuse surface's
//! reflectance at that wavelength ([`BandTable::reflectance`], the albedo's
//! spectrum of [`ReflectancePrimaries`]), so that a coloured light on a
//! coloured surface reflects the product of their spectra; the others are
//! reflected channel by channel, by the RGB albedo.

use alloc::vec::Vec;
use core::fmt;
use glam::{DVec3, Vec3};

pub use crate::model::cie::VISIBLE_NM;
use crate::model::photon::WHITE_BAND;
use crate::model::reflectance::ReflectancePrimaries;
use crate::model::wavelength_rgb::WavelengthRgb;

/// The most bands a table may have (the photon stores its band in a `u16`,
/// and shaders size per-band arrays by it).
pub const MAX_BANDS: usize = 256;

/// Which band table a render uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BandSpec {
    /// The paper's three bands R, G, B (Table 1).
    Paper3,
    /// The paper's seven rainbow bands (Table 3).
    Paper7,
    /// N physically based bands over 380–780 nm, weights from CIE 1931.
    Physical(u16),
}

impl fmt::Display for BandSpec {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            BandSpec::Paper3 => f.write_str("paper3"),
            BandSpec::Paper7 => f.write_str("paper7"),
            BandSpec::Physical(n) => write!(f, "{n}"),
        }
    }
}

/// One spectral band.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Band {
    /// Name for the paper's bands ("red", …); `None` for physically based ones.
    pub name: Option<&'static str>,
    /// The wavelength photons of this band are traced with, in nm.
    pub lambda_nm: f32,
    /// The interval of the spectrum the band stands for, in nm.
    pub interval_nm: (f32, f32),
    /// Linear RGB weight C_i of the band; the weights of a table sum to (1, 1, 1).
    pub weight: Vec3,
}

/// An ordered table of bands (ordered from long to short wavelength for the
/// paper presets, short to long for physical tables; the index is the band id).
#[derive(Clone, Debug, PartialEq)]
pub struct BandTable {
    spec: BandSpec,
    bands: Vec<Band>,
    /// The colour of paths at their own wavelength, when they take it from there.
    by_wavelength: Option<WavelengthRgb>,
    /// The albedos' reflectance spectra, with `by_wavelength`.
    primaries: Option<ReflectancePrimaries>,
}

/// The paper's Table 1: (name, nominal wavelength in nm, weight). The paper
/// gives indices of refraction, not wavelengths; the wavelengths are the
/// nominal colours of its bands and are what physically based glasses use.
const PAPER3: [(&str, f32, [f32; 3]); 3] =
    [("red", 650.0, [1.0, 0.0, 0.0]), ("green", 550.0, [0.0, 1.0, 0.0]), ("blue", 450.0, [0.0, 0.0, 1.0])];

/// The paper's Table 3, with the +0.002/+0.002/+0.001 corrections it prints so
/// that each channel sums to exactly 1.
const PAPER7: [(&str, f32, [f32; 3]); 7] = [
    ("red", 650.0, [0.265, 0.0, 0.0]),
    ("orange", 600.0, [0.263, 0.244, 0.0]),
    ("yellow", 580.0, [0.263, 0.377, 0.0]),
    ("green", 550.0, [0.0, 0.379, 0.0]),
    ("blue", 470.0, [0.0, 0.0, 0.498]),
    ("indigo", 440.0, [0.077, 0.0, 0.253]),
    ("violet", 410.0, [0.132, 0.0, 0.249]),
];

impl BandTable {
    /// Builds the table for `spec`. `Physical(n)` needs `1 <= n <= MAX_BANDS`
    /// (checked by scene validation; out-of-range values are clamped here).
    pub fn new(spec: BandSpec) -> Self {
        let bands = match spec {
            BandSpec::Paper3 => paper(&PAPER3),
            BandSpec::Paper7 => paper(&PAPER7),
            BandSpec::Physical(n) => physical(usize::from(n).clamp(1, MAX_BANDS)),
        };
        BandTable { spec, bands, by_wavelength: None, primaries: None }
    }

    /// This table, colouring paths by their own wavelength when `continuous`
    /// (paths traced at a wavelength of their own) and the bands are
    /// physically based; the paper's presets keep their weights.
    pub fn colour_by_wavelength(mut self, continuous: bool) -> Self {
        let physical = matches!(self.spec, BandSpec::Physical(_));
        self.by_wavelength = (continuous && physical).then(WavelengthRgb::new);
        self.primaries = (continuous && physical).then(ReflectancePrimaries::new);
        self
    }

    /// The albedos' reflectance spectra, when paths take their colour from
    /// their wavelength.
    pub fn reflectance_primaries(&self) -> Option<&ReflectancePrimaries> {
        self.primaries.as_ref()
    }

    /// What a diffuse surface of RGB albedo `albedo` reflects of a path of
    /// band `band` at `lambda_nm`, per RGB channel of the path's colour: its
    /// reflectance ρ(λ) in every channel when paths are coloured by their
    /// wavelength, else the albedo channel by channel (white light, the
    /// paper's presets, split and random-band sampling). An albedo with
    /// equal channels reflects exactly them (a grey's spectrum is flat).
    #[inline]
    pub fn reflectance(&self, albedo: Vec3, band: u16, lambda_nm: f32) -> Vec3 {
        match &self.primaries {
            Some(p) if band != WHITE_BAND && (albedo.x != albedo.y || albedo.y != albedo.z) => {
                Vec3::splat(p.reflectance(albedo, lambda_nm))
            }
            _ => albedo,
        }
    }

    /// The share of a path's flux that a diffuse surface of RGB albedo
    /// `albedo` reflects, the survival probability of indirect light's
    /// Russian roulette: ρ(λ) when paths are coloured by their wavelength
    /// (exact), else the albedo weighted by the path's colour (a band's
    /// colour is one number after the bounce, so a coloured surface's
    /// light keeps the band's hue: exact for grey surfaces and the paper's
    /// primaries). At most 1.
    #[inline]
    pub fn bounce_reflectance(&self, albedo: Vec3, band: u16, lambda_nm: f32) -> f32 {
        let grey = albedo.x == albedo.y && albedo.y == albedo.z;
        match &self.primaries {
            _ if grey => albedo.x.clamp(0.0, 1.0),
            Some(p) if band != WHITE_BAND => p.reflectance(albedo, lambda_nm).clamp(0.0, 1.0),
            _ => {
                let colour = self.rgb_of_flux(band, lambda_nm, 1.0).max(Vec3::ZERO);
                let total = colour.x + colour.y + colour.z;
                let mean = (albedo.x + albedo.y + albedo.z) / 3.0;
                if total > 0.0 { (colour.dot(albedo) / total).clamp(0.0, 1.0) } else { mean.clamp(0.0, 1.0) }
            }
        }
    }

    /// The colour of each wavelength, when paths take their colour from it.
    pub fn wavelength_colours(&self) -> Option<&WavelengthRgb> {
        self.by_wavelength.as_ref()
    }

    /// The spec this table was built from.
    pub fn spec(&self) -> BandSpec {
        self.spec
    }

    /// The bands, indexed by band id.
    pub fn bands(&self) -> &[Band] {
        &self.bands
    }

    /// Number of bands N.
    pub fn len(&self) -> usize {
        self.bands.len()
    }

    /// Never true for a valid table; here for clippy's `len_without_is_empty`.
    pub fn is_empty(&self) -> bool {
        self.bands.is_empty()
    }

    /// Band `i`.
    pub fn band(&self, i: usize) -> &Band {
        &self.bands[i]
    }

    /// Σ C_i over the table (white, (1, 1, 1), up to rounding).
    pub fn white(&self) -> Vec3 {
        self.bands.iter().map(|b| b.weight).sum()
    }

    /// Linear RGB of flux `flux` carried by a path of band `band` at
    /// wavelength `lambda_nm` (or white light for
    /// [`crate::model::photon::WHITE_BAND`]): Φ times the colour of
    /// `lambda_nm` when paths are coloured by wavelength, else N·C_i·Φ
    /// (one band carries 1/N of the white flux and its weight is 1/N of
    /// white on average).
    #[inline]
    pub fn rgb_of_flux(&self, band: u16, lambda_nm: f32, flux: f32) -> Vec3 {
        match (self.bands.get(usize::from(band)), &self.by_wavelength) {
            (None, _) => Vec3::splat(flux),
            (Some(_), Some(colours)) => colours.at(lambda_nm) * flux,
            (Some(b), None) => b.weight * (flux * self.bands.len() as f32),
        }
    }

    /// The hue one path of band `band` at `lambda_nm` adds to the paper's
    /// estimator (C_i, or the colour of the wavelength over N); white
    /// light's is (1, 1, 1), counted in every band.
    #[inline]
    pub fn hue(&self, band: u16, lambda_nm: f32) -> Vec3 {
        match (self.bands.get(usize::from(band)), &self.by_wavelength) {
            (None, _) => Vec3::ONE,
            (Some(_), Some(colours)) => colours.at(lambda_nm) / self.bands.len() as f32,
            (Some(b), None) => b.weight,
        }
    }

    /// The largest magnitude of any channel a path's colour (per unit of
    /// flux, before the factor N of a band's weight) can have: what
    /// fixed-point sums size their terms by.
    pub fn max_colour(&self) -> f32 {
        let n = self.bands.len() as f32;
        match &self.by_wavelength {
            Some(colours) => colours.max_channel() / n,
            None => self.bands.iter().map(|b| b.weight.abs().max_element()).fold(0.0, f32::max),
        }
    }
}

fn paper(rows: &[(&'static str, f32, [f32; 3])]) -> Vec<Band> {
    rows.iter()
        .enumerate()
        .map(|(i, &(name, lambda, w))| {
            // Interval: halfway to the neighbours (the ends extend symmetrically).
            let prev = if i > 0 { rows[i - 1].1 } else { lambda + (lambda - rows[1].1) };
            let next = if i + 1 < rows.len() { rows[i + 1].1 } else { lambda - (rows[i - 1].1 - lambda) };
            Band {
                name: Some(name),
                lambda_nm: lambda,
                interval_nm: ((lambda + next) * 0.5, (lambda + prev) * 0.5),
                weight: Vec3::from(w),
            }
        })
        .collect()
}

fn physical(n: usize) -> Vec<Band> {
    let (lo, hi) = (VISIBLE_NM.0 as f64, VISIBLE_NM.1 as f64);
    let width = (hi - lo) / n as f64;
    let rgb: Vec<DVec3> = (0..n)
        .map(|i| {
            let a = lo + width * i as f64;
            crate::model::color::xyz_to_linear_srgb(crate::model::cie::integrate(a, a + width))
        })
        .collect();
    let total: DVec3 = rgb.iter().copied().sum();
    (0..n)
        .map(|i| {
            let a = lo + width * i as f64;
            Band {
                name: None,
                lambda_nm: (a + width * 0.5) as f32,
                interval_nm: (a as f32, (a + width) as f32),
                weight: (rgb[i] / total).as_vec3(),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_table_sums_to_white() {
        let mut specs = alloc::vec![BandSpec::Paper3, BandSpec::Paper7];
        specs.extend([1u16, 2, 3, 7, 16, 64, 256].map(BandSpec::Physical));
        for spec in specs {
            let t = BandTable::new(spec);
            assert!((t.white() - Vec3::ONE).abs().max_element() < 1e-5, "{spec}: {}", t.white());
        }
    }

    /// A physically based band's weight N·C_i is the colour of a
    /// wavelength averaged over the band: colouring paths by their
    /// wavelength and by their band agree on average.
    #[test]
    fn a_physical_band_weight_is_the_colours_mean_over_the_band() {
        let rgb = crate::model::wavelength_rgb::WavelengthRgb::new();
        for n in [1u16, 3, 8, 32] {
            let table = BandTable::new(BandSpec::Physical(n));
            for band in table.bands() {
                let (lo, hi) = band.interval_nm;
                let want = band.weight * f32::from(n);
                let got = rgb.mean(lo, hi);
                assert!((got - want).abs().max_element() < 2e-3, "{n} bands, {lo}–{hi} nm: {got} vs {want}");
            }
        }
    }

    #[test]
    fn physical_bands_have_plausible_hues() {
        let t = BandTable::new(BandSpec::Physical(3));
        // Equal thirds of 380–780 nm: blue; green-to-orange (yellow, since the
        // eye sees little of the long third, most of red's weight is here); red.
        let w: Vec<Vec3> = t.bands().iter().map(|b| b.weight).collect();
        assert!(w[0].z > w[0].x && w[0].z > w[0].y);
        assert!(w[1].x > w[1].z && w[1].y > w[1].z);
        assert!(w[2].x > w[2].y && w[2].x > w[2].z);
    }

    #[test]
    fn a_grey_reflects_exactly_itself_and_a_colour_its_spectrum() {
        let table = BandTable::new(BandSpec::Physical(16)).colour_by_wavelength(true);
        for g in [0.0, 0.3, 1.0] {
            for nm in [380.0, 455.5, 589.0, 780.0] {
                assert_eq!(table.reflectance(Vec3::splat(g), 3, nm), Vec3::splat(g), "grey {g} at {nm} nm");
            }
        }
        // A red surface reflects red light and little violet, in every channel of the path's colour.
        let red = Vec3::new(0.9, 0.1, 0.1);
        let at_700 = table.reflectance(red, 15, 700.0);
        assert!(at_700.x > 0.85 && at_700.x == at_700.y && at_700.y == at_700.z, "{at_700}");
        assert!(table.reflectance(red, 0, 420.0).x < 0.2);
        // White light and band-coloured paths are reflected channel by channel.
        assert_eq!(table.reflectance(red, WHITE_BAND, 0.0), red);
        assert_eq!(BandTable::new(BandSpec::Paper7).colour_by_wavelength(true).reflectance(red, 0, 650.0), red);
        assert_eq!(BandTable::new(BandSpec::Physical(16)).reflectance(red, 15, 755.0), red);
    }
}
