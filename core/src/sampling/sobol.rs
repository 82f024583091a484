//! Owen-scrambled Sobol points: the low-discrepancy numbers of a photon's emission and wavelength.
//!
//! A pass's photons 0..N are the first N points of the Sobol sequence in
//! three dimensions (the two of the light's sample and the spectrum's), so
//! their directions and wavelengths are stratified jointly: every elementary
//! box of the unit square holds its share of photons, where independent
//! random numbers leave clumps and holes. Each pass scrambles the points
//! with its own seed (Owen's nested uniform scrambling in Burley's hashed
//! form, "Practical Hash-based Owen Scrambling", JCGT 2020): the points
//! stay stratified, each is uniform on its own, and passes are independent
//! randomised-QMC replicates, so a render's error still falls as 1/√passes
//! from a lower start and sums of passes stay unbiased.
//!
//! Like [`crate::util::rng`], every number is a pure function of (seed, index,
//! dimension) in 32-bit integer arithmetic, mirrored bit for bit by the
//! WGSL twin in `backend-gpu/src/shaders/common.wgsl`. The generator
//! matrices are not tabulated: each column follows from the previous ones
//! by the recurrence of the dimension's primitive polynomial (Joe & Kuo's
//! direction numbers for dimensions 2 and 3), so a GPU thread needs no table.

use crate::model::scene::PhotonSequence;
use crate::util::rng::{dim, random_f32, random_u32};

/// How many Sobol dimensions [`sobol_u32`] generates.
pub const DIMENSIONS: u32 = 3;

/// Dimension `dimension` (0, 1 or 2) of unscrambled Sobol point `index`, as a
/// 32-bit fraction: the XOR of the generator matrix's columns v_k for the
/// index's set bits.
///
/// - 0: the van der Corput sequence (v_k = 2^(32−k), the index's bits reversed);
/// - 1: polynomial x + 1, m = (1): v_k = v_(k−1) ⊕ v_(k−1)/2;
/// - 2: polynomial x² + x + 1, m = (1, 3): v_k = v_(k−1) ⊕ v_(k−2) ⊕ v_(k−2)/4,
///   started from v_0 = 0x5555_5555, the one value for which the recurrence
///   gives v_2 = 3/4 (m_2 = 3).
pub fn sobol_u32(index: u32, dimension: u32) -> u32 {
    if dimension == 0 {
        return index.reverse_bits();
    }
    let (mut x, mut v, mut prev, mut i) = (0u32, 1u32 << 31, 0x5555_5555u32, index);
    while i != 0 {
        if i & 1 != 0 {
            x ^= v;
        }
        let next = if dimension == 1 { v ^ (v >> 1) } else { v ^ prev ^ (prev >> 2) };
        (prev, v) = (v, next);
        i >>= 1;
    }
    x
}

/// Owen's nested uniform scramble of a 32-bit fraction: Laine and Karras's
/// hash on the reversed bits, in which every bit is flipped by a function of
/// the bits above it only (Burley 2020, listing 2). Stratification of the
/// points into elementary boxes survives it.
pub fn owen_scramble(x: u32, seed: u32) -> u32 {
    let mut x = x.reverse_bits();
    x = x.wrapping_add(seed);
    x ^= x.wrapping_mul(0x6c50_b47c);
    x ^= x.wrapping_mul(0xb82f_1e52);
    x ^= x.wrapping_mul(0xc7af_e638);
    x ^= x.wrapping_mul(0x8d22_f6e6);
    x.reverse_bits()
}

/// The scramble seed of `dimension` in the pass with `seed`: a hash no
/// photon's random numbers use (photon indices stay below `u32::MAX`).
#[inline]
fn scramble_seed(seed: u32, dimension: u32) -> u32 {
    random_u32(seed, u32::MAX, dimension)
}

/// Dimension `dimension` of scrambled Sobol point `index` in `[0, 1)`, with
/// the 24 bits of resolution of [`crate::util::rng::random_f32`].
#[inline]
pub fn sobol_f32(seed: u32, index: u32, dimension: u32) -> f32 {
    (owen_scramble(sobol_u32(index, dimension), scramble_seed(seed, dimension)) >> 8) as f32 * (1.0 / 16_777_216.0)
}

/// The Sobol dimension of a photon's number `dimension` ([`dim`]): the
/// light's two-dimensional sample and the spectrum; `None` for the rest
/// (the light and target choices and every decision along the path stay
/// random, so no dimension of the sequence is spent where it buys little).
#[inline]
pub fn sobol_dimension(dimension: u32) -> Option<u32> {
    match dimension {
        dim::DIRECTION => Some(0),
        d if d == dim::DIRECTION + 1 => Some(1),
        dim::SPECTRUM => Some(2),
        _ => None,
    }
}

