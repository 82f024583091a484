//! Counter-based random numbers: a pure function of (seed, photon index, dimension).
//!
//! There is no RNG state: every backend (scalar, SIMD lanes, GPU threads)
//! computes the same number for the same photon and dimension, whatever the
//! order in which photons are traced. The hash is PCG's output permutation
//! (O'Neill 2014, as used by Jarzynski & Olano 2020), integer-only so that
//! the WGSL twin in `backend-gpu/src/shaders/rng.wgsl` is bit-identical.

/// One round of the PCG hash (RXS-M-XS on a 32-bit LCG step).
#[inline]
pub fn pcg_hash(input: u32) -> u32 {
    let state = input.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
    let word = ((state >> ((state >> 28) + 4)) ^ state).wrapping_mul(277_803_737);
    (word >> 22) ^ word
}

/// The random 32-bit word for `(seed, index, dimension)`.
#[inline]
pub fn random_u32(seed: u32, index: u32, dimension: u32) -> u32 {
    pcg_hash(pcg_hash(pcg_hash(seed) ^ index).wrapping_add(dimension))
}

/// A uniform float in `[0, 1)` with 24 bits of resolution.
#[inline]
pub fn random_f32(seed: u32, index: u32, dimension: u32) -> f32 {
    (random_u32(seed, index, dimension) >> 8) as f32 * (1.0 / 16_777_216.0)
}

/// Random dimensions used by photon emission (the first few of every photon).
pub mod dim {
    /// Which light emits the photon.
    pub const LIGHT: u32 = 0;
    /// Two dimensions for the light's own sample: the emission direction,
    /// or where on its disc a beam's photon starts.
    pub const DIRECTION: u32 = 1;
    /// Which projection-map target a photon is aimed at.
    pub const TARGET: u32 = 3;
    /// The spectrum of a white photon that does not split: the band it
    /// continues as and, for continuous sampling, its wavelength within the
    /// band (one number, so a stratified sequence stratifies the spectrum).
    pub const SPECTRUM: u32 = 4;
    /// Two dimensions for where on an area light a photon starts (its
    /// direction takes [`DIRECTION`]'s two).
    pub const AREA: u32 = 5;
    /// The scramble of an environment region's suns, one Sobol sequence over
    /// the passes (the index is the region's, not a photon's; see
    /// `plan::drawn_suns`).
    pub const SKY: u32 = 7;
    /// First dimension of the path's scattering decisions.
    pub const PATH: u32 = 8;
    /// The scramble of an area light's shadow aims, one Sobol sequence over
    /// the passes (the index is the light's; see `plan::area_aims`), past
    /// every dimension a photon uses.
    pub const AIM: u32 = u32::MAX;
    /// The scramble of the offset of each pass's choice of emissive
    /// triangles, one Sobol sequence over the passes (index 0; see
    /// `plan::drawn_triangles`), below [`AIM`].
    pub const TRIANGLES: u32 = u32::MAX - 1;
    /// Dimensions reserved per band path (one per bounce, at most this many bounces).
    pub const PER_BAND: u32 = 64;

    /// The dimension of the scattering decision at `bounce` on the path of `band`
    /// (`band` is [`crate::model::photon::WHITE_BAND`] before a split).
    #[inline]
    pub fn scatter(band: u16, bounce: u32) -> u32 {
        PATH + (band as u32).wrapping_add(1) % 0x1_0000 * PER_BAND + bounce
    }

    /// Added to a scattering dimension for the absorption decision at the
    /// same hit: above every scattering dimension (those end below 2²²).
    pub const ABSORB: u32 = 1 << 24;

    /// The dimension of the decision whether the path of `band` survives
    /// the glass it crossed before `bounce` (coloured glass).
    #[inline]
    pub fn absorb(band: u16, bounce: u32) -> u32 {
        scatter(band, bounce) + ABSORB
    }

    /// Added to a scattering dimension for the first of the two numbers of
    /// a diffuse bounce's direction at the same hit (indirect light; the
    /// second is one [`ABSORB`] above it): above every absorption decision.
    pub const BOUNCE: u32 = 2 << 24;

    /// The two dimensions of the direction a path of `band` leaves a
    /// diffuse surface in at `bounce` (its survival takes [`scatter`]'s).
    #[inline]
    pub fn bounce(band: u16, bounce: u32) -> [u32; 2] {
        let first = scatter(band, bounce) + BOUNCE;
        [first, first + ABSORB]
    }

    /// Added to a scattering dimension for the choice of the one wavelength
    /// an indirect photon goes on as at dispersive glass: above both of a
    /// diffuse bounce's direction numbers.
    pub const CHOOSE: u32 = 4 << 24;

    /// The dimension of that choice at `bounce` (the path carries several
    /// wavelengths, so its band is [`crate::model::photon::WHITE_BAND`]).
    #[inline]
    pub fn choose(bounce: u32) -> u32 {
        scatter(u16::MAX, bounce) + CHOOSE
    }

    /// Added to a scattering dimension for the choice whether a path goes
    /// on as a blended metal's specular part: above every wavelength choice.
    pub const METAL_PART: u32 = 5 << 24;

    /// The dimension of that choice for the path of `band` at `bounce`
    /// ([`crate::optics::metal`]: the specular part's share is the probability).
    #[inline]
    pub fn metal_part(band: u16, bounce: u32) -> u32 {
        scatter(band, bounce) + METAL_PART
    }

    /// Added to a scattering dimension for the first of the two numbers of
    /// the diffuse bounce of a path a specular layer passed to its base
    /// (its facet took [`bounce`]'s; the second is one [`ABSORB`] above
    /// it): above the specular part's choice.
    pub const BASE_BOUNCE: u32 = 6 << 24;

    /// The two dimensions of that bounce's direction for the path of
    /// `band` at `bounce`.
    #[inline]
    pub fn base_bounce(band: u16, bounce: u32) -> [u32; 2] {
        let first = scatter(band, bounce) + BASE_BOUNCE;
        [first, first + ABSORB]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uniform_floats_cover_unit_interval() {
        let n = 100_000;
        let mut sum = 0.0f64;
        let mut lo = 1.0f32;
        let mut hi = 0.0f32;
        for i in 0..n {
            let x = random_f32(7, i, 3);
            assert!((0.0..1.0).contains(&x));
            sum += x as f64;
            lo = lo.min(x);
            hi = hi.max(x);
        }
        let mean = sum / n as f64;
        assert!((mean - 0.5).abs() < 0.005, "mean {mean}");
        assert!(lo < 1e-3 && hi > 0.999);
    }

    #[test]
    fn dimensions_and_seeds_are_decorrelated() {
        let same = (0..10_000)
            .filter(|&i| random_u32(1, i, 0) == random_u32(1, i, 1) || random_u32(1, i, 0) == random_u32(2, i, 0))
            .count();
        assert_eq!(same, 0);
    }
}
