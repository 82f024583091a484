//! Which opaque metallic-roughness material (glTF's, Bevy's
//! `StandardMaterial`) is drawn as a metal: glTF blends a metal and a
//! diffuse surface by a metalness, texel by texel; prismatic draws each
//! material as one or the other, as most of its surface is.

use crate::model::scene::Texture;

/// The metalness from which a surface is drawn as a metal.
pub const METAL_METALLIC: f32 = 0.5;

/// How a material's metalness is drawn, and what of it that leaves out.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Metalness {
    /// The metalness is [`METAL_METALLIC`] or more over most of the
    /// surface: the material is drawn as a metal, else diffuse.
    pub metal: bool,
    /// Some texels fall on the other side of [`METAL_METALLIC`] (drawn as
    /// the rest).
    pub varies: bool,
    /// Some texels (or the factor) lie strictly between 0 and 1: a blend
    /// of metal and diffuse, drawn as whichever it is closer to.
    pub partial: bool,
}

impl Metalness {
    /// The metalness `factor` (glTF's `metallicFactor`, Bevy's `metallic`)
    /// times the blue channel of `texture` (glTF's
    /// `metallicRoughnessTexture`, read as linear values) texel by texel;
    /// the factor alone without one. One pass over the texels.
    pub fn of(factor: f32, texture: Option<&Texture>) -> Metalness {
        let (mut count, mut metallic, mut partial) = (0usize, 0usize, false);
        let mut add = |m: f32| {
            count += 1;
            metallic += usize::from(m >= METAL_METALLIC);
            partial |= m > 0.0 && m < 1.0;
        };
        match texture {
            Some(t) => t.texels.iter().for_each(|&x| add(factor * ((x >> 16) & 255) as f32 / 255.0)),
            None => add(factor),
        }
        // Some texels on each side of the threshold: the minority is drawn as the rest.
        Metalness { metal: 2 * metallic >= count, varies: metallic != 0 && metallic != count, partial }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::scene::Sampler;
    use alloc::string::String;

    /// A row of texels with these blue channels (metalness) and green 255.
    fn blue(channels: &[u32]) -> Texture {
        Texture {
            name: String::from("metallic-roughness"),
            width: channels.len() as u32,
            height: 1,
            texels: channels.iter().map(|&b| b << 16 | 255 << 8).collect(),
            sampler: Sampler::default(),
        }
    }

    #[test]
    fn a_material_is_drawn_as_most_of_its_surface_is() {
        let whole = |metal| Metalness { metal, varies: false, partial: false };
        assert_eq!(Metalness::of(1.0, None), whole(true));
        assert_eq!(Metalness::of(0.0, None), whole(false));
        assert_eq!(Metalness::of(0.5, None), Metalness { metal: true, varies: false, partial: true });
        assert_eq!(Metalness::of(0.49, None), Metalness { metal: false, varies: false, partial: true });
        assert_eq!(Metalness::of(1.0, Some(&blue(&[255, 255, 255]))), whole(true));
        assert_eq!(
            Metalness::of(1.0, Some(&blue(&[255, 0, 255]))),
            Metalness { metal: true, varies: true, partial: false }
        );
        assert_eq!(
            Metalness::of(1.0, Some(&blue(&[0, 0, 255]))),
            Metalness { metal: false, varies: true, partial: false }
        );
        // Half and half: a metal (the threshold's side of a tie).
        assert_eq!(Metalness::of(1.0, Some(&blue(&[0, 255]))), Metalness { metal: true, varies: true, partial: false });
        // The factor scales every texel: 0.4 × 255 is diffuse, a blend.
        assert_eq!(
            Metalness::of(0.4, Some(&blue(&[255, 255]))),
            Metalness { metal: false, varies: false, partial: true }
        );
        assert_eq!(Metalness::of(0.0, Some(&blue(&[255, 255]))), whole(false));
    }
}
