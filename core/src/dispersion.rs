//! Dispersion models n(λ) and the named glasses.
//!
//! Every model gives an index of refraction for each band of any band table:
//! continuous models are evaluated at the band's wavelength; the per-band
//! table needs as many entries as there are bands; the paper's glass uses its
//! printed indices with its own presets and a Cauchy fit through them
//! otherwise.

use crate::bands::{BandSpec, BandTable};
use crate::math;
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
    /// Fused silica (Malitson 1965).
    FusedSilica,
    /// Water at 20 °C (Daimon & Masumura 2007).
    Water,
    /// Diamond (Peter 1923).
    Diamond,
    /// The glass of Gwak & Ryou's paper (n from 1.515 to 1.582).
    Paper,
}

impl Glass {
    /// Every named glass, for listings and error messages.
    pub const ALL: [Glass; 6] =
        [Glass::Bk7, Glass::Sf11, Glass::FusedSilica, Glass::Water, Glass::Diamond, Glass::Paper];

    /// The name used in scene files.
    pub fn name(self) -> &'static str {
        match self {
            Glass::Bk7 => "bk7",
            Glass::Sf11 => "sf11",
            Glass::FusedSilica => "fused_silica",
            Glass::Water => "water",
            Glass::Diamond => "diamond",
            Glass::Paper => "paper",
        }
    }

    /// Looks a glass up by its scene-file name.
    pub fn from_name(name: &str) -> Option<Glass> {
        Glass::ALL.into_iter().find(|g| g.name() == name)
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

    #[test]
    fn paper_glass_uses_the_printed_indices_with_its_presets() {
        let t7 = BandTable::new(BandSpec::Paper7);
        let t3 = BandTable::new(BandSpec::Paper3);
        let d = Dispersion::Paper;
        assert_eq!((0..7).map(|i| d.ior_for_band(&t7, i)).collect::<Vec<_>>(), PAPER7_IOR.to_vec());
        assert_eq!((0..3).map(|i| d.ior_for_band(&t3, i)).collect::<Vec<_>>(), PAPER3_IOR.to_vec());
    }
}
