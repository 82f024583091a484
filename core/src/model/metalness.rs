//! How much of a metallic-roughness surface (glTF's, Bevy's
//! `StandardMaterial`) is metal, and the specular layer of the rest: glTF
//! blends a metal and a dielectric base of the same base colour by a
//! metalness, texel by texel, and the base is a diffuse surface under a
//! dielectric's specular reflection (`KHR_materials_ior`,
//! `KHR_materials_specular`). prismatic draws a metal with a metalness
//! below 1 as that blend at every hit ([`crate::optics::metal`]).

use glam::Vec3;

/// A metal's metalness: glTF's `metallicFactor`, times the blue channel of
/// its material's roughness map (glTF's `metallicRoughnessTexture`, read as
/// linear values: green scales the roughness, blue the metalness) where
/// `mapped`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Metalness {
    /// The factor, in [0, 1]: 1 is a whole metal.
    pub factor: f32,
    /// The factor is scaled texel by texel by the blue channel of the
    /// material's roughness map (which it must have).
    pub mapped: bool,
    /// The specular layer of the non-metal part (`None`: it is diffuse
    /// alone, as a scene file's blended metal is unless it names one).
    pub layer: Option<SpecularLayer>,
}

impl Metalness {
    /// A whole metal: metalness 1 everywhere.
    pub const WHOLE: Metalness = Metalness { factor: 1.0, mapped: false, layer: None };

    /// A surface of metalness `factor` everywhere, with no specular layer.
    pub const fn plain(factor: f32) -> Metalness {
        Metalness { factor, mapped: false, layer: None }
    }

    /// No metal at all: a diffuse base under the specular layer `layer`
    /// (glTF's non-metals).
    pub const fn layered(layer: SpecularLayer) -> Metalness {
        Metalness { factor: 0.0, mapped: false, layer: Some(layer) }
    }

    /// The metalness of factor `factor` (glTF's `metallicFactor`, Bevy's
    /// `metallic`) times the blue channel of the texels `texels` (glTF's
    /// `metallicRoughnessTexture`'s, r + 256 g + 65536 b) texel by texel,
    /// the factor alone without them; `None` where no texel is metal at all (a diffuse surface). A
    /// texture whose texels are all fully metallic is not kept (the factor
    /// alone says the same). One pass over the texels.
    pub fn of(factor: f32, texels: Option<&[u32]>) -> Option<Metalness> {
        let factor = factor.clamp(0.0, 1.0);
        let Some(texels) = texels else {
            return (factor > 0.0).then_some(Metalness::plain(factor));
        };
        let (mut any, mut all) = (false, true);
        for &x in texels {
            let blue = (x >> 16) & 255;
            any |= blue > 0;
            all &= blue == 255;
        }
        (factor > 0.0 && any).then_some(Metalness { factor, mapped: !all, layer: None })
    }

    /// This metalness with `layer` on its non-metal part (none on a whole
    /// metal, which has no such part).
    pub fn with_layer(self, layer: Option<SpecularLayer>) -> Metalness {
        Metalness { layer: layer.filter(|_| !self.is_whole()), ..self }
    }

    /// The share of a photon path stored on a point of this metalness m
    /// (its factor: the metalness at a point, [`crate::plan::prepared::PreparedScene::metalness_at`])
    /// that goes on reflected: m + (1 − m) F90, the most its specular part
    /// reflects (m without a layer; 1 where it is whole metal).
    #[inline]
    pub fn specular_share(&self) -> f32 {
        let m = self.factor;
        match self.layer {
            Some(l) => m + (1.0 - m) * l.f90,
            None => m,
        }
    }

    /// The share of the light the diffuse part of a point of this
    /// metalness m reflects toward a viewer at cosine `cos` to the normal:
    /// (1 − m) (1 − max F_layer(cos)) ([`SpecularLayer::diffuse_share`]).
    #[inline]
    pub fn diffuse_share(&self, cos: f32) -> f32 {
        (1.0 - self.factor) * self.layer.map_or(1.0, |l| l.diffuse_share(cos))
    }

    /// True where every point is metal (factor 1, no map).
    pub fn is_whole(&self) -> bool {
        self.factor >= 1.0 && !self.mapped
    }

    /// The metalness where the roughness map reads `blue` (its blue channel,
    /// linear; ignored unless `mapped`).
    #[inline]
    pub fn at(&self, blue: f32) -> f32 {
        if self.mapped { self.factor * blue } else { self.factor }
    }
}

/// The specular reflection of a dielectric base (glTF's non-metal part):
/// Schlick's Fresnel from `f0` head on to `f90` at grazing, the same GGX
/// facets as the metal's. glTF's `KHR_materials_specular` makes F0 =
/// min(F0(ior) · specularColorFactor, 1) · specularFactor and F90 =
/// specularFactor, where F0(ior) = ((n − 1)/(n + 1))² (`KHR_materials_ior`,
/// 0.04 at the default 1.5); what it does not reflect reaches the diffuse
/// base ([`SpecularLayer::diffuse_share`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpecularLayer {
    /// Reflectance at normal incidence per linear RGB channel, in [0, f90].
    pub f0: Vec3,
    /// Reflectance at grazing incidence, in [0, 1].
    pub f90: f32,
    /// The base's index of refraction, which a film on it sits on
    /// ([`crate::optics::metal`]).
    pub ior: f32,
}

