//! A metal's reflection, ready for tracing: Schlick's Fresnel from the
//! reflectance at normal incidence per RGB channel (glTF's metal), taken
//! per wavelength by that colour's reflectance spectrum as a diffuse
//! albedo is ([`crate::model::bands::BandTable::reflectance`]), and the
//! GGX distribution of its facets ([`crate::optics::microfacet`]; none on
//! a polished metal). Where the ray goes is [`crate::optics::scatter::scatter_metal`]'s.

use crate::geometry::primitive::basis;
use crate::model::bands::BandTable;
use crate::optics::microfacet::Ggx;
use glam::Vec3;

/// A metal's optics.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MetalOptics {
    /// Reflectance at normal incidence per linear RGB channel.
    pub f0: Vec3,
    /// The facets' normal distribution; `None`: polished (roughness 0).
    pub ggx: Option<Ggx>,
}

impl MetalOptics {
    /// The optics of a metal of colour `color` and glTF roughness `roughness`.
    pub fn new(color: Vec3, roughness: f32) -> Self {
        MetalOptics { f0: color, ggx: (roughness > 0.0).then(|| Ggx::from_roughness(roughness)) }
    }

    /// Schlick's Fresnel per RGB channel for light meeting a facet at
    /// cosine `cos`: F0 + (1 − F0)(1 − cos)⁵. Linear in F0, so the
    /// reflectance spectrum of this colour is Schlick's of F0's spectrum.
    #[inline]
    pub fn fresnel(&self, cos: f32) -> Vec3 {
        let x = 1.0 - cos.clamp(0.0, 1.0);
        let x2 = x * x;
        self.f0 + (Vec3::ONE - self.f0) * (x2 * x2 * x)
    }

    /// True when its wavelengths reflect differently (F0 is not grey): a
    /// white photon splits here into its bands or hero wavelengths, or
    /// goes on as one band ([`crate::photons::trace`]).
    #[inline]
    pub fn is_chromatic(&self) -> bool {
        self.f0.x != self.f0.y || self.f0.y != self.f0.z
    }

    /// The share of a photon path's flux (band `band` at `lambda_nm`)
    /// that a facet met at cosine `cos` reflects: its survival probability.
    #[inline]
    pub fn reflectance(&self, cos: f32, band: u16, lambda_nm: f32, bands: &BandTable) -> f32 {
        bands.bounce_reflectance(self.fresnel(cos), band, lambda_nm)
    }

    /// What a facet met at cosine `cos` keeps of each RGB channel of a
    /// view path of band `band` at `lambda_nm` (a white path: Fresnel per channel).
    #[inline]
    pub fn tint(&self, cos: f32, band: u16, lambda_nm: f32, bands: &BandTable) -> Vec3 {
        bands.reflectance(self.fresnel(cos), band, lambda_nm)
    }

    /// The BRDF D G2 F / (4 cos θo cos θi) per RGB channel of a view path
    /// of band `band` at `lambda_nm`, from `wi` toward `wo` about the
    /// normal `n` (unit vectors; zero unless both are above it, and for a
    /// polished metal, whose reflection is a direction, not a density).
    pub fn reflection(&self, wo: Vec3, wi: Vec3, n: Vec3, band: u16, lambda_nm: f32, bands: &BandTable) -> Vec3 {
        let Some(ggx) = self.ggx else { return Vec3::ZERO };
        let (t, b) = basis(n);
        let local = |w: Vec3| Vec3::new(w.dot(t), w.dot(b), w.dot(n));
        let (o, i) = (local(wo), local(wi));
        let density = ggx.reflection(o, i, 1.0);
        if density == 0.0 {
            return Vec3::ZERO;
        }
        self.tint(o.dot((o + i).normalize()), band, lambda_nm, bands) * density
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn schlicks_fresnel_is_f0_head_on_and_one_at_grazing() {
        let gold = MetalOptics::new(Vec3::new(1.0, 0.78, 0.34), 0.0);
        assert_eq!(gold.fresnel(1.0), gold.f0);
        assert_eq!(gold.fresnel(0.0), Vec3::ONE);
        assert!(gold.ggx.is_none() && gold.is_chromatic());
        assert!(!MetalOptics::new(Vec3::splat(0.9), 0.5).is_chromatic());
        assert_eq!(MetalOptics::new(Vec3::splat(0.9), 0.5).ggx, Some(Ggx { alpha: 0.25 }));
    }
}
