//! Dispersion models n(λ) and the named glasses.
//!
//! Every model gives an index of refraction for each band of any band table:
//! continuous models are evaluated at the band's wavelength; the per-band
//! table needs as many entries as there are bands; the paper's glass uses its
//! printed indices with its own presets and a Cauchy fit through them
//! otherwise.

use crate::model::bands::{BandSpec, BandTable};
use crate::util::math;
use alloc::vec::Vec;
use core::fmt;

/// Most terms a Sellmeier formula may have.
pub const MAX_SELLMEIER_TERMS: usize = 6;

/// A model of the index of refraction as a function of wavelength.
#[derive(Clone, Debug, PartialEq)]
pub enum Dispersion {
    /// The same index at every wavelength (never splits a white photon).
    Constant(f32),
    /// Cauchy: n = A + B/λ², λ in µm.
    Cauchy {
        /// A.
        a: f32,
        /// B, in µm².
        b: f32,
    },
    /// Sellmeier: n² = 1 + Σ B_k λ²/(λ² − C_k), λ in µm, C_k in µm².
    Sellmeier {
        /// B_k.
        b: Vec<f64>,
        /// C_k, in µm².
        c: Vec<f64>,
    },
    /// Abbe number form of glTF's KHR_materials_dispersion:
    /// n(λ) = n_d + (n_d − 1)/V_d · (523655/λ² − 1.5168), λ in nm.
    Abbe {
        /// n_d, the index at the helium d line (587.56 nm).
        nd: f32,
        /// V_d, the Abbe number.
        vd: f32,
    },
    /// One index per band, in band order; needs exactly N entries.
    PerBand(Vec<f32>),
    /// Measured n(λ): indices `n` at wavelengths `lambda_nm` (strictly
    /// increasing, covering the visible range), read by linear
    /// interpolation (a catalogue's or a spectrometer's table).
    Table {
        /// Wavelengths in nm, strictly increasing.
        lambda_nm: Vec<f32>,
        /// n at each wavelength.
        n: Vec<f32>,
    },
    /// The paper's glass: its Tables 1 and 3 with its presets, a Cauchy fit
    /// through Table 3 with any other band table (within 0.013 of the table).
    Paper,
}

/// The named glasses a scene may refer to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Glass {
    /// Schott N-BK7 borosilicate crown.
    Bk7,
    /// Schott N-SF11 dense flint (high dispersion).
    Sf11,
    /// Schott N-SF6 dense flint.
    Sf6,
    /// Schott N-F2 flint.
    F2,
    /// Schott N-BAF10 barium flint.
    Baf10,
    /// Schott N-LASF9 lanthanum dense flint (high index).
    Lasf9,
    /// Schott N-FK51A fluor crown (very low dispersion).
    Fk51a,
    /// Fused silica (Malitson 1965).
    FusedSilica,
    /// Water at 20 °C (Daimon & Masumura 2007).
    Water,
    /// Diamond (Peter 1923).
    Diamond,
    /// The glass of Gwak & Ryou's paper (n from 1.515 to 1.582).
    Paper,
}

/// Where the Schott glasses' Sellmeier coefficients, n_d and V_d come from.
pub const SCHOTT_SOURCE: &str = "SCHOTT optical glass data sheets (Sellmeier coefficients at 22 °C; n_d, V_d)";

/// What a catalogue publishes of a glass: n_d (587.56 nm), V_d and the source.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CatalogueEntry {
    /// Index at the helium d line, 587.5618 nm.
    pub nd: f32,
    /// Abbe number (n_d − 1)/(n_F − n_C).
    pub vd: f32,
    /// Where the figures come from.
    pub source: &'static str,
}

impl Glass {
    /// Every named glass, for listings and error messages.
    pub const ALL: [Glass; 11] = [
        Glass::Bk7,
        Glass::Sf11,
        Glass::Sf6,
        Glass::F2,
        Glass::Baf10,
        Glass::Lasf9,
        Glass::Fk51a,
        Glass::FusedSilica,
        Glass::Water,
        Glass::Diamond,
        Glass::Paper,
    ];

