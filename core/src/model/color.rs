//! Colour conversions: CIE XYZ to linear sRGB, exposure and tone maps, and
//! linear to 8-bit sRGB.

use glam::{DMat3, DVec3, Mat3, Vec3};

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
    /// Khronos PBR Neutral (the glTF sample viewer's): the identity up to
    /// 0.76 apart from a small toe, so a base colour under white light of
    /// radiance 1 shows as authored; above it the peak channel rolls off
    /// toward 1 and the colour desaturates toward white, as film does.
    PbrNeutral,
    /// AgX (Troy Sobotka's, in Benjamin Wrensch's minimal form: the inset
    /// matrix, a log₂ encoding over [−12.47, 4.03] stops about 0.18, the
    /// default look's contrast curve, the outset matrix, display gamma 2.2):
    /// a filmic curve with about 16.5 stops of range whose bright saturated
    /// colours (a spectrum's bands) move toward white instead of clipping
    /// to the primaries.
    Agx,
}

impl ToneMap {
    /// Every tone map, in the order the scene reference lists them.
    pub const ALL: [ToneMap; 4] = [ToneMap::Clamp, ToneMap::Reinhard, ToneMap::PbrNeutral, ToneMap::Agx];

    /// The scene-file name.
    pub fn name(self) -> &'static str {
        match self {
            ToneMap::Clamp => "clamp",
            ToneMap::Reinhard => "reinhard",
            ToneMap::PbrNeutral => "pbr_neutral",
            ToneMap::Agx => "agx",
        }
    }

    /// Parses a scene-file name.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|t| t.name() == name)
    }

    /// Maps one linear pixel (the final clamp happens in [`to_srgb8`]).
    #[inline]
    pub fn apply(self, rgb: Vec3) -> Vec3 {
        match self {
            ToneMap::Clamp => rgb,
            ToneMap::Reinhard => {
                let y = luminance(rgb).max(0.0);
                rgb / (1.0 + y)
            }
            ToneMap::PbrNeutral => pbr_neutral(rgb.max(Vec3::ZERO)),
            ToneMap::Agx => agx(rgb.max(Vec3::ZERO)),
        }
    }
}

/// Rec. 709 luminance of linear RGB.
#[inline]
pub fn luminance(rgb: Vec3) -> f32 {
    rgb.dot(Vec3::new(0.2126, 0.7152, 0.0722))
}

/// Khronos PBR Neutral, as its specification writes it: F90 = 0.04,
/// compression from K_s = 0.8 − F90, desaturation K_d = 0.15.
fn pbr_neutral(c: Vec3) -> Vec3 {
    const F90: f32 = 0.04;
    const KS: f32 = 0.8 - F90;
    const KD: f32 = 0.15;
    let x = c.min_element();
    let f = if x <= 2.0 * F90 { x - x * x / (4.0 * F90) } else { F90 };
    let c = c - f;
    let p = c.max_element();
    if p <= KS {
        return c;
    }
    let pn = 1.0 - (1.0 - KS) * (1.0 - KS) / (p + 1.0 - 2.0 * KS);
    let g = 1.0 / (KD * (p - pn) + 1.0);
    c * (pn / p * g) + Vec3::splat(pn * (1.0 - g))
}

/// AgX's inset matrix (linear sRGB in, columns as written by Wrensch).
const AGX_INSET: Mat3 = Mat3::from_cols_array(&[
    0.842_479_06,
    0.042_328_24,
    0.042_375_655,
    0.078_433_6,
    0.878_468_6,
    0.078_433_6,
    0.079_223_745,
    0.079_166_13,
    0.879_143,
]);

/// AgX's outset matrix, the inset's inverse.
const AGX_OUTSET: Mat3 = Mat3::from_cols_array(&[
    1.196_879,
    -0.052_896_85,
    -0.052_971_635,
    -0.098_020_88,
    1.151_903_1,
    -0.098_043_45,
    -0.099_029_74,
    -0.098_961_18,
    1.151_073_7,
]);

/// The log₂ range AgX encodes, in stops about 0.18.
const AGX_EV: (f32, f32) = (-12.473_93, 4.026_069);

/// AgX's default look: the sigmoid in the log domain, as the sixth-degree
/// polynomial fit (mean squared error 3.7e-6).
fn agx_contrast(x: f32) -> f32 {
    let (x2, x4) = (x * x, x * x * x * x);
    15.5 * x4 * x2 - 40.14 * x4 * x + 31.96 * x4 - 6.868 * x2 * x + 0.4298 * x2 + 0.1191 * x - 0.00232
}

fn agx(c: Vec3) -> Vec3 {
    let (lo, hi) = AGX_EV;
    let inset = AGX_INSET * c;
    let curve = |v: f32| {
        let ev = if v > 0.0 { crate::util::math::log2(v).clamp(lo, hi) } else { lo };
        agx_contrast((ev - lo) / (hi - lo))
    };
    let display = AGX_OUTSET * Vec3::new(curve(inset.x), curve(inset.y), curve(inset.z));
    // The curve's output is display-encoded with gamma 2.2: back to linear,
    // which the sRGB encoding then takes to the display.
    display.max(Vec3::ZERO).map(|v| crate::util::math::powf(v, 2.2))
}

/// How a linear image is shown: scaled by its exposure (automatic or
/// none), tone mapped, clamped and sRGB-encoded.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Display {
    /// The curve.
    pub tone_map: ToneMap,
    /// Scale the image so that its log-average luminance is [`MIDDLE_GREY`]
    /// ([`auto_exposure`]) before the curve.
    pub auto_exposure: bool,
}

