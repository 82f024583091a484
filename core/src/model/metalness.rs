//! How much of a metallic-roughness surface (glTF's, Bevy's
//! `StandardMaterial`) is metal: glTF blends a metal and a dielectric base
//! of the same base colour by a metalness, texel by texel. prismatic draws
//! a metal with a metalness below 1 as that blend at every hit: the metal
//! reflects its share and the rest is diffuse of the metal's colour (the
//! base's specular layer is not drawn).

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
}

impl Metalness {
    /// A whole metal: metalness 1 everywhere.
    pub const WHOLE: Metalness = Metalness { factor: 1.0, mapped: false };

    /// The metalness of factor `factor` (glTF's `metallicFactor`, Bevy's
    /// `metallic`) times the blue channel of the texels `texels` (glTF's
    /// `metallicRoughnessTexture`'s, r + 256 g + 65536 b) texel by texel,
    /// the factor alone without them; `None` where no texel is metal at all (a diffuse surface). A
    /// texture whose texels are all fully metallic is not kept (the factor
    /// alone says the same). One pass over the texels.
    pub fn of(factor: f32, texels: Option<&[u32]>) -> Option<Metalness> {
        let factor = factor.clamp(0.0, 1.0);
        let Some(texels) = texels else {
            return (factor > 0.0).then_some(Metalness { factor, mapped: false });
        };
        let (mut any, mut all) = (false, true);
        for &x in texels {
            let blue = (x >> 16) & 255;
            any |= blue > 0;
            all &= blue == 255;
        }
        (factor > 0.0 && any).then_some(Metalness { factor, mapped: !all })
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
        let plain = |factor| Some(Metalness { factor, mapped: false });
        assert_eq!(Metalness::of(1.0, None), Some(Metalness::WHOLE));
        assert_eq!(Metalness::of(0.0, None), None);
        assert_eq!(Metalness::of(0.3, None), plain(0.3));
        assert_eq!(Metalness::of(1.5, None), Some(Metalness::WHOLE), "clamped");
        // A map of whole metal says nothing the factor does not.
        assert_eq!(Metalness::of(1.0, Some(&*blue(&[255, 255]))), Some(Metalness::WHOLE));
        assert_eq!(Metalness::of(0.4, Some(&*blue(&[255, 255]))), plain(0.4));
        assert_eq!(Metalness::of(1.0, Some(&*blue(&[0, 128]))), Some(Metalness { factor: 1.0, mapped: true }));
        assert_eq!(Metalness::of(1.0, Some(&*blue(&[0, 0]))), None, "no texel is metal");
        assert_eq!(Metalness::of(0.0, Some(&*blue(&[255, 255]))), None);
        assert!(Metalness::WHOLE.is_whole() && !plain(0.3).unwrap().is_whole());
    }

    #[test]
    fn the_map_scales_the_factor_where_it_is_mapped() {
        let m = Metalness { factor: 0.5, mapped: true };
        assert_eq!(m.at(0.5), 0.25);
        assert_eq!(Metalness { mapped: false, ..m }.at(0.5), 0.5);
    }
}
