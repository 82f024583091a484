//! Beer–Lambert absorption inside coloured glass: the absorption
//! coefficients of a dielectric for white light (per RGB channel) and for
//! each band, and the transmittance of a path length inside.
//!
//! A scene states the colour the way glTF does ([`Attenuation`]): the
//! fraction of each linear RGB channel left after a distance, so channel c
//! is absorbed with σ_c = −ln(color_c)/distance. A band is absorbed with
//! the σ of its colour: the channels' σ averaged with the band's RGB weight
//! (negative parts left out), so a red band is absorbed like the red
//! channel and a yellow band like red and green together. White view rays
//! keep the three channels; band photons and band view rays use their
//! band's σ.

use crate::model::bands::BandTable;
use crate::model::photon::WHITE_BAND;
use crate::model::scene::Attenuation;
use crate::util::math::{exp, ln};
use alloc::vec::Vec;
use glam::Vec3;

/// A dielectric's absorption coefficients (per world unit of path inside).
#[derive(Clone, Debug, PartialEq)]
pub struct Absorption {
    /// σ per linear RGB channel, for white view rays.
    pub rgb: Vec3,
    /// σ per band of the render's band table.
    pub band: Vec<f32>,
}

impl Absorption {
    /// The coefficients of `attenuation` for the bands of `bands`; `None`
    /// for clear glass (every channel kept whole).
    pub fn new(attenuation: &Attenuation, bands: &BandTable) -> Option<Self> {
        let c = attenuation.color;
        let rgb = Vec3::new(-ln(c.x), -ln(c.y), -ln(c.z)) / attenuation.distance;
        if rgb.max_element() <= 0.0 {
            return None;
        }
        let white = white_coefficient(rgb);
        let band = bands
            .bands()
            .iter()
            .map(|b| {
                let w = b.weight.max(Vec3::ZERO);
                let sum = w.x + w.y + w.z;
                if sum > 0.0 { w.dot(rgb) / sum } else { white }
            })
            .collect();
        Some(Absorption { rgb, band })
    }

    /// σ for `band` ([`WHITE_BAND`]: the white photon's).
    #[inline]
    pub fn coefficient(&self, band: u16) -> f32 {
        if band == WHITE_BAND { white_coefficient(self.rgb) } else { self.band[usize::from(band)] }
    }

    /// The fraction of a `band` photon or view ray that crosses `length` inside.
    #[inline]
    pub fn transmittance(&self, band: u16, length: f32) -> f32 {
        exp(-self.coefficient(band) * length)
    }

    /// What a view ray keeps of each RGB channel after `length` inside: the
    /// channels' own for white rays, the band's σ in all three for a band.
    #[inline]
    pub fn view_transmittance(&self, band: u16, length: f32) -> Vec3 {
        if band == WHITE_BAND {
            Vec3::new(exp(-self.rgb.x * length), exp(-self.rgb.y * length), exp(-self.rgb.z * length))
        } else {
            Vec3::splat(self.transmittance(band, length))
        }
    }
}

/// σ of a white photon that does not split, the channels' mean (the plan
/// splits white photons at coloured glass, so only a band without RGB
/// weight meets it; WGSL `absorption_coefficient` has the same sum).
#[inline]
fn white_coefficient(rgb: Vec3) -> f32 {
    (rgb.x + rgb.y + rgb.z) / 3.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::bands::BandSpec;

    #[test]
    fn white_light_keeps_the_stated_colour_after_the_stated_distance() {
        let bands = BandTable::new(BandSpec::Paper7);
        let a = Attenuation { color: Vec3::new(0.9, 0.5, 0.25), distance: 2.0 };
        let abs = Absorption::new(&a, &bands).expect("coloured");
        let kept = abs.view_transmittance(WHITE_BAND, 2.0);
        assert!((kept - a.color).abs().max_element() < 1e-6, "{kept}");
        // Half the distance keeps the square root; the bands are absorbed
        // between the extreme channels, red bands least.
        assert!(
            (abs.view_transmittance(WHITE_BAND, 1.0) - Vec3::new(0.9f32.sqrt(), 0.5f32.sqrt(), 0.5))
                .abs()
                .max_element()
                < 1e-6
        );
        let (lo, hi) = (abs.rgb.min_element(), abs.rgb.max_element());
        assert!(abs.band.iter().all(|&s| s >= lo - 1e-6 && s <= hi + 1e-6), "{:?}", abs.band);
        assert!(abs.band[0] < abs.band[6], "red {} violet {}", abs.band[0], abs.band[6]);
    }

    #[test]
    fn clear_glass_has_no_absorption() {
        let bands = BandTable::new(BandSpec::Paper3);
        assert_eq!(Absorption::new(&Attenuation { color: Vec3::ONE, distance: 1.0 }, &bands), None);
    }
}
