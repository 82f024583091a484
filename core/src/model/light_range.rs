//! A light's range (glTF's `KHR_lights_punctual` `range`): the distance
//! at which its light must be taken as zero. The extension recommends the
//! window w(d) = clamp(1 − (d / range)⁴, 0, 1) on the inverse square law,
//! which keeps the law near the light and reaches 0 smoothly at the range.
//!
//! prismatic applies it where the light meets its first surface: the
//! light arriving along a ray from the light is windowed by the distance
//! it travelled. Direct light at a point at distance d is w(d) I cos θ/d²,
//! and a photon's flux is windowed at its first hit (what the window takes
//! counts as escaped). What a surface within range reflects or refracts
//! goes on as light does (a glass within range casts its caustic wherever
//! it falls), as the range cuts off the light, not the scene.

/// The window of light that has travelled `distance` from a light of
/// `range` (`None`: no range, 1 everywhere).
#[inline]
pub fn range_window(distance: f32, range: Option<f32>) -> f32 {
    match range {
        None => 1.0,
        Some(range) => {
            let ratio = distance / range;
            let squared = ratio * ratio;
            (1.0 - squared * squared).clamp(0.0, 1.0)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_window_is_one_at_the_light_and_zero_from_its_range_on() {
        assert_eq!(range_window(0.0, Some(5.0)), 1.0);
        assert_eq!(range_window(3.0, None), 1.0);
        assert_eq!(range_window(5.0, Some(5.0)), 0.0);
        assert_eq!(range_window(7.0, Some(5.0)), 0.0);
        assert_eq!(range_window(f32::INFINITY, Some(5.0)), 0.0);
        // Half the range: 1 − 1/16.
        assert!((range_window(2.5, Some(5.0)) - 15.0 / 16.0).abs() < 1e-7);
    }
}
