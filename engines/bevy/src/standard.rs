//! A `StandardMaterial` (a [`crate::CausticMaterial`]'s base) as a
//! prismatic material: diffuse in its base colour and base colour texture
//! under its specular layer (`reflectance`, `specular_tint`), or a metal in
//! its base colour blended with that base by its metalness ([`Metalness`]:
//! `metallic` times its metallic-roughness texture's blue channel), its
//! roughness scaled by that texture's green channel,
//! its normals tilted by its normal map. What prismatic cannot draw of it
//! is named, as the glTF loader names what it leaves out.

use crate::images::{AppImages, Channels};
use bevy::math::Affine2;
use bevy::mesh::UvChannel;
use bevy::prelude::*;
use prismatic_core::model::metalness::{Metalness, SpecularLayer};
use prismatic_core::model::scene::{Material, MaterialKind, NormalMap, Texture};
use prismatic_core::{MetalColor, Vec3 as CoreVec3};

/// A material as the mirror draws it.
pub(crate) struct Drawn {
    /// The prismatic material.
    pub material: Material,
    /// Where it reads a texture: the transform of the mesh's `UV_0` into
    /// its textures' coordinates (`uv_transform`); `None`: it reads none.
    pub uv_transform: Option<Affine2>,
}

impl Drawn {
    /// The material without its textures (its mesh has no texture coordinates).
    pub(crate) fn untextured(self) -> Material {
        let mut material = self.material;
        match &mut material.kind {
            MaterialKind::Diffuse { texture, .. } => *texture = None,
            MaterialKind::Metal { texture, metalness, .. } => {
                // Without its map the metalness is its factor's.
                (*texture, metalness.mapped) = (None, false);
            }
            _ => {}
        }
        (material.normal_map, material.roughness_map) = (None, None);
        material
    }
}

/// The textures a material named `name` reads; what of them is left out
/// is added to `left_out`.
struct Maps<'a, 'w, 's> {
    name: &'a str,
    images: &'a mut AppImages<'w, 's>,
    left_out: &'a mut Vec<String>,
}

impl Maps<'_, '_, '_> {
    /// The material's map `what` read as `channels` (`None`: it has none,
    /// it is loading, or it is left out).
    fn read(
        &mut self,
        what: &str,
        handle: &Option<Handle<Image>>,
        uv: &UvChannel,
        channels: Channels,
    ) -> Option<Texture> {
        let handle = handle.as_ref()?;
        if *uv != UvChannel::Uv0 {
            self.left_out.push(format!("{}: {what} reads UV_1 (prismatic reads UV_0 only)", self.name));
            return None;
        }
        self.images.texture(handle, channels).unwrap_or_else(|e| {
            self.left_out.push(format!("{}: {what}: {e}", self.name));
            None
        })
    }

    /// `m`'s normal map (in glTF's convention, whichever `m` is in).
    fn normal_map(&mut self, m: &StandardMaterial) -> Option<NormalMap> {
        let channels = if m.flip_normal_map_y { Channels::LinearGreenFlipped } else { Channels::Linear };
        let texture = self.read("normal_map_texture", &m.normal_map_texture, &m.normal_map_channel, channels)?;
        Some(NormalMap { texture, scale: 1.0 })
    }
}

/// The normal map of `m`, the material Bevy draws a [`crate::Glass`] mesh
/// named `name` with (its ripples are the glass's), and the transform of
/// the mesh's `UV_0` into it; what is left out is added to `left_out`.
pub(crate) fn glass_normal_map(
    m: &StandardMaterial,
    name: &str,
    images: &mut AppImages,
    left_out: &mut Vec<String>,
) -> Option<(NormalMap, Affine2)> {
    let map = Maps { name, images, left_out }.normal_map(m)?;
    Some((map, m.uv_transform))
}

/// The specular layer of `m`'s dielectric base: F0 = 0.16 · reflectance²
/// times `specular_tint` (Bevy's mapping: its default reflectance of 0.5 is
/// glTF's 0.04), F90 1, over a base of index `ior` (where a film sits);
/// `None` at reflectance 0.
fn specular_layer(m: &StandardMaterial) -> Option<SpecularLayer> {
    let t = m.specular_tint.to_linear();
    let f0 = CoreVec3::new(t.red, t.green, t.blue) * (0.16 * m.reflectance * m.reflectance);
    let f0 = f0.clamp(CoreVec3::ZERO, CoreVec3::ONE);
    (m.reflectance > 0.0).then_some(SpecularLayer { f0, f90: 1.0, ior: m.ior })
}

/// `m` as a prismatic material named `name`; what of it is left out is
/// added to `left_out`.
pub(crate) fn drawn(m: &StandardMaterial, name: String, images: &mut AppImages, left_out: &mut Vec<String>) -> Drawn {
    let mut maps = Maps { name: &name, images, left_out };
    let normal_map = maps.normal_map(m);
    let metallic_roughness = maps.read(
        "metallic_roughness_texture",
        &m.metallic_roughness_texture,
        &m.metallic_roughness_channel,
        Channels::Linear,
    );
    let base_colour_texture =
        maps.read("base_color_texture", &m.base_color_texture, &m.base_color_channel, Channels::Colour);
    let metal = match (&m.metallic_roughness_texture, &metallic_roughness) {
        (Some(handle), Some(texture)) => maps.images.metalness(handle, m.metallic, texture),
        _ => Metalness::of(m.metallic, None),
    };
    let layer = specular_layer(m);
    let metalness = metal.map(|metal| metal.with_layer(layer)).or_else(|| layer.map(Metalness::layered));
    let c = m.base_color.to_linear();
    let color = CoreVec3::new(c.red, c.green, c.blue);
    let (kind, roughness_map) = match metalness {
        // Its base colour (times its texture) is its reflectance at normal
        // incidence and its diffuse part's albedo.
        Some(metalness) => {
            let kind = MaterialKind::Metal {
                color: MetalColor::Rgb(color.clamp(CoreVec3::ZERO, CoreVec3::ONE)),
                roughness: m.perceptual_roughness.clamp(0.0, 1.0),
                texture: base_colour_texture,
                film: None,
                metalness,
            };
            (kind, metallic_roughness)
        }
        None => {
            let diffuse = MaterialKind::Diffuse {
                albedo: color,
                checker: None,
                texture: base_colour_texture,
                emission: CoreVec3::ZERO,
            };
            (diffuse, None)
        }
    };
    let material = Material { normal_map, roughness_map, ..Material::new(name, kind) };
    let reads_texture = material.normal_map.is_some()
        || material.roughness_map.is_some()
        || matches!(
            material.kind,
            MaterialKind::Diffuse { texture: Some(_), .. } | MaterialKind::Metal { texture: Some(_), .. }
        );
    Drawn { material, uv_transform: reads_texture.then_some(m.uv_transform) }
}
