//! A metal's reflection, ready for tracing: its Fresnel and the GGX
//! distribution of its facets ([`crate::optics::microfacet`]; none on a
//! polished metal). An RGB metal (glTF's) reflects with Schlick's Fresnel
//! from its reflectance at normal incidence per RGB channel, taken per
//! wavelength by that colour's reflectance spectrum as a diffuse albedo
//! is ([`crate::model::bands::BandTable::reflectance`]); a measured metal
//! with the exact Fresnel of its complex index at the path's wavelength
//! ([`conductor_fresnel`], [`crate::model::metals`]), and a white view path
//! sees the bands' mean. A film on a metal replaces its Fresnel by the
//! film's Airy sum over the metal ([`crate::optics::thin_film`]); a colour
//! texture scales F0 where a ray meets it
//! ([`crate::plan::prepared::PreparedScene::metal_at`]). Where the ray
//! goes is [`crate::optics::scatter::scatter_metal`]'s.
//!
//! A metalness m below 1 (glTF's, [`Metalness`]) blends the metal with a
//! diffuse surface of albedo F0 (the base colour), optionally under a
//! dielectric's specular layer ([`SpecularLayer`]: glTF's non-metals).
//! Both reflections share the facets, so they are one specular part of
//! Fresnel m F_metal + (1 − m) F_layer ([`MetalOptics::specular_tint`]),
//! and the diffuse part reflects the share (1 − m)(1 − max F_layer) of
//! what it is seen by ([`Metalness::diffuse_share`]; under a film on the
//! layer, the film's F_layer: [`filmed_layer_tint`]). A photon is
//! stored on it as on a diffuse surface (its flux is the light arriving,
//! whatever the surface does with it) and goes on reflected with the
//! probability m + (1 − m) F90 ([`MetalOptics::specular_share`],
//! [`crate::util::rng::dim::metal_part`]), then survives by the specular
//! part's Fresnel over that share ([`MetalOptics::specular_reflectance`]):
//! together, by the specular part's Fresnel. The camera sees the diffuse
//! part's light and caustic weighted by its share and the specular
//! part's reflection by its Fresnel. m and the layer are the ones at the
//! point met ([`crate::plan::prepared::PreparedScene::metal_at`] sets them:
//! a metalness map and specular maps vary them).

use crate::geometry::primitive::basis;
use crate::model::bands::BandTable;
use crate::model::metalness::{Metalness, SpecularLayer};
use crate::model::metals::{MetalColor, NamedMetal};
use crate::model::photon::WHITE_BAND;
use crate::model::scene::ThinFilm;
use crate::optics::microfacet::{Ggx, conductor_fresnel};
use crate::util::math::sqrt;
use glam::Vec3;

/// The most an RGB metal's F0 is taken as under a film: its index
/// (1 + √F0)/(1 − √F0) stays finite (about 4·10⁴).
pub const MAX_FILMED_F0: f32 = 0.9999;

/// A metal's optics.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MetalOptics {
    /// Reflectance at normal incidence per linear RGB channel (a measured
    /// metal's: the colour of its spectrum, [`NamedMetal::color`]).
    pub f0: Vec3,
    /// The measured metal whose optical constants give its Fresnel; `None`:
    /// Schlick's from `f0`.
    pub measured: Option<NamedMetal>,
    /// The facets' normal distribution; `None`: polished (roughness 0).
    pub ggx: Option<Ggx>,
    /// Its material's colour texture scales `f0` where a ray meets it
    /// ([`crate::plan::prepared::PreparedScene::metal_at`], whose optics
    /// at a point have `f0` scaled and this unset).
    pub textured: bool,
    /// Its material's specular colour map colours its layer where a ray
    /// meets it ([`crate::plan::prepared::PreparedScene::metal_at`], whose
    /// optics at a point have the layer there and this unset).
    pub layer_textured: bool,
    /// The film on its surface (`None`: bare; a film of no thickness is none).
    pub film: Option<ThinFilm>,
    /// How much of it is metal; the rest is diffuse of albedo `f0`.
    pub metalness: Metalness,
}

impl MetalOptics {
    /// The optics of a metal of colour `color` and glTF roughness `roughness`.
    pub fn new(color: MetalColor, roughness: f32) -> Self {
        let measured = match color {
            MetalColor::Measured(m) => Some(m),
            MetalColor::Rgb(_) => None,
        };
        MetalOptics {
            f0: color.rgb(),
            measured,
            ggx: (roughness > 0.0).then(|| Ggx::from_roughness(roughness)),
            textured: false,
            layer_textured: false,
            film: None,
            metalness: Metalness::WHOLE,
        }
    }

