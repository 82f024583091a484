//! Colour conversions: CIE XYZ to linear sRGB, and linear to 8-bit sRGB.

use glam::{DMat3, DVec3, Vec3};

/// XYZ → linear sRGB (D65), IEC 61966-2-1.
pub const XYZ_TO_LINEAR_SRGB: DMat3 = DMat3::from_cols_array(&[
    3.240_454_2,
    -0.969_266_0,
    0.055_643_4,
    -1.537_138_5,
    1.876_010_8,
    -0.204_025_9,
    -0.498_531_4,
    0.041_556_0,
    1.057_225_2,
]);

/// Converts CIE XYZ to linear sRGB.
pub fn xyz_to_linear_srgb(xyz: DVec3) -> DVec3 {
    XYZ_TO_LINEAR_SRGB * xyz
}

/// The sRGB transfer function for one channel, input clamped to `[0, 1]`.
pub fn encode_srgb(linear: f32) -> f32 {
    let c = if linear.is_nan() { 0.0 } else { linear.clamp(0.0, 1.0) };
    if c <= 0.003_130_8 { 12.92 * c } else { 1.055 * crate::util::math::powf(c, 1.0 / 2.4) - 0.055 }
}

/// How linear radiance becomes displayable before the sRGB encoding.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ToneMap {
    /// Clip each channel at 1 (bright caustics turn white).
    #[default]
    Clamp,
    /// Reinhard on luminance, Y/(1 + Y): compresses highlights while keeping
    /// their hue, so a bright caustic's coloured rim stays coloured.
    Reinhard,
}

impl ToneMap {
    /// The scene-file name.
    pub fn name(self) -> &'static str {
        match self {
            ToneMap::Clamp => "clamp",
            ToneMap::Reinhard => "reinhard",
        }
    }

    /// Maps one linear pixel (the final clamp happens in [`to_srgb8`]).
    #[inline]
    pub fn apply(self, rgb: Vec3) -> Vec3 {
        match self {
            ToneMap::Clamp => rgb,
            ToneMap::Reinhard => {
                let y = rgb.dot(Vec3::new(0.2126, 0.7152, 0.0722)).max(0.0);
                rgb / (1.0 + y)
            }
        }
    }
}

/// Linear RGB to 8-bit sRGB. The clamp happens here, on the final pixel only:
/// band weights may be negative (spectral colours lie outside the sRGB gamut).
pub fn to_srgb8(rgb: Vec3) -> [u8; 3] {
    let q = |c: f32| (encode_srgb(c) * 255.0 + 0.5) as u8;
    [q(rgb.x), q(rgb.y), q(rgb.z)]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_encoding_end_points_and_mid_grey() {
        assert_eq!(to_srgb8(Vec3::ZERO), [0, 0, 0]);
        assert_eq!(to_srgb8(Vec3::ONE), [255, 255, 255]);
        assert_eq!(to_srgb8(Vec3::splat(0.2159)), [128, 128, 128]);
        assert_eq!(to_srgb8(Vec3::new(f32::NAN, -1.0, 7.0)), [0, 0, 255]);
    }

    #[test]
    fn reinhard_keeps_hue_and_compresses_highlights() {
        let hot = Vec3::new(8.0, 4.0, 0.5);
        let mapped = ToneMap::Reinhard.apply(hot);
        assert!(mapped.max_element() < hot.max_element());
        assert!((mapped.x / mapped.y - 2.0).abs() < 1e-6, "hue ratio kept");
        assert_eq!(ToneMap::Clamp.apply(hot), hot);
    }

    #[test]
    fn d65_white_maps_to_equal_rgb() {
        let rgb = xyz_to_linear_srgb(DVec3::new(0.950_47, 1.0, 1.088_83));
        assert!((rgb - DVec3::ONE).abs().max_element() < 1e-3, "{rgb}");
    }
}
