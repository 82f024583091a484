//! The numbers of a sampled view path ([`crate::model::scene::ViewPaths::Sampled`]):
//! pass k's path through a pixel takes its point in the pixel and its hero
//! wavelengths' shift from Owen-scrambled Sobol point k (one scramble per
//! pixel, so each pixel's passes are stratified and neighbouring pixels are
//! not correlated), and its Fresnel choices from counter-based random
//! numbers, one per hero path and bounce.
//! Every number is a pure function of (seed, pixel, pass), so pass k's view
//! is the same on every backend and in any order of passes; the WGSL twin
//! draws them in `backend-gpu/src/shaders/view.wgsl` (`pixel`,
//! `through_dielectric` and the hero split entry of `visit`).

use crate::sampling::sobol::sobol_f32;
use crate::util::rng::{random_f32, random_u32};

/// The dimension of the pixel's scramble seed in [`random_u32`] ("view"):
/// far above every dimension a photon uses.
pub const PIXEL_SCRAMBLE: u32 = 0x7669_6577;

/// The first dimension of a path's Fresnel choices (one per specular
/// bounce), after the three Sobol dimensions (jitter x, y and spectrum).
pub const BRANCH: u32 = 3;

/// Fresnel choices reserved per hero path (one per bounce).
pub const PER_PATH: u32 = 64;

/// The first dimension of a path's metal facets (two per bounce, per hero
/// path), above every Fresnel choice.
pub const FACET: u32 = 0x1000;

/// Pass `pass`'s numbers for one pixel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PixelSampler {
    scramble: u32,
    pass: u32,
}

impl PixelSampler {
    /// The numbers of pass `pass` in pixel `pixel` (row-major) of a render with `seed`.
    #[inline]
    pub fn new(seed: u32, pixel: u32, pass: u32) -> Self {
        PixelSampler { scramble: random_u32(seed, pixel, PIXEL_SCRAMBLE), pass }
    }

    /// The pixel's scramble seed (what the view shader keeps per pixel).
    #[inline]
    pub fn scramble(&self) -> u32 {
        self.scramble
    }

    /// The path's point in the pixel, as fractions of its width and height.
    #[inline]
    pub fn jitter(&self) -> (f32, f32) {
        (sobol_f32(self.scramble, self.pass, 0), sobol_f32(self.scramble, self.pass, 1))
    }

    /// The path's spectrum number: the shift of its hero wavelengths at
    /// the first dispersive glass ([`crate::photons::wavelengths::spectrum_share`]).
    #[inline]
    pub fn spectrum(&self) -> f32 {
        sobol_f32(self.scramble, self.pass, 2)
    }

    /// The number that chooses the Fresnel branch of hero path `path` (0
    /// before the split) at specular bounce `depth`.
    #[inline]
    pub fn branch(&self, path: u32, depth: u32) -> f32 {
        random_f32(self.scramble, self.pass, BRANCH + path * PER_PATH + depth)
    }

    /// The two numbers that draw the facet of a rough metal that hero path
    /// `path` (0 before the split) reflects off at specular bounce `depth`.
    #[inline]
    pub fn facet(&self, path: u32, depth: u32) -> (f32, f32) {
        let d = FACET + 2 * (path * PER_PATH + depth);
        (random_f32(self.scramble, self.pass, d), random_f32(self.scramble, self.pass, d + 1))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_pixels_passes_are_stratified_and_pixels_differ() {
        // 16 passes of one pixel put one jitter in each 4 × 4 cell.
        let mut cells = [0u32; 16];
        for pass in 0..16 {
            let (x, y) = PixelSampler::new(1, 12_345, pass).jitter();
            assert!((0.0..1.0).contains(&x) && (0.0..1.0).contains(&y));
            cells[(y * 4.0) as usize * 4 + (x * 4.0) as usize] += 1;
        }
        assert_eq!(cells, [1; 16]);
        assert_ne!(PixelSampler::new(1, 1, 0).jitter(), PixelSampler::new(1, 2, 0).jitter());
        assert_ne!(PixelSampler::new(1, 1, 0).jitter(), PixelSampler::new(2, 1, 0).jitter());
    }
}
