//! An environment's radiance map: linear RGB radiance over every direction,
//! stored equirectangular (latitude–longitude), as HDR environments are
//! published; a constant one, and the built-in studio that lights a glTF
//! file which brings no light.

use alloc::string::String;
use alloc::sync::Arc;
use alloc::vec::Vec;
use core::f32::consts::PI;
use core::fmt;
use glam::Vec3;

/// The largest environment map side (8192 × 4096 texels of 12 bytes are
/// 400 MB: more than any environment a caustic needs).
pub const MAX_ENVIRONMENT_SIDE: u32 = 8_192;

/// Radiance in every direction, equirectangular: a direction d is at
/// u = 0.5 + atan2(d.x, −d.z)/2π across the image and v = acos(d.y)/π down
/// it (row 0 is the zenith), so the image's centre is what a camera looking
/// down −z sees, +x a quarter to its right and +z at both edges
/// ([`crate::sampling::environment`] reads it).
#[derive(Clone, PartialEq)]
pub struct EnvironmentMap {
    /// Where it came from (a file, `"studio"`), for messages.
    pub name: String,
    /// Texels per row.
    pub width: u32,
    /// Rows.
    pub height: u32,
    /// Linear RGB radiance, row by row from the zenith. Shared, so that
    /// cloning a scene does not copy the map.
    pub texels: Arc<[Vec3]>,
}

/// Its name, size and a hash of its texels (FNV-1a of their bits), not
/// the millions of texels themselves: a scene's fingerprint prints it.
impl fmt::Debug for EnvironmentMap {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let hash = self
            .texels
            .iter()
            .flat_map(|t| t.to_array())
            .fold(0xcbf2_9ce4_8422_2325u64, |h, c| (h ^ u64::from(c.to_bits())).wrapping_mul(0x0100_0000_01b3));
        f.debug_struct("EnvironmentMap")
            .field("name", &self.name)
            .field("width", &self.width)
            .field("height", &self.height)
            .field("texels", &format_args!("fnv1a:{hash:016x}"))
            .finish()
    }
}

impl EnvironmentMap {
    /// The same radiance `rgb` in every direction.
    pub fn constant(rgb: Vec3) -> Self {
        EnvironmentMap { name: "constant".into(), width: 1, height: 1, texels: Arc::from([rgb]) }
    }

    /// The built-in studio: a neutral grey dome, 1 at the zenith falling
    /// smoothly to 0.35 at the horizon, over a ground of 0.12 (64 × 32
    /// texels). Neutral, so that materials show their authored colours;
    /// brighter above, so that objects are modelled by a soft key from
    /// overhead and sit on the ground with a contact shadow; no sun, so
    /// that no hard shadow falls where the author put none. (The glTF
    /// sample viewer opens files in a neutral studio environment too.)
    pub fn studio() -> Self {
        let (width, height) = (64u32, 32u32);
        let texels: Vec<Vec3> = (0..height)
            .flat_map(|y| {
                let theta = PI * (y as f32 + 0.5) / height as f32;
                let up = crate::util::math::cos(theta);
                let grey = if up > 0.0 { 0.35 + 0.65 * up * up } else { 0.12 };
                (0..width).map(move |_| Vec3::splat(grey))
            })
            .collect();
        EnvironmentMap { name: "studio".into(), width, height, texels: texels.into() }
    }
}