    /// Some of it is diffuse: photons are stored on it and the camera
    /// sees a diffuse part ([`Metalness::is_whole`] is false).
    #[inline]
    pub fn is_blended(&self) -> bool {
        !self.metalness.is_whole()
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

    /// True when its wavelengths reflect differently (F0 is not grey, or
    /// a texture may colour it, or its specular layer is coloured or a
    /// texture may colour it): a
    /// white photon splits here into its bands or hero wavelengths, or
    /// goes on as one band ([`crate::photons::trace`]). The metal's colour
    /// counts only where some of it is metal.
    #[inline]
    pub fn is_chromatic(&self) -> bool {
        let metal = self.measured.is_some()
            || self.textured
            || self.film.is_some()
            || self.f0.x != self.f0.y
            || self.f0.y != self.f0.z;
        let some_metal = self.metalness.factor > 0.0;
        let layer = self
            .metalness
            .layer
            .is_some_and(|l| l.f0.x != l.f0.y || l.f0.y != l.f0.z || self.film.is_some() || self.layer_textured);
        (metal && some_metal) || (layer && self.is_blended())
    }

    /// What its layer `l`'s facet met at cosine `cos` keeps of each RGB
    /// channel of a view path of band `band` at `lambda_nm`: Schlick's, or
    /// under a film its Airy sum at the path's wavelength (a white path:
    /// Σ C_b F(λ_b) over the bands).
    #[inline]
    fn layer_tint(&self, l: SpecularLayer, cos: f32, band: u16, lambda_nm: f32, bands: &BandTable) -> Vec3 {
        match self.film {
            Some(film) => filmed_layer_tint(l, film, cos, band, lambda_nm, bands),
            None => bands.reflectance(l.fresnel(cos), band, lambda_nm),
        }
    }

    /// The share of a photon path's flux (band `band` at `lambda_nm`)
    /// that its layer `l`'s facet met at cosine `cos` reflects.
    #[inline]
    fn layer_reflectance(&self, l: SpecularLayer, cos: f32, band: u16, lambda_nm: f32, bands: &BandTable) -> f32 {
        match self.film {
            Some(film) if band != WHITE_BAND => layer_filmed(l, film, cos, lambda_nm),
            Some(_) => bands.bounce_reflectance(self.layer_tint(l, cos, band, lambda_nm, bands), band, lambda_nm),
            None => bands.bounce_reflectance(l.fresnel(cos), band, lambda_nm),
        }
    }

    /// Its metalness m at the point whose optics these are.
    #[inline]
    fn m(&self) -> f32 {
        self.metalness.factor
    }

    /// [`Metalness::specular_share`] at the point whose optics these are.
    #[inline]
    pub fn specular_share(&self) -> f32 {
        self.metalness.specular_share()
    }

    /// What the specular part's facet met at cosine `cos` keeps of each
    /// RGB channel of a view path of band `band` at `lambda_nm`: m F_metal
    /// + (1 − m) F_layer ([`MetalOptics::tint`] for a whole metal).
    #[inline]
    pub fn specular_tint(&self, cos: f32, band: u16, lambda_nm: f32, bands: &BandTable) -> Vec3 {
        let m = self.m();
        let metal = if m > 0.0 { self.tint(cos, band, lambda_nm, bands) * m } else { Vec3::ZERO };
        match self.metalness.layer {
            Some(l) => metal + self.layer_tint(l, cos, band, lambda_nm, bands) * (1.0 - m),
            None => metal,
        }
    }

    /// The share of a photon path's flux (band `band` at `lambda_nm`),
    /// gone on with [`MetalOptics::specular_share`]'s probability, that
    /// a facet met at cosine `cos` reflects: its survival probability,
    /// (m R_metal + (1 − m) R_layer) / (m + (1 − m) F90), at most 1
    /// ([`MetalOptics::reflectance`] for a metal without a layer).
    #[inline]
    pub fn specular_reflectance(&self, cos: f32, band: u16, lambda_nm: f32, bands: &BandTable) -> f32 {
        let m = self.m();
        let metal = if m > 0.0 { self.reflectance(cos, band, lambda_nm, bands) } else { 0.0 };
        match self.metalness.layer {
            Some(l) => {
                let layer = self.layer_reflectance(l, cos, band, lambda_nm, bands);
                (m * metal + (1.0 - m) * layer) / self.specular_share()
            }
            None => metal,
        }
    }

    /// What a facet met at cosine `cos` reflects of a path of band `band`
    /// at `lambda_nm` through `film`: the film's Airy sum over the metal,
    /// a measured metal's complex index at that wavelength, or for an RGB
    /// metal the real index (1 + √F0)/(1 − √F0) whose Fresnel is its F0 at
    /// that wavelength head on (as `KHR_materials_iridescence` reads a
    /// metal's base colour).
    #[inline]
    fn filmed(&self, film: ThinFilm, cos: f32, band: u16, lambda_nm: f32, bands: &BandTable) -> f32 {
        let base = match self.measured {
            Some(metal) => metal.optical_constants(lambda_nm),
            None => {
                let r = sqrt(bands.bounce_reflectance(self.f0, band, lambda_nm).min(MAX_FILMED_F0));
                ((1.0 + r) / (1.0 - r), 0.0)
            }
        };
        film.reflectance_on(cos, 1.0, base, lambda_nm)
    }

    /// The share of a photon path's flux (band `band` at `lambda_nm`)
    /// that a facet met at cosine `cos` reflects: its survival probability.
    #[inline]
    pub fn reflectance(&self, cos: f32, band: u16, lambda_nm: f32, bands: &BandTable) -> f32 {
        match (self.film, self.measured) {
            (Some(film), _) if band != WHITE_BAND => self.filmed(film, cos, band, lambda_nm, bands),
            (None, None) => bands.bounce_reflectance(self.fresnel(cos), band, lambda_nm),
            (None, Some(metal)) if band != WHITE_BAND => measured_fresnel(metal, cos, lambda_nm),
            // White light (a view path's; a photon splits first): the bands' mean.
            _ => bands.bounce_reflectance(self.tint(cos, band, lambda_nm, bands), band, lambda_nm),
        }
    }

    /// What a facet met at cosine `cos` keeps of each RGB channel of a
    /// view path of band `band` at `lambda_nm` (a white path: Fresnel per
    /// channel; of a measured or filmed metal, Σ C_b F(λ_b) over the
    /// bands, whose weights C_b sum to white).
    #[inline]
    pub fn tint(&self, cos: f32, band: u16, lambda_nm: f32, bands: &BandTable) -> Vec3 {
        if let Some(film) = self.film {
            return match band {
                WHITE_BAND => (bands.bands().iter().enumerate())
                    .map(|(b, info)| info.weight * self.filmed(film, cos, b as u16, info.lambda_nm, bands))
                    .sum(),
                _ => Vec3::splat(self.filmed(film, cos, band, lambda_nm, bands)),
            };
        }
        match self.measured {
            None => bands.reflectance(self.fresnel(cos), band, lambda_nm),
            Some(metal) if band == WHITE_BAND => {
                bands.bands().iter().map(|b| b.weight * measured_fresnel(metal, cos, b.lambda_nm)).sum()
            }
            Some(metal) => Vec3::splat(measured_fresnel(metal, cos, lambda_nm)),
        }
    }

    /// The share of a photon path's flux (band `band` at `lambda_nm`),
    /// gone on with [`MetalOptics::specular_share`]'s probability, that
    /// the specular layer's facet met at cosine `cos` passes to the
    /// diffuse base below: (1 − m)(F90 − R_layer) / (m + (1 − m) F90), so
    /// that the base takes (1 − m)(1 − R_layer) in all; 0 without a layer.
    #[inline]
    pub fn layer_passes(&self, cos: f32, band: u16, lambda_nm: f32, bands: &BandTable) -> f32 {
        let Some(l) = self.metalness.layer else { return 0.0 };
        let layer = self.layer_reflectance(l, cos, band, lambda_nm, bands);
        ((1.0 - self.m()) * (l.f90 - layer) / self.specular_share()).max(0.0)
    }

    /// The specular part's BRDF D G2 F / (4 cos θo cos θi) per RGB
    /// channel of a view path of band `band` at `lambda_nm`, F its
    /// [`MetalOptics::specular_tint`], from `wi` toward `wo` about the
    /// normal `n` (unit vectors; zero unless both are above it, and for a
    /// polished surface, whose reflection is a direction, not a density).
    pub fn reflection(&self, wo: Vec3, wi: Vec3, n: Vec3, band: u16, lambda_nm: f32, bands: &BandTable) -> Vec3 {
        let Some(ggx) = self.ggx else { return Vec3::ZERO };
        let (t, b) = basis(n);
        let local = |w: Vec3| Vec3::new(w.dot(t), w.dot(b), w.dot(n));
        let (o, i) = (local(wo), local(wi));
        let density = ggx.reflection(o, i, 1.0);
        if density == 0.0 {
            return Vec3::ZERO;
        }
        self.specular_tint(o.dot((o + i).normalize()), band, lambda_nm, bands) * density
    }
}

/// What the specular layer `layer` under `film`, its facet met at cosine
/// `cos`, keeps of each RGB channel of a view path of band `band` at
/// `lambda_nm`: the film's Airy sum at the path's wavelength (a white
/// path: Σ C_b F(λ_b) over the bands).
#[inline]
pub fn filmed_layer_tint(
    layer: SpecularLayer,
    film: ThinFilm,
    cos: f32,
    band: u16,
    lambda_nm: f32,
    bands: &BandTable,
) -> Vec3 {
    match band {
        WHITE_BAND => bands.bands().iter().map(|b| b.weight * layer_filmed(layer, film, cos, b.lambda_nm)).sum(),
        _ => Vec3::splat(layer_filmed(layer, film, cos, lambda_nm)),
    }
}

/// The reflectance of the specular layer `layer` under `film` for light
/// meeting a facet at cosine `cos`, at `lambda_nm`: F90 times the film's
/// Airy sum over the base's index (glTF's iridescence replaces the
/// dielectric's Fresnel, its colour included).
#[inline]
fn layer_filmed(layer: SpecularLayer, film: ThinFilm, cos: f32, lambda_nm: f32) -> f32 {
    layer.f90 * film.reflectance_on(cos, 1.0, (layer.ior, 0.0), lambda_nm)
}

/// The Fresnel reflectance of measured `metal` at `lambda_nm` for light
/// meeting a facet at cosine `cos`.
#[inline]
pub fn measured_fresnel(metal: NamedMetal, cos: f32, lambda_nm: f32) -> f32 {
    let (n, k) = metal.optical_constants(lambda_nm);
    conductor_fresnel(cos, n, k)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn schlicks_fresnel_is_f0_head_on_and_one_at_grazing() {
        let gold = MetalOptics::new(MetalColor::Rgb(Vec3::new(1.0, 0.78, 0.34)), 0.0);
        assert_eq!(gold.fresnel(1.0), gold.f0);
        assert_eq!(gold.fresnel(0.0), Vec3::ONE);
        assert!(gold.ggx.is_none() && gold.is_chromatic());
        let grey = MetalOptics::new(MetalColor::Rgb(Vec3::splat(0.9)), 0.5);
        assert!(!grey.is_chromatic());
        assert_eq!(grey.ggx, Some(Ggx { alpha: 0.25 }));
    }

    /// A grey layer is white light's alike, unless a colour map may tint
    /// it (its optics at a point have the layer there, and so are grey again).
    #[test]
    fn a_layer_a_colour_map_tints_splits_white_light() {
        let layer = SpecularLayer::gltf(1.5, 1.0, Vec3::ONE);
        let plastic = MetalOptics {
            metalness: Metalness { layer, ..Metalness::plain(0.0) },
            ..MetalOptics::new(MetalColor::Rgb(Vec3::splat(0.5)), 0.3)
        };
        assert!(!plastic.is_chromatic());
        assert!(MetalOptics { layer_textured: true, ..plastic }.is_chromatic());
    }

    #[test]
    fn a_measured_metal_reflects_each_wavelength_by_its_own_index() {
        let bands = BandTable::new(crate::model::bands::BandSpec::Physical(16));
        let gold = MetalOptics::new(MetalColor::Measured(NamedMetal::Gold), 0.0);
        assert!(gold.is_chromatic() && gold.f0 == NamedMetal::Gold.color());
        for lambda in [400.0f32, 450.0, 500.0, 550.0, 600.0, 650.0, 700.0] {
            // Head on, the closed form ((n − 1)² + k²)/((n + 1)² + k²).
            let head_on = gold.reflectance(1.0, 3, lambda, &bands);
            assert!((head_on - NamedMetal::Gold.normal_reflectance(lambda)).abs() < 1e-5, "{lambda}: {head_on}");
            // Grazing, everything; and a band path's tint is its one number.
            assert!((gold.reflectance(0.0, 3, lambda, &bands) - 1.0).abs() < 1e-6);
            assert_eq!(gold.tint(0.5, 3, lambda, &bands), Vec3::splat(gold.reflectance(0.5, 3, lambda, &bands)));
        }
        // Gold reflects red far better than blue.
        assert!(gold.reflectance(1.0, 0, 650.0, &bands) > 2.0 * gold.reflectance(1.0, 0, 450.0, &bands));
        // A white path sees the bands' mean: gold's colour head on.
        let white = gold.tint(1.0, WHITE_BAND, 0.0, &bands);
        assert!((white - gold.f0).abs().max_element() < 0.02, "{white} vs {}", gold.f0);
    }
}
