//! Textures from image files (PNG, JPEG) and from glTF's decoded images,
//! as the core's packed 8-bit texels: a base colour's sRGB-encoded, a
//! normal map's linear (the bytes as the file holds them either way).

use prismatic_core::model::scene::{Sampler, Texture};
use std::path::Path;
use std::sync::Arc;

/// Reads the image at `path`; the error names the file and why.
pub fn load(path: &Path, sampler: Sampler) -> Result<Texture, String> {
    let image = image::ImageReader::open(path)
        .and_then(|r| r.with_guessed_format())
        .map_err(|e| format!("cannot read texture {}: {e}", path.display()))?
        .decode()
        .map_err(|e| format!("cannot decode texture {}: {e}", path.display()))?
        .into_rgb8();
    let (width, height) = image.dimensions();
    Ok(from_rgb8(path.display().to_string(), width, height, image.pixels().map(|p| p.0), sampler))
}

/// A texture from 8-bit pixels, row by row from the top.
pub fn from_rgb8(
    name: String,
    width: u32,
    height: u32,
    pixels: impl Iterator<Item = [u8; 3]>,
    sampler: Sampler,
) -> Texture {
    let texels: Arc<[u32]> = pixels.map(|[r, g, b]| u32::from(r) | u32::from(g) << 8 | u32::from(b) << 16).collect();
    Texture { name, width, height, texels, sampler }
}