    /// The name used in scene files (Schott's designation, lower case).
    pub fn name(self) -> &'static str {
        match self {
            Glass::Bk7 => "n-bk7",
            Glass::Sf11 => "n-sf11",
            Glass::Sf6 => "n-sf6",
            Glass::F2 => "n-f2",
            Glass::Baf10 => "n-baf10",
            Glass::Lasf9 => "n-lasf9",
            Glass::Fk51a => "n-fk51a",
            Glass::FusedSilica => "fused_silica",
            Glass::Water => "water",
            Glass::Diamond => "diamond",
            Glass::Paper => "paper",
        }
    }

    /// Looks a glass up by its scene-file name, in any case; Schott glasses
    /// also without their "n-" (`bk7`, `SF11`).
    pub fn from_name(name: &str) -> Option<Glass> {
        Glass::ALL.into_iter().find(|g| {
            let own = g.name();
            own.eq_ignore_ascii_case(name)
                || own.strip_prefix("n-").is_some_and(|short| short.eq_ignore_ascii_case(name))
        })
    }

    /// The catalogue's n_d and V_d, for the glasses that have them.
    pub fn catalogue(self) -> Option<CatalogueEntry> {
        let schott = |nd, vd| Some(CatalogueEntry { nd, vd, source: SCHOTT_SOURCE });
        match self {
            Glass::Bk7 => schott(1.5168, 64.17),
            Glass::Sf11 => schott(1.78472, 25.68),
            Glass::Sf6 => schott(1.80518, 25.36),
            Glass::F2 => schott(1.62005, 36.43),
            Glass::Baf10 => schott(1.67003, 47.11),
            Glass::Lasf9 => schott(1.85025, 32.17),
            Glass::Fk51a => schott(1.48656, 84.47),
            Glass::FusedSilica => {
                Some(CatalogueEntry { nd: 1.458_46, vd: 67.82, source: "Malitson, JOSA 55 (1965) 1205" })
            }
            Glass::Water | Glass::Diamond | Glass::Paper => None,
        }
    }

    /// The dispersion model of the glass.
    pub fn dispersion(self) -> Dispersion {
        let sellmeier = |b: [f64; 3], c: [f64; 3]| Dispersion::Sellmeier { b: b.to_vec(), c: c.to_vec() };
        match self {
            Glass::Bk7 => {
                sellmeier([1.039_612_12, 0.231_792_344, 1.010_469_45], [0.006_000_698_67, 0.020_017_914_4, 103.560_653])
            }
            Glass::Sf11 => {
                sellmeier([1.737_596_95, 0.313_747_346, 1.898_781_01], [0.013_188_707, 0.062_306_814_2, 155.236_29])
            }
            Glass::Sf6 => {
                sellmeier([1.779_317_63, 0.338_149_866, 2.087_344_74], [0.013_371_418_2, 0.061_753_362_1, 174.017_59])
            }
            Glass::F2 => {
                sellmeier([1.397_570_37, 0.159_201_403, 1.268_654_3], [0.009_959_061_43, 0.054_693_175_2, 119.248_346])
            }
            Glass::Baf10 => {
                sellmeier([1.585_149_5, 0.143_559_385, 1.085_212_69], [0.009_266_812_82, 0.042_448_980_5, 105.613_573])
            }
            Glass::Lasf9 => {
                sellmeier([2.000_295_47, 0.298_926_886, 1.806_918_43], [0.012_142_601_7, 0.053_873_623_6, 156.530_829])
            }
            Glass::Fk51a => sellmeier(
                [0.971_247_817, 0.216_901_417, 0.904_651_666],
                [0.004_723_019_95, 0.015_357_561_2, 168.681_33],
            ),
            Glass::FusedSilica => {
                sellmeier([0.696_166_3, 0.407_942_6, 0.897_479_4], [0.004_679_148_26, 0.013_512_063_1, 97.934_002_5])
            }
            Glass::Water => Dispersion::Sellmeier {
                b: [5.684_027_565e-1, 1.726_177_391e-1, 2.086_189_578e-2, 1.130_748_688e-1].to_vec(),
                c: [5.101_829_712e-3, 1.821_153_936e-2, 2.620_722_293e-2, 1.069_792_721e1].to_vec(),
            },
            Glass::Diamond => {
                Dispersion::Sellmeier { b: [0.3306, 4.3356].to_vec(), c: [0.030_625, 0.011_236].to_vec() }
            }
            Glass::Paper => Dispersion::Paper,
        }
    }
}

