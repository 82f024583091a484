//! Bevy's images as prismatic's textures, texel by texel with their
//! samplers, converted once per image and kept until Bevy says the image
//! changed.

use bevy::asset::{AssetEvent, AssetId};
use bevy::ecs::system::SystemParam;
use bevy::image::{Image, ImageAddressMode, ImageFilterMode, ImageSampler};
use bevy::prelude::*;
use prismatic_core::model::metalness::Metalness;
use prismatic_core::model::scene::{Filter, Sampler, Texture, Wrap};
use std::collections::HashMap;

/// How a texture's channels are read.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) enum Channels {
    /// A colour (a base colour): its sRGB-encoded bytes.
    Colour,
    /// Data (a normal or metallic-roughness map): its linear values.
    Linear,
    /// A normal map in DirectX's convention (`flip_normal_map_y`): linear
    /// values, green turned over to glTF's.
    LinearGreenFlipped,
}

/// The app's images as the mirror reads them.
#[derive(SystemParam)]
pub(crate) struct AppImages<'w, 's> {
    images: Res<'w, Assets<Image>>,
    events: MessageReader<'w, 's, AssetEvent<Image>>,
    converted: Local<'s, Textures>,
}

impl AppImages<'_, '_> {
    /// Forgets the textures of images Bevy changed since the last call.
    pub(crate) fn refresh(&mut self) {
        self.converted.forget(self.events.read());
    }

    /// The texture of `handle`'s image read as `channels` ([`Textures::get`]).
    pub(crate) fn texture(&mut self, handle: &Handle<Image>, channels: Channels) -> Result<Option<Texture>, String> {
        self.converted.get(&self.images, handle, channels)
    }

    /// [`Textures::metalness`].
    pub(crate) fn metalness(&mut self, handle: &Handle<Image>, factor: f32, texture: &Texture) -> Option<Metalness> {
        self.converted.metalness(handle, factor, texture)
    }
}

/// The textures converted so far, by image and channels, and the
/// metalness of metallic-roughness images, by image and factor.
#[derive(Default)]
pub(crate) struct Textures {
    converted: HashMap<(AssetId<Image>, Channels), Texture>,
    metalness: HashMap<(AssetId<Image>, u32), Option<Metalness>>,
}

impl Textures {
    /// Forgets the images Bevy modified or removed.
    pub(crate) fn forget<'a>(&mut self, events: impl Iterator<Item = &'a AssetEvent<Image>>) {
        for event in events {
            if let AssetEvent::Modified { id } | AssetEvent::Removed { id } | AssetEvent::Unused { id } = event {
                self.converted.retain(|(image, _), _| image != id);
                self.metalness.retain(|(image, _), _| image != id);
            }
        }
    }

    /// [`Metalness::of`] `factor` and `texture` (`handle`'s image read as
    /// linear values), counted once per image and factor, not each frame:
    /// a pass over every texel.
    pub(crate) fn metalness(&mut self, handle: &Handle<Image>, factor: f32, texture: &Texture) -> Option<Metalness> {
        *self
            .metalness
            .entry((handle.id(), factor.to_bits()))
            .or_insert_with(|| Metalness::of(factor, Some(&texture.texels)))
    }

    /// The texture of `handle`'s image read as `channels`; `Ok(None)` while
    /// it is loading; an error says why the plugin cannot read it.
    pub(crate) fn get(
        &mut self,
        images: &Assets<Image>,
        handle: &Handle<Image>,
        channels: Channels,
    ) -> Result<Option<Texture>, String> {
        let key = (handle.id(), channels);
        if let Some(texture) = self.converted.get(&key) {
            return Ok(Some(texture.clone()));
        }
        let Some(image) = images.get(handle) else { return Ok(None) };
        let name = handle.path().map_or_else(|| format!("image {:?}", handle.id()), |p| p.to_string());
        let texture = texture(image, name, channels)?;
        self.converted.insert(key, texture.clone());
        Ok(Some(texture))
    }
}

/// `image` as a prismatic texture: 8 bits a channel, packed `r | g << 8 |
/// b << 16`, rows from the top (as Bevy's and glTF's v runs).
pub(crate) fn texture(image: &Image, name: String, channels: Channels) -> Result<Texture, String> {
    if image.data.is_none() {
        return Err(format!("{name}: its texels are in the render world only (RenderAssetUsages::RENDER_WORLD)"));
    }
    let (width, height) = (image.width(), image.height());
    let byte = |x: f32| (x.clamp(0.0, 1.0) * 255.0).round() as u32;
    let mut texels = Vec::with_capacity(width as usize * height as usize);
    for y in 0..height {
        for x in 0..width {
            let color = image
                .get_color_at(x, y)
                .map_err(|e| format!("{name}: cannot read its {:?} texels: {e}", image.texture_descriptor.format))?;
            let [r, g, b] = match channels {
                Channels::Colour => {
                    let c = color.to_srgba();
                    [c.red, c.green, c.blue]
                }
                Channels::Linear => {
                    let c = color.to_linear();
                    [c.red, c.green, c.blue]
                }
                Channels::LinearGreenFlipped => {
                    let c = color.to_linear();
                    [c.red, 1.0 - c.green, c.blue]
                }
            };
            texels.push(byte(r) | byte(g) << 8 | byte(b) << 16);
        }
    }
    Ok(Texture { name, width, height, texels: texels.into(), sampler: sampler(&image.sampler) })
}

