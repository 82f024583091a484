//! A linear-RGB image as renderers produce it.

use crate::model::color::{Display, to_srgb8};
use alloc::vec;
use alloc::vec::Vec;
use glam::Vec3;

/// Row-major linear RGB pixels, top row first.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width * height` pixels.
    pub pixels: Vec<Vec3>,
}

impl Image {
    /// A black image.
    pub fn new(width: u32, height: u32) -> Self {
        Image { width, height, pixels: vec![Vec3::ZERO; width as usize * height as usize] }
    }

    /// Pixel (x, y).
    pub fn get(&self, x: u32, y: u32) -> Vec3 {
        self.pixels[(y * self.width + x) as usize]
    }

    /// 8-bit sRGB bytes, RGBRGB…, as `display` shows them: exposed, tone
    /// mapped and clamped per pixel.
    pub fn to_srgb8(&self, display: Display) -> Vec<u8> {
        let k = display.exposure(&self.pixels);
        self.pixels.iter().flat_map(|&p| to_srgb8(display.tone_map.apply(p * k))).collect()
    }

    /// True when every pixel is finite.
    pub fn is_finite(&self) -> bool {
        self.pixels.iter().all(|p| p.is_finite())
    }
}