/// Number `dimension` of white photon `index` in the pass with `seed`:
/// scrambled Sobol where `sequence` asks for it and the dimension has one,
/// else the counter-based random number.
#[inline]
pub fn photon_f32(sequence: PhotonSequence, seed: u32, index: u32, dimension: u32) -> f32 {
    match sobol_dimension(dimension) {
        Some(d) if sequence == PhotonSequence::Sobol => sobol_f32(seed, index, d),
        _ => random_f32(seed, index, dimension),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use alloc::vec;
    use alloc::vec::Vec;

    /// The `dims` coordinates of points 0..2^m, scrambled with `scramble`'s seeds or not.
    fn points(m: u32, dims: &[u32], scramble: Option<u32>) -> Vec<Vec<u32>> {
        (0..1u32 << m)
            .map(|i| {
                dims.iter()
                    .map(|&d| {
                        let x = sobol_u32(i, d);
                        scramble.map_or(x, |s| owen_scramble(x, scramble_seed(s, d)))
                    })
                    .collect()
            })
            .collect()
    }

    /// The largest number of points in one elementary box with `split[j]`
    /// bits along dimension j, over all boxes.
    fn fullest_box(points: &[Vec<u32>], split: &[u32]) -> usize {
        let total: u32 = split.iter().sum();
        let mut counts = vec![0usize; 1 << total];
        for p in points {
            let mut cell = 0usize;
            for (x, &b) in p.iter().zip(split) {
                cell = (cell << b) | if b == 0 { 0 } else { (x >> (32 - b)) as usize };
            }
            counts[cell] += 1;
        }
        counts.into_iter().max().unwrap()
    }

    /// Whether the points form a (t, m, s)-net: every elementary box of
    /// volume 2^(t−m) holds exactly 2^t points.
    fn is_net(points: &[Vec<u32>], m: u32, t: u32) -> bool {
        let s = points[0].len();
        let mut split = vec![0u32; s];
        let mut ok = true;
        // Every split of m − t bits among the dimensions.
        fn each(split: &mut [u32], j: usize, left: u32, f: &mut dyn FnMut(&[u32])) {
            if j + 1 == split.len() {
                split[j] = left;
                f(split);
                return;
            }
            for b in 0..=left {
                split[j] = b;
                each(split, j + 1, left - b, f);
            }
        }
        each(&mut split, 0, m - t, &mut |split| ok &= fullest_box(points, split) == 1 << t);
        ok
    }

    #[test]
    fn first_points_are_sobols() {
        // Joe & Kuo's m values of the third dimension: 1, 3, 3, 9, 29.
        let m = [1u32, 3, 3, 9, 29];
        for (k, m) in m.iter().enumerate() {
            assert_eq!(sobol_u32(1 << k, 2), m << (31 - k), "column {k}");
        }
        assert_eq!([1, 2, 3].map(|i| sobol_u32(i, 1)), [1 << 31, 3 << 30, 1 << 30]);
    }

    #[test]
    fn every_power_of_two_prefix_is_a_net_scrambled_or_not() {
        for scramble in [None, Some(1), Some(0xdead_beef)] {
            for m in 1..=10 {
                // Each dimension alone is stratified perfectly, and so are
                // the first two together ((0, m, 2)-nets).
                for d in 0..DIMENSIONS {
                    assert!(is_net(&points(m, &[d], scramble), m, 0), "dimension {d}, m {m}, {scramble:?}");
                }
                assert!(is_net(&points(m, &[0, 1], scramble), m, 0), "m {m}, {scramble:?}");
                // All three: a (1, m, 3)-net.
                assert!(is_net(&points(m, &[0, 1, 2], scramble), m, 1), "m {m}, {scramble:?}");
            }
        }
    }

    #[test]
    fn scrambled_points_are_uniform_and_seeds_differ() {
        let n = 1 << 14;
        for d in 0..DIMENSIONS {
            let mean = (0..n).map(|i| sobol_f32(7, i, d) as f64).sum::<f64>() / n as f64;
            assert!((mean - 0.5).abs() < 1e-3, "dimension {d}: mean {mean}");
            assert!((0..n).all(|i| (0.0..1.0).contains(&sobol_f32(7, i, d))));
        }
        let same = (0..n).filter(|&i| sobol_f32(7, i, 0) == sobol_f32(8, i, 0)).count();
        assert!(same < 4, "{same} equal points under two seeds");
    }
}
