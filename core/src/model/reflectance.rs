//! The reflectance spectrum of an RGB albedo: ρ(λ) = r·R(λ) + g·G(λ) +
//! b·B(λ), with three fixed primary spectra (Mallett & Yuksel, "Spectral
//! Primary Decomposition for Rendering with sRGB Reflectance", EGSR 2019),
//! so that a coloured light on a coloured surface reflects the product of
//! their spectra, not of their RGB colours.
//!
//! The primaries are `core/data/reflectance_primaries.csv`, computed by
//! `scripts/reflectance_primaries.py` for this renderer's colour space (the
//! colour of a wavelength, [`crate::model::wavelength_rgb`], where the
//! equal-energy light is white): the smoothest spectra that lie in [0, 1],
//! sum to 1 at every wavelength and have the colours (1, 0, 0), (0, 1, 0)
//! and (0, 0, 1) under that light. So every albedo in the unit cube is a
//! valid reflectance, white (1, 1, 1) and every grey are exactly flat, and
//! RGB → spectrum → RGB is exact.
//!
//! Chosen over Jakob & Hanika's sigmoid polynomials (which
//! [`crate::model::rgb_spectrum`] fits to lights' colours) because the
//! reflectance is linear in the albedo: a texture, a checker or a
//! bilinear texel blend needs no fitted table (J&H's 64³ × 3 coefficients
//! per colour space), a visible point keeps its RGB albedo, and the light a
//! surface reflects from a light of any spectrum is a 3 × 3 matrix per
//! light times the albedo
//! ([`crate::sampling::light_spectrum::LightSpectrum::reflected`]). The
//! price: saturated colours get broader, less natural spectra than J&H's.

use crate::model::wavelength_rgb::{FIRST_NM, ROWS, STEP_NM};
use glam::Vec3;

const CSV: &str = include_str!("../../data/reflectance_primaries.csv");

/// The three primary reflectances on the colour table's grid
/// ([`crate::model::wavelength_rgb::ROWS`] rows from 360 nm at 5 nm; beyond
/// the CSV's 380–780 nm, its end rows).
#[derive(Clone, Debug, PartialEq)]
pub struct ReflectancePrimaries {
    rows: [Vec3; ROWS],
}

impl Default for ReflectancePrimaries {
    fn default() -> Self {
        Self::new()
    }
}

impl ReflectancePrimaries {
    /// Parses the compiled-in table.
    pub fn new() -> Self {
        let parsed: alloc::vec::Vec<(f32, Vec3)> = CSV
            .lines()
            .map(str::trim)
            .filter(|l| !l.is_empty() && !l.starts_with('#') && !l.starts_with("lambda"))
            .map(|l| {
                let mut f = l.split(',').map(|x| x.trim().parse::<f32>().unwrap_or(f32::NAN));
                let mut next = || f.next().unwrap_or(f32::NAN);
                (next(), Vec3::new(next(), next(), next()))
            })
            .collect();
        let (first, last) = (parsed[0], parsed[parsed.len() - 1]);
        // The CSV's first row is this grid's row `offset` (both on 5 nm steps).
        let offset = ((first.0 - FIRST_NM) / STEP_NM + 0.5) as usize;
        let rows = core::array::from_fn(|i| match i.checked_sub(offset) {
            None => first.1,
            Some(k) => parsed.get(k).map_or(last.1, |r| r.1),
        });
        ReflectancePrimaries { rows }
    }

    /// The rows, for backends that read the table themselves.
    pub fn rows(&self) -> &[Vec3; ROWS] {
        &self.rows
    }

    /// (R(λ), G(λ), B(λ)), linear between rows, the end rows beyond the table.
    #[inline]
    pub fn at(&self, lambda_nm: f32) -> Vec3 {
        let x = ((lambda_nm - FIRST_NM) / STEP_NM).clamp(0.0, (ROWS - 1) as f32);
        let i = (x as usize).min(ROWS - 2);
        let f = x - i as f32;
        self.rows[i] + (self.rows[i + 1] - self.rows[i]) * f
    }

    /// ρ(λ) of albedo `rgb`.
    #[inline]
    pub fn reflectance(&self, rgb: Vec3, lambda_nm: f32) -> f32 {
        rgb.dot(self.at(lambda_nm))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::cie::VISIBLE_NM;
    use crate::model::wavelength_rgb::WavelengthRgb;

    /// The colour of ρ under the equal-energy light: its mean over the
    /// visible range times each wavelength's colour (1/8 nm trapezoid).
    fn colour_under_e(rho: impl Fn(f32) -> f32) -> Vec3 {
        let colours = WavelengthRgb::new();
        let (lo, hi) = VISIBLE_NM;
        let steps = ((hi - lo) * 8.0) as usize;
        let h = (hi - lo) / steps as f32;
        let term = |nm: f32| colours.at(nm) * rho(nm);
        let mut sum = (term(lo) + term(hi)) * 0.5;
        for k in 1..steps {
            sum += term(lo + h * k as f32);
        }
        sum / steps as f32
    }

    #[test]
    fn primaries_are_reflectances_that_sum_to_one() {
        let p = ReflectancePrimaries::new();
        for row in p.rows() {
            assert!(row.min_element() >= 0.0 && row.max_element() <= 1.0, "{row}");
            assert!((row.element_sum() - 1.0).abs() < 1e-6, "{row}");
        }
        // White and greys are exactly flat.
        for nm in [380.0, 431.3, 555.0, 700.2, 780.0] {
            assert!((p.reflectance(Vec3::ONE, nm) - 1.0).abs() < 1e-6);
            assert!((p.reflectance(Vec3::splat(0.4), nm) - 0.4).abs() < 1e-6);
        }
    }

    #[test]
    fn rgb_to_reflectance_to_rgb_under_the_equal_energy_light() {
        let p = ReflectancePrimaries::new();
        let steps = [0.0, 0.25, 0.5, 0.75, 1.0];
        for r in steps {
            for g in steps {
                for b in steps {
                    let rgb = Vec3::new(r, g, b);
                    let back = colour_under_e(|nm| p.reflectance(rgb, nm));
                    assert!((back - rgb).abs().max_element() < 0.5 / 255.0, "{rgb} -> {back}");
                }
            }
        }
    }
}