impl fmt::Display for Glass {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The paper's Table 3 indices, in the order of the `paper7` bands.
const PAPER7_IOR: [f32; 7] = [1.515, 1.536, 1.547, 1.550, 1.564, 1.578, 1.582];
/// The paper's Table 1 indices, in the order of the `paper3` bands.
const PAPER3_IOR: [f32; 3] = [1.515, 1.550, 1.564];

impl Dispersion {
    /// n at wavelength `lambda_nm`, for the models that are functions of λ.
    /// `None` for the per-band table (it has no wavelength axis).
    pub fn ior_at(&self, lambda_nm: f32) -> Option<f32> {
        let l_um = f64::from(lambda_nm) * 1e-3;
        let l2 = l_um * l_um;
        Some(match self {
            Dispersion::Constant(n) => *n,
            Dispersion::Cauchy { a, b } => a + b / l2 as f32,
            Dispersion::Sellmeier { b, c } => {
                let n2 = 1.0 + b.iter().zip(c).map(|(b, c)| b * l2 / (l2 - c)).sum::<f64>();
                math::sqrt_f64(n2.max(0.0)) as f32
            }
            Dispersion::Abbe { nd, vd } => nd + (nd - 1.0) / vd * (523_655.0 / (lambda_nm * lambda_nm) - 1.5168),
            Dispersion::Paper => {
                let (a, b) = paper_cauchy_fit();
                a + b / l2 as f32
            }
            Dispersion::Table { lambda_nm: xs, n: ys } => interpolate(xs, ys, lambda_nm),
            Dispersion::PerBand(_) => return None,
        })
    }

    /// n for band `band` of `table`.
    ///
    /// # Panics
    /// For a per-band table shorter than `table` (scene validation rejects it).
    pub fn ior_for_band(&self, table: &BandTable, band: usize) -> f32 {
        match (self, table.spec()) {
            (Dispersion::PerBand(n), _) => n[band],
            (Dispersion::Paper, BandSpec::Paper7) => PAPER7_IOR[band],
            (Dispersion::Paper, BandSpec::Paper3) => PAPER3_IOR[band],
            _ => self.ior_at(table.band(band).lambda_nm).unwrap_or(1.0),
        }
    }

