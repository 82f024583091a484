//! Progressive photon mapping: many independent photon passes with a gather
//! radius that shrinks from pass to pass, averaged into one image.
//!
//! This is the memoryless form of Knaus & Zwicker (2011): pass k (from 1)
//! gathers with r_k² = r_1² · Π_{j=1}^{k−1} (j + α)/(j + 1), and the image is
//! the plain mean of the passes' images. With 0 < α < 1 both the variance
//! and the bias of the mean go to zero, so the mean converges to the true
//! caustic, which a fixed radius never does (it stays blurred by r).
//! Hachisuka's α ≈ 0.7 is the usual compromise between the two.

use crate::image::Image;
use crate::math::sqrt;
use crate::prepared::PreparedScene;
use crate::rng::random_u32;
use alloc::vec;
use alloc::vec::Vec;
use glam::DVec3;

/// Hachisuka et al.'s recommended fraction of photons kept per pass.
pub const DEFAULT_ALPHA: f32 = 0.7;

/// The radius of pass `k` (1-based) when pass 1 uses `r1`.
pub fn pass_radius(r1: f32, alpha: f32, k: u32) -> f32 {
    let mut r2 = f64::from(r1) * f64::from(r1);
    for j in 1..k {
        r2 *= (f64::from(j) + f64::from(alpha)) / (f64::from(j) + 1.0);
    }
    sqrt(r2 as f32)
}

/// The scene of pass `k` (1-based): its own seed (derived from the scene's,
/// so passes are independent) and the pass's radius.
pub fn pass_scene(scene: &PreparedScene, alpha: f32, k: u32) -> PreparedScene {
    let mut pass = scene.clone();
    let r = &mut pass.scene.render;
    r.seed = random_u32(r.seed, k, u32::MAX);
    r.radius = pass_radius(r.radius, alpha, k);
    pass
}

/// The running mean of the passes' images, kept in f64.
#[derive(Clone, Debug, PartialEq)]
pub struct PassAverage {
    width: u32,
    height: u32,
    sum: Vec<DVec3>,
    passes: u32,
}

impl PassAverage {
    /// An empty average for `width` × `height` images.
    pub fn new(width: u32, height: u32) -> Self {
        PassAverage { width, height, sum: vec![DVec3::ZERO; width as usize * height as usize], passes: 0 }
    }

    /// Adds one pass's image (same size).
    ///
    /// # Panics
    /// If the image size differs.
    pub fn add(&mut self, image: &Image) {
        assert_eq!((image.width, image.height), (self.width, self.height), "pass image size");
        for (s, p) in self.sum.iter_mut().zip(&image.pixels) {
            *s += p.as_dvec3();
        }
        self.passes += 1;
    }

    /// Passes added so far.
    pub fn passes(&self) -> u32 {
        self.passes
    }

    /// The mean image (black before the first pass).
    pub fn mean(&self) -> Image {
        let scale = 1.0 / f64::from(self.passes.max(1));
        let mut image = Image::new(self.width, self.height);
        for (p, s) in image.pixels.iter_mut().zip(&self.sum) {
            *p = (*s * scale).as_vec3();
        }
        image
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn radius_shrinks_as_the_closed_form_says() {
        assert_eq!(pass_radius(0.1, 0.7, 1), 0.1);
        // r_2² = r_1² (1 + α)/2.
        assert!((pass_radius(0.1, 0.7, 2) - 0.1 * (0.85f32).sqrt()).abs() < 1e-7);
        // Π (j+α)/(j+1) ~ Γ(2)/Γ(1+α) · k^(α−1): r_k² falls like k^(−0.3).
        let r = |k| f64::from(pass_radius(1.0, 0.7, k)).powi(2);
        let slope = (r(4000) / r(1000)).ln() / 4f64.ln();
        assert!((slope + 0.3).abs() < 1e-3, "slope {slope}");
        // α = 1 keeps the radius.
        assert_eq!(pass_radius(0.1, 1.0, 50), 0.1);
    }

    #[test]
    fn the_average_is_the_mean_of_the_passes() {
        let mut avg = PassAverage::new(2, 1);
        let mut a = Image::new(2, 1);
        a.pixels[0] = glam::Vec3::splat(1.0);
        let mut b = Image::new(2, 1);
        b.pixels[0] = glam::Vec3::splat(3.0);
        b.pixels[1] = glam::Vec3::X;
        avg.add(&a);
        avg.add(&b);
        assert_eq!(avg.passes(), 2);
        assert_eq!(avg.mean().pixels, [glam::Vec3::splat(2.0), glam::Vec3::new(0.5, 0.0, 0.0)]);
    }
}
