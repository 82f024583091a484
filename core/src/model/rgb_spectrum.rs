//! RGB to a smooth spectrum (Jakob & Hanika, "A Low-Dimensional Function
//! Space for Efficient Spectral Upsampling", 2019): s(λ) = S(c₀t² + c₁t +
//! c₂) with t = (λ − 380 nm)/400 nm and the sigmoid S(x) = ½ + x/(2√(1 +
//! x²)), whose three coefficients are fitted so that the spectrum under the
//! equal-energy light has the given colour (in the renderer's linear RGB,
//! where that light is white).
//!
//! Chosen over Smits (1999) and over Meng et al. (2015) because it is
//! smooth (no steps at bin edges), bounded in [0, 1] (a valid reflectance,
//! and so a valid relative emission), three numbers per colour, and fits
//! the whole sRGB gamut; the paper precomputes a 64³ table per colour
//! space to serve textures, which a light's few colours do not need: here
//! the fit runs when a scene is read (Gauss–Newton from the middle grey's
//! flat spectrum, walking toward the target in eight steps as the paper's
//! table does from its centre). Equal channels give the flat spectrum
//! exactly.

use crate::model::cie::VISIBLE_NM;
use crate::model::wavelength_rgb::WavelengthRgb;
use crate::util::math::sqrt_f64;
use glam::{DMat3, DVec3};

/// The sigmoid S(x) = ½ + x / (2√(1 + x²)).
#[inline]
pub fn sigmoid(x: f64) -> f64 {
    0.5 + x / (2.0 * sqrt_f64(1.0 + x * x))
}

/// The spectrum of coefficients `c` at `nm`.
#[inline]
pub fn smooth_power(c: [f32; 3], nm: f64) -> f64 {
    let t = (nm - f64::from(VISIBLE_NM.0)) / f64::from(VISIBLE_NM.1 - VISIBLE_NM.0);
    sigmoid((f64::from(c[0]) * t + f64::from(c[1])) * t + f64::from(c[2]))
}

/// Wavelengths the fit samples (1 nm over the visible range).
const SAMPLES: usize = 401;

/// The 1 nm samples of the visible range with their trapezoid weights
/// (which sum to 1).
fn samples() -> impl Iterator<Item = (f64, f64)> {
    (0..SAMPLES).map(|i| {
        let w = if i == 0 || i == SAMPLES - 1 { 0.5 } else { 1.0 };
        (f64::from(VISIBLE_NM.0) + i as f64, w / (SAMPLES - 1) as f64)
    })
}

/// The colour of `power` under the equal-energy light: its mean over the
/// visible range times the colour of each wavelength.
pub fn colour_of(power: impl Fn(f64) -> f64, colours: &WavelengthRgb) -> DVec3 {
    samples().map(|(nm, w)| colours.at(nm as f32).as_dvec3() * (power(nm) * w)).sum()
}

/// The mean of `power` over the visible range.
pub fn mean_of(power: impl Fn(f64) -> f64) -> f64 {
    samples().map(|(nm, w)| power(nm) * w).sum()
}

/// The coefficients whose spectrum has colour `rgb` (each channel in
/// [0, 1]) under the equal-energy light, or `None` for equal channels
/// (the flat spectrum, which no finite coefficients give exactly).
pub fn fit(rgb: DVec3, colours: &WavelengthRgb) -> Option<[f32; 3]> {
    if rgb.x == rgb.y && rgb.y == rgb.z {
        return None;
    }
    let target = rgb.clamp(DVec3::ZERO, DVec3::ONE);
    let (lo, span) = (f64::from(VISIBLE_NM.0), f64::from(VISIBLE_NM.1 - VISIBLE_NM.0));
    let rows: alloc::vec::Vec<(f64, DVec3)> =
        samples().map(|(nm, w)| ((nm - lo) / span, colours.at(nm as f32).as_dvec3() * w)).collect();
    // The colour of coefficients c, and its Jacobian (columns ∂/∂c₀, ∂/∂c₁, ∂/∂c₂).
    let evaluate = |c: DVec3| {
        let (mut colour, mut j) = (DVec3::ZERO, DMat3::ZERO);
        for &(t, weight) in &rows {
            let x = (c.x * t + c.y) * t + c.z;
            let slope = 0.5 / ((1.0 + x * x) * sqrt_f64(1.0 + x * x));
            colour += weight * sigmoid(x);
            j.x_axis += weight * (slope * t * t);
            j.y_axis += weight * (slope * t);
            j.z_axis += weight * slope;
        }
        (colour, j)
    };
    let mut c = DVec3::ZERO;
    const STEPS: u32 = 8;
    for step in 1..=STEPS {
        let goal = DVec3::splat(0.5).lerp(target, f64::from(step) / f64::from(STEPS));
        for _ in 0..40 {
            let (colour, j) = evaluate(c);
            let r = colour - goal;
            if r.abs().max_element() < 1e-7 {
                break;
            }
            if j.determinant().abs() < 1e-300 {
                break;
            }
            // Gauss–Newton with step halving while the residual grows.
            let delta = j.inverse() * r;
            let mut scale = 1.0;
            let before = r.length_squared();
            while scale > 1e-4 {
                let next = c - delta * scale;
                if (evaluate(next).0 - goal).length_squared() < before {
                    c = next;
                    break;
                }
                scale *= 0.5;
            }
            if scale <= 1e-4 {
                break;
            }
        }
    }
    Some(c.as_vec3().to_array())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// RGB → spectrum → RGB under the equal-energy light: within 1/255 for
    /// the gamut's corners and a grid of its interior (the worst is about
    /// 1e-4 of 1/255: the colour of a wavelength has negative lobes, so the
    /// sigmoid reaches even the primaries).
    #[test]
    fn rgb_round_trips_through_its_spectrum() {
        let colours = WavelengthRgb::new();
        let mut worst = 0.0f64;
        let levels = [0.0, 0.05, 0.2, 0.35, 0.5, 0.65, 0.8, 0.95, 1.0];
        for r in levels {
            for g in levels {
                for b in levels {
                    let rgb = DVec3::new(r, g, b);
                    let Some(c) = fit(rgb, &colours) else { continue };
                    let back = colour_of(|nm| smooth_power(c, nm), &colours);
                    worst = worst.max((back - rgb).abs().max_element());
                }
            }
        }
        assert!(worst < 1.0 / 255.0, "worst channel error {worst}");
    }

    #[test]
    fn equal_channels_are_the_flat_spectrum() {
        assert_eq!(fit(DVec3::splat(0.7), &WavelengthRgb::new()), None);
    }
}
