//! The colour of light at one wavelength: linear sRGB of unit flux at λ,
//! from the CIE 1931 colour-matching functions, normalised so that the
//! equal-energy spectrum over the visible range is white, (1, 1, 1).
//!
//! A path traced at its own wavelength λ (continuous and hero sampling)
//! adds its flux times [`WavelengthRgb::at`]`(λ)`: with λ uniform over
//! 380–780 nm the mean is white, so white light stays white, and the image
//! converges to the spectral limit whatever the band count (bands only
//! stratify the spectrum). A physically based band's weight is this
//! colour's mean over the band's interval, divided by N: the two agree.

use crate::model::cie::{self, VISIBLE_NM};
use crate::model::color::xyz_to_linear_srgb;
use glam::{DVec3, Vec3};

/// First wavelength of the table, in nm (the CIE table's).
pub const FIRST_NM: f32 = cie::FIRST_NM as f32;
/// Spacing of the table, in nm.
pub const STEP_NM: f32 = cie::STEP_NM as f32;
/// Rows of the table (360–830 nm).
pub const ROWS: usize = cie::ROWS;

/// The colour of unit flux at each wavelength of the CIE table, read by
/// linear interpolation (the colour-matching functions are linear
/// between their rows, and so is their colour).
#[derive(Clone, Debug, PartialEq)]
pub struct WavelengthRgb {
    rows: [Vec3; ROWS],
}

impl Default for WavelengthRgb {
    fn default() -> Self {
        Self::new()
    }
}

impl WavelengthRgb {
    /// The table, white for the equal-energy spectrum over [`VISIBLE_NM`]
    /// (the paper's white: each channel is divided by its mean over the
    /// range, as the band tables' weights are).
    pub fn new() -> Self {
        let (lo, hi) = (f64::from(VISIBLE_NM.0), f64::from(VISIBLE_NM.1));
        let mean = xyz_to_linear_srgb(cie::integrate(lo, hi)) / (hi - lo);
        let rows = cie::rows().map(|xyz: DVec3| (xyz_to_linear_srgb(xyz) / mean).as_vec3());
        WavelengthRgb { rows }
    }

    /// The rows, for backends that read the table themselves.
    pub fn rows(&self) -> &[Vec3; ROWS] {
        &self.rows
    }

    /// Linear RGB of unit flux at `lambda_nm` (zero outside 360–830 nm).
    #[inline]
    pub fn at(&self, lambda_nm: f32) -> Vec3 {
        let x = (lambda_nm - FIRST_NM) / STEP_NM;
        if !(x >= 0.0 && x <= (ROWS - 1) as f32) {
            return Vec3::ZERO;
        }
        let i = (x as usize).min(ROWS - 2);
        let f = x - i as f32;
        self.rows[i] + (self.rows[i + 1] - self.rows[i]) * f
    }

    /// The mean colour over `lo_nm..hi_nm` (the trapezoid rule on a
    /// 1/8 nm grid; the colour of the equal-energy light of that interval).
    pub fn mean(&self, lo_nm: f32, hi_nm: f32) -> Vec3 {
        let steps = (((hi_nm - lo_nm) * 8.0) as usize).max(1);
        let h = (hi_nm - lo_nm) / steps as f32;
        let mut sum = (self.at(lo_nm) + self.at(hi_nm)) * 0.5;
        for k in 1..steps {
            sum += self.at(lo_nm + h * k as f32);
        }
        sum / steps as f32
    }

    /// The largest magnitude of any channel at any wavelength (fixed-point
    /// sums size their terms by it).
    pub fn max_channel(&self) -> f32 {
        self.rows.iter().map(|r| r.abs().max_element()).fold(0.0, f32::max)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equal_energy_light_is_white() {
        let m = WavelengthRgb::new().mean(VISIBLE_NM.0, VISIBLE_NM.1);
        assert!((m - Vec3::ONE).abs().max_element() < 1e-4, "{m}");
    }

    #[test]
    fn hues_along_the_spectrum() {
        let rgb = WavelengthRgb::new();
        let (blue, green, red) = (rgb.at(450.0), rgb.at(530.0), rgb.at(640.0));
        assert!(blue.z > blue.x && blue.z > blue.y, "{blue}");
        assert!(green.y > green.x && green.y > green.z, "{green}");
        assert!(red.x > red.y && red.x > red.z, "{red}");
        assert_eq!(rgb.at(300.0), Vec3::ZERO);
        assert_eq!(rgb.at(f32::NAN), Vec3::ZERO);
    }
}