impl SpecularLayer {
    /// glTF's layer of a base of index `ior`, `KHR_materials_specular`'s
    /// `specularFactor` `weight` and `specularColorFactor` `color`; `None`
    /// where it reflects nothing (weight 0; an index of 1 still reflects
    /// toward grazing, as glTF's Fresnel does).
    pub fn gltf(ior: f32, weight: f32, color: Vec3) -> Option<SpecularLayer> {
        let f0 = SpecularLayer::unclipped_f0(ior, color).min(Vec3::ONE) * weight;
        (weight > 0.0).then_some(SpecularLayer { f0, f90: weight, ior })
    }

    /// glTF's reflectance head on of a layer of index `ior` and colour
    /// `color` at weight 1, before it is clipped to 1: `color` ·
    /// ((n − 1)/(n + 1))².
    pub fn unclipped_f0(ior: f32, color: Vec3) -> Vec3 {
        let r = (ior - 1.0) / (ior + 1.0);
        color * (r * r)
    }

    /// Schlick's Fresnel per RGB channel for light meeting a facet at
    /// cosine `cos`: F0 + (F90 − F0)(1 − cos)⁵.
    #[inline]
    pub fn fresnel(&self, cos: f32) -> Vec3 {
        let x = 1.0 - cos.clamp(0.0, 1.0);
        let x2 = x * x;
        self.f0 + (Vec3::splat(self.f90) - self.f0) * (x2 * x2 * x)
    }

    /// The share of the light seen at cosine `cos` to the normal that the
    /// diffuse base below reflects: 1 − max F(cos), as glTF's `fresnel_mix`
    /// weighs it (with the view's angle to the normal for the half
    /// vector's, as glTF viewers do for image-based light).
    #[inline]
    pub fn diffuse_share(&self, cos: f32) -> f32 {
        1.0 - self.fresnel(cos).max_element()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use alloc::vec::Vec;

    /// Texels with these blue channels (metalness) and green 255.
    fn blue(channels: &[u32]) -> Vec<u32> {
        channels.iter().map(|&b| b << 16 | 255 << 8).collect()
    }

    #[test]
    fn a_surface_with_any_metal_is_a_metal_blended_by_its_metalness() {
        let plain = |factor| Some(Metalness::plain(factor));
        assert_eq!(Metalness::of(1.0, None), Some(Metalness::WHOLE));
        assert_eq!(Metalness::of(0.0, None), None);
        assert_eq!(Metalness::of(0.3, None), plain(0.3));
        assert_eq!(Metalness::of(1.5, None), Some(Metalness::WHOLE), "clamped");
        // A map of whole metal says nothing the factor does not.
        assert_eq!(Metalness::of(1.0, Some(&*blue(&[255, 255]))), Some(Metalness::WHOLE));
        assert_eq!(Metalness::of(0.4, Some(&*blue(&[255, 255]))), plain(0.4));
        assert_eq!(Metalness::of(1.0, Some(&*blue(&[0, 128]))), Some(Metalness { mapped: true, ..Metalness::WHOLE }));
        assert_eq!(Metalness::of(1.0, Some(&*blue(&[0, 0]))), None, "no texel is metal");
        assert_eq!(Metalness::of(0.0, Some(&*blue(&[255, 255]))), None);
        assert!(Metalness::WHOLE.is_whole() && !plain(0.3).unwrap().is_whole());
    }

    #[test]
    fn the_map_scales_the_factor_where_it_is_mapped() {
        let m = Metalness { mapped: true, ..Metalness::plain(0.5) };
        assert_eq!(m.at(0.5), 0.25);
        assert_eq!(Metalness { mapped: false, ..m }.at(0.5), 0.5);
    }
}

#[cfg(test)]
mod layer_tests {
    use super::*;

    #[test]
    fn gltfs_default_layer_reflects_four_percent_head_on_and_all_at_grazing() {
        let layer = SpecularLayer::gltf(1.5, 1.0, Vec3::ONE).unwrap();
        assert!((layer.f0 - Vec3::splat(0.04)).abs().max_element() < 1e-7, "{layer:?}");
        assert_eq!(layer.fresnel(1.0), layer.f0);
        assert_eq!(layer.fresnel(0.0), Vec3::ONE);
        assert!((layer.diffuse_share(1.0) - 0.96).abs() < 1e-6);
        assert_eq!(layer.diffuse_share(0.0), 0.0);
    }

    #[test]
    fn specular_factor_and_colour_scale_the_layer_as_khr_materials_specular_says() {
        // F0 = min(F0(ior) · colour, 1) · factor, F90 = factor.
        let layer = SpecularLayer::gltf(2.0, 0.5, Vec3::new(1.0, 20.0, 0.5)).unwrap();
        let f0 = 1.0 / 9.0;
        assert!((layer.f0 - Vec3::new(f0 * 0.5, 0.5, f0 * 0.25)).abs().max_element() < 1e-6, "{layer:?}");
        assert_eq!(layer.f90, 0.5);
        assert!((layer.diffuse_share(0.0) - 0.5).abs() < 1e-6, "half reaches the base at grazing");
        assert_eq!(SpecularLayer::gltf(1.5, 0.0, Vec3::ONE), None);
        assert_eq!(SpecularLayer::gltf(1.0, 1.0, Vec3::ONE).map(|l| l.fresnel(1.0)), Some(Vec3::ZERO));
    }
}