    /// True when the model is the same at every wavelength by construction.
    pub fn is_constant(&self) -> bool {
        matches!(self, Dispersion::Constant(_))
    }
}

/// `ys` at `x` by linear interpolation between the samples at `xs`
/// (increasing); the end values outside them.
fn interpolate(xs: &[f32], ys: &[f32], x: f32) -> f32 {
    let i = xs.partition_point(|&v| v < x);
    match (i, xs.len()) {
        (_, 0) => 1.0,
        (0, _) => ys[0],
        (i, len) if i == len => ys[len - 1],
        (i, _) => {
            let t = (x - xs[i - 1]) / (xs[i] - xs[i - 1]);
            ys[i - 1] + t * (ys[i] - ys[i - 1])
        }
    }
}

/// Least-squares Cauchy fit n = A + B/λ² through the paper's Table 3 at the
/// `paper7` band wavelengths; returns (A, B in µm²).
pub fn paper_cauchy_fit() -> (f32, f32) {
    let table = BandTable::new(BandSpec::Paper7);
    let pts = table.bands().iter().zip(PAPER7_IOR).map(|(b, n)| {
        let l_um = f64::from(b.lambda_nm) * 1e-3;
        (1.0 / (l_um * l_um), f64::from(n))
    });
    let (mut sx, mut sy, mut sxx, mut sxy, mut k) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for (x, y) in pts {
        sx += x;
        sy += y;
        sxx += x * x;
        sxy += x * y;
        k += 1.0;
    }
    let b = (k * sxy - sx * sy) / (k * sxx - sx * sx);
    let a = (sy - b * sx) / k;
    (a as f32, b as f32)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paper_fit_passes_near_the_table() {
        let (a, b) = paper_cauchy_fit();
        assert!(b > 0.0, "normal dispersion");
        for (band, n) in BandTable::new(BandSpec::Paper7).bands().iter().zip(PAPER7_IOR) {
            let l = band.lambda_nm * 1e-3;
            // The paper's red (1.515) sits 0.013 below any smooth curve through the rest.
            assert!((a + b / (l * l) - n).abs() < 0.015, "{} nm", band.lambda_nm);
        }
    }

    /// Every catalogue glass's Sellmeier curve gives the n_d and V_d the
    /// catalogue prints (to its printed precision).
    #[test]
    fn catalogue_glasses_match_their_published_nd_and_vd() {
        let (d, f, c) = (587.5618, 486.1327, 656.2725);
        let mut checked = 0;
        for glass in Glass::ALL {
            let Some(entry) = glass.catalogue() else { continue };
            let model = glass.dispersion();
            let n = |l: f32| f64::from(model.ior_at(l).unwrap());
            let nd = n(d);
            let vd = (nd - 1.0) / (n(f) - n(c));
            assert!((nd - f64::from(entry.nd)).abs() < 2e-4, "{glass}: n_d {nd} vs {}", entry.nd);
            assert!((vd - f64::from(entry.vd)).abs() < 0.1, "{glass}: V_d {vd} vs {}", entry.vd);
            checked += 1;
        }
        assert_eq!(checked, 8);
    }

    #[test]
    fn glasses_are_found_by_schott_name_in_any_case_and_by_short_name() {
        for (name, glass) in
            [("N-BK7", Glass::Bk7), ("bk7", Glass::Bk7), ("sf11", Glass::Sf11), ("N-LaSF9", Glass::Lasf9)]
        {
            assert_eq!(Glass::from_name(name), Some(glass), "{name}");
        }
        assert_eq!(Glass::from_name("n-water"), None);
        for g in Glass::ALL {
            assert_eq!(Glass::from_name(g.name()), Some(g));
        }
    }

    #[test]
    fn a_table_interpolates_linearly_and_holds_its_ends() {
        let t = Dispersion::Table { lambda_nm: vec![400.0, 500.0, 700.0], n: vec![1.60, 1.55, 1.51] };
        assert_eq!(t.ior_at(400.0), Some(1.60));
        assert!((t.ior_at(450.0).unwrap() - 1.575).abs() < 1e-6);
        assert!((t.ior_at(600.0).unwrap() - 1.53).abs() < 1e-6);
        assert_eq!(t.ior_at(350.0), Some(1.60));
        assert_eq!(t.ior_at(800.0), Some(1.51));
    }

    #[test]
    fn paper_glass_uses_the_printed_indices_with_its_presets() {
        let t7 = BandTable::new(BandSpec::Paper7);
        let t3 = BandTable::new(BandSpec::Paper3);
        let d = Dispersion::Paper;
        assert_eq!((0..7).map(|i| d.ior_for_band(&t7, i)).collect::<Vec<_>>(), PAPER7_IOR.to_vec());
        assert_eq!((0..3).map(|i| d.ior_for_band(&t3, i)).collect::<Vec<_>>(), PAPER3_IOR.to_vec());
    }
}
