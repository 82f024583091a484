//! Procedural images for the built-in glTF scenes: stone tiles for floors
//! and graph paper for walls (whose lines show what glass refracts).

use crate::gltf_write::GltfTexture;

/// glTF's code for repeat wrapping.
const REPEAT: u32 = 10497;

/// Pale stone tiles with dark joints, 2×2 tiles of 32 texels.
pub fn tiles() -> GltfTexture {
    let pixels = (0..64 * 64)
        .map(|i| {
            let (x, y) = (i % 64, i / 64);
            let joint = x % 32 < 2 || y % 32 < 2;
            // Alternate tiles a shade apart, as real stone varies.
            let shade = if (x / 32 + y / 32) % 2 == 0 { 0 } else { 14 };
            if joint { [96, 90, 84] } else { [226 - shade, 218 - shade, 200 - shade] }
        })
        .collect();
    GltfTexture { width: 64, height: 64, pixels, nearest: false, wrap: [REPEAT; 2] }
}

/// Blue-grey graph paper: lines every 16 texels.
pub fn graph_paper() -> GltfTexture {
    let pixels = (0..64 * 64)
        .map(|i| {
            let (x, y) = (i % 64, i / 64);
            if x % 16 == 0 || y % 16 == 0 { [40, 52, 82] } else { [150, 162, 186] }
        })
        .collect();
    GltfTexture { width: 64, height: 64, pixels, nearest: false, wrap: [REPEAT; 2] }
}