/// Bevy's sampler as prismatic's. The default one is `ImagePlugin`'s
/// default: linear, clamped to the edge (as `ImageSamplerDescriptor`'s).
fn sampler(sampler: &ImageSampler) -> Sampler {
    let ImageSampler::Descriptor(d) = sampler else {
        return Sampler { filter: Filter::Linear, wrap_u: Wrap::ClampToEdge, wrap_v: Wrap::ClampToEdge };
    };
    let wrap = |mode| match mode {
        ImageAddressMode::Repeat => Wrap::Repeat,
        ImageAddressMode::MirrorRepeat => Wrap::MirroredRepeat,
        // A border colour is not a texel prismatic has: the edge's is nearest.
        ImageAddressMode::ClampToEdge | ImageAddressMode::ClampToBorder => Wrap::ClampToEdge,
    };
    let filter = match d.mag_filter {
        ImageFilterMode::Nearest => Filter::Nearest,
        ImageFilterMode::Linear => Filter::Linear,
    };
    Sampler { filter, wrap_u: wrap(d.address_mode_u), wrap_v: wrap(d.address_mode_v) }
}

#[cfg(test)]
mod tests {
    use super::*;
    use bevy::asset::RenderAssetUsages;
    use bevy::image::ImageSamplerDescriptor;
    use bevy::render::render_resource::{Extent3d, TextureDimension, TextureFormat};

    fn image(format: TextureFormat, texels: &[[u8; 4]]) -> Image {
        let size = Extent3d { width: texels.len() as u32, height: 1, depth_or_array_layers: 1 };
        let data = texels.concat();
        Image::new(size, TextureDimension::D2, data, format, RenderAssetUsages::MAIN_WORLD)
    }

    #[test]
    fn colours_keep_their_srgb_bytes_and_data_its_linear_values() {
        let texels = [[10, 128, 250, 255], [0, 255, 64, 255]];
        let packed = |[r, g, b, _]: [u8; 4]| u32::from(r) | u32::from(g) << 8 | u32::from(b) << 16;
        let srgb = image(TextureFormat::Rgba8UnormSrgb, &texels);
        let colour = texture(&srgb, "base".into(), Channels::Colour).unwrap();
        assert_eq!(&*colour.texels, &texels.map(packed));
        let linear = image(TextureFormat::Rgba8Unorm, &texels);
        let data = texture(&linear, "mr".into(), Channels::Linear).unwrap();
        assert_eq!(&*data.texels, &texels.map(packed));
        let flipped = texture(&linear, "normal".into(), Channels::LinearGreenFlipped).unwrap();
        assert_eq!(&*flipped.texels, &[[10, 127, 250, 255], [0, 0, 64, 255]].map(packed));
        // A linear image read as a colour is encoded: 128/255 linear is sRGB 188.
        let encoded = texture(&linear, "base".into(), Channels::Colour).unwrap();
        assert_eq!((encoded.texels[0] >> 8) & 255, 188);
    }

    #[test]
    fn samplers_follow_bevys() {
        let mut img = image(TextureFormat::Rgba8Unorm, &[[0; 4]]);
        let plain = texture(&img, "a".into(), Channels::Linear).unwrap().sampler;
        assert_eq!(plain, Sampler { filter: Filter::Linear, wrap_u: Wrap::ClampToEdge, wrap_v: Wrap::ClampToEdge });
        img.sampler = ImageSampler::Descriptor(ImageSamplerDescriptor {
            address_mode_u: ImageAddressMode::Repeat,
            address_mode_v: ImageAddressMode::MirrorRepeat,
            mag_filter: ImageFilterMode::Nearest,
            ..default()
        });
        let own = texture(&img, "a".into(), Channels::Linear).unwrap().sampler;
        assert_eq!(own, Sampler { filter: Filter::Nearest, wrap_u: Wrap::Repeat, wrap_v: Wrap::MirroredRepeat });
    }

    #[test]
    fn an_image_is_read_once_and_again_when_bevy_changes_it() {
        let mut images = Assets::<Image>::default();
        let handle = images.add(image(TextureFormat::Rgba8Unorm, &[[1, 2, 255, 255]]));
        let mut textures = Textures::default();
        let first = textures.get(&images, &handle, Channels::Linear).unwrap().unwrap();
        assert_eq!(textures.metalness(&handle, 1.0, &first), Some(Metalness::WHOLE));
        images.get_mut(&handle).unwrap().data = Some(vec![9, 9, 0, 255]);
        let cached = textures.get(&images, &handle, Channels::Linear).unwrap().unwrap();
        assert_eq!(cached.texels, first.texels, "not read again before Bevy says it changed");
        textures.forget([AssetEvent::Modified { id: handle.id() }].iter());
        let again = textures.get(&images, &handle, Channels::Linear).unwrap().unwrap();
        assert_eq!(&*again.texels, &[9 | 9 << 8]);
        assert_eq!(textures.metalness(&handle, 1.0, &again), None, "no metal left");
    }

    #[test]
    fn unreadable_images_say_why() {
        let mut img = image(TextureFormat::Rgba8Unorm, &[[0; 4]]);
        img.data = None;
        let e = texture(&img, "floor.ktx2".into(), Channels::Colour).unwrap_err();
        assert!(e.contains("floor.ktx2") && e.contains("render world only"), "{e}");
    }
}