/// The luminance automatic exposure gives the image's log-average: the
/// 18 % grey of photography's key value (Reinhard et al. 2002).
pub const MIDDLE_GREY: f32 = 0.18;

/// The factor that puts the log-average luminance of `pixels` at
/// [`MIDDLE_GREY`]: 0.18 / exp(mean ln Y) over the pixels with light
/// (Y > 0 and finite; a black background or a shadow would drag the mean
/// toward 0 and blow out what is lit), 1 when no pixel has any. The
/// log-average, not the mean, so that a few bright caustic pixels do not
/// darken the rest.
pub fn auto_exposure(pixels: &[Vec3]) -> f32 {
    let (sum, n) = pixels
        .iter()
        .map(|&p| luminance(p))
        .filter(|y| y.is_finite() && *y > 0.0)
        .fold((0.0f64, 0u64), |(s, n), y| (s + f64::from(crate::util::math::ln(y)), n + 1));
    if n == 0 {
        return 1.0;
    }
    let mean = crate::util::math::exp((sum / n as f64) as f32);
    (MIDDLE_GREY / mean).clamp(1e-8, 1e8)
}

impl Display {
    /// The factor the image's pixels are scaled by before the curve.
    pub fn exposure(self, pixels: &[Vec3]) -> f32 {
        if self.auto_exposure { auto_exposure(pixels) } else { 1.0 }
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
    #[test]
    fn pbr_neutral_follows_its_specification() {
        let close = |a: Vec3, b: Vec3| (a - b).abs().max_element() < 1e-5;
        // Below the compression: only the toe's offset f (x − x²/(4·0.04) under 0.08, else 0.04).
        assert!(close(ToneMap::PbrNeutral.apply(Vec3::new(0.5, 0.4, 0.3)), Vec3::new(0.46, 0.36, 0.26)));
        assert!(close(ToneMap::PbrNeutral.apply(Vec3::new(0.5, 0.4, 0.0)), Vec3::new(0.5, 0.4, 0.0)));
        let x = 0.05;
        let f = x - x * x / 0.16;
        assert!(close(ToneMap::PbrNeutral.apply(Vec3::new(0.6, 0.3, x)), Vec3::new(0.6 - f, 0.3 - f, x - f)));
        // White of radiance 1: peak p = 0.96, p_n = 1 − 0.04²·… = 1 − 0.24²/0.44, all grey.
        let pn = 1.0 - 0.24 * 0.24 / 0.44;
        assert!(close(ToneMap::PbrNeutral.apply(Vec3::ONE), Vec3::splat(pn)));
        // Above: the peak rolls off below 1 and a colour moves toward white.
        let hot = ToneMap::PbrNeutral.apply(Vec3::new(40.0, 4.0, 0.5));
        assert!(hot.max_element() < 1.0 && hot.max_element() > 0.99, "{hot}");
        assert!(hot.z / hot.x > 0.5 / 40.0, "desaturated toward white: {hot}");
        // Continuous where the compression starts, and monotone along a grey ramp.
        let below = ToneMap::PbrNeutral.apply(Vec3::splat(0.8 - 1e-4));
        let above = ToneMap::PbrNeutral.apply(Vec3::splat(0.8 + 1e-4));
        assert!((above - below).abs().max_element() < 1e-3);
        let ramp: Vec<f32> = (0..200).map(|i| ToneMap::PbrNeutral.apply(Vec3::splat(i as f32 * 0.05)).x).collect();
        assert!(ramp.windows(2).all(|w| w[1] >= w[0]));
    }

    #[test]
    fn agx_puts_middle_grey_on_its_pivot_and_rolls_highlights_off() {
        // 0.18 sits at x = 12.47/16.5 = 0.606 of the log range, which the
        // curve takes to 0.18^(1/2.4) = 0.489 on the display (the
        // polynomial fit within 0.01; then back to linear with gamma 2.2).
        let grey = ToneMap::Agx.apply(Vec3::splat(0.18));
        let shown = crate::util::math::powf(grey.x, 1.0 / 2.2);
        assert!((shown - 0.4894).abs() < 1e-2, "{shown}");
        assert!((grey - Vec3::splat(grey.x)).abs().max_element() < 1e-4, "grey stays grey: {grey}");
        // Sixteen stops over it, a saturated red goes toward white, not to (1, 0, 0).
        let hot = ToneMap::Agx.apply(Vec3::new(1000.0, 0.0, 0.0));
        assert!(hot.x > 0.9 && hot.y > 0.1, "{hot}");
        assert!(ToneMap::Agx.apply(Vec3::ZERO).max_element() < 1e-3);
        let ramp: Vec<f32> = (0..100).map(|i| ToneMap::Agx.apply(Vec3::splat(0.01 * 1.1f32.powi(i))).x).collect();
        assert!(ramp.windows(2).all(|w| w[1] >= w[0] - 1e-6));
    }

    #[test]
    fn auto_exposure_puts_the_log_average_of_lit_pixels_at_middle_grey() {
        let pixels = [Vec3::splat(0.5), Vec3::splat(2.0), Vec3::ZERO, Vec3::splat(f32::NAN)];
        // The geometric mean of 0.5 and 2 is 1; black and NaN are not counted.
        assert!((auto_exposure(&pixels) - MIDDLE_GREY).abs() < 1e-6);
        assert_eq!(auto_exposure(&[Vec3::ZERO; 4]), 1.0);
        let display = Display { tone_map: ToneMap::Clamp, auto_exposure: false };
        assert_eq!(display.exposure(&pixels), 1.0);
        for tone_map in ToneMap::ALL {
            assert_eq!(ToneMap::from_name(tone_map.name()), Some(tone_map));
        }
    }
}
