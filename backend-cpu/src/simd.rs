//! Eight-lane vector types for packets: `Vec3x8` (structure of arrays over
//! `wide::f32x8`) and the counter-based RNG for eight photons at once.
//!
//! Arithmetic mirrors the scalar core operation for operation (glam's `dot`
//! is `(x·x + y·y) + z·z`, `normalize` multiplies by `1/length`), so a lane
//! computes the same bits as the scalar reference.

use glam::Vec3;
use prismatic_core::model::scene::PhotonSequence;
use prismatic_core::sampling::sobol;
use wide::{f32x8, i32x8, u32x8};

/// Eight 3-vectors, one per lane.
#[derive(Clone, Copy, Debug)]
pub struct Vec3x8 {
    /// x components.
    pub x: f32x8,
    /// y components.
    pub y: f32x8,
    /// z components.
    pub z: f32x8,
}

impl Vec3x8 {
    /// All lanes zero.
    pub const ZERO: Self = Vec3x8 { x: f32x8::ZERO, y: f32x8::ZERO, z: f32x8::ZERO };

    /// The same vector in every lane.
    #[inline]
    pub fn splat(v: Vec3) -> Self {
        Vec3x8 { x: f32x8::splat(v.x), y: f32x8::splat(v.y), z: f32x8::splat(v.z) }
    }

    /// Packs eight vectors.
    #[inline]
    pub fn from_lanes(v: &[Vec3; 8]) -> Self {
        Vec3x8 { x: f32x8::new(v.map(|v| v.x)), y: f32x8::new(v.map(|v| v.y)), z: f32x8::new(v.map(|v| v.z)) }
    }

    /// Lane `i` as a scalar vector.
    #[inline]
    pub fn lane(&self, i: usize) -> Vec3 {
        Vec3::new(self.x.as_array()[i], self.y.as_array()[i], self.z.as_array()[i])
    }

    /// Dot product, `(x·x + y·y) + z·z` as glam computes it.
    #[inline]
    pub fn dot(self, o: Self) -> f32x8 {
        self.x * o.x + self.y * o.y + self.z * o.z
    }

    /// Cross product (glam's operation order).
    #[inline]
    pub fn cross(self, o: Self) -> Self {
        Vec3x8 { x: self.y * o.z - o.y * self.z, y: self.z * o.x - o.z * self.x, z: self.x * o.y - o.x * self.y }
    }

    /// Squared length.
    #[inline]
    pub fn length_squared(self) -> f32x8 {
        self.dot(self)
    }

    /// Unit vectors (glam: `self * (1 / length)`).
    #[inline]
    pub fn normalize(self) -> Self {
        self * (f32x8::ONE / self.length_squared().sqrt())
    }

    /// Per-lane choice: `mask ? a : b`.
    #[inline]
    pub fn select(mask: f32x8, a: Self, b: Self) -> Self {
        Vec3x8 { x: mask.select(a.x, b.x), y: mask.select(a.y, b.y), z: mask.select(a.z, b.z) }
    }

    /// The largest absolute component per lane.
    #[inline]
    pub fn abs_max_element(self) -> f32x8 {
        self.x.abs().max(self.y.abs()).max(self.z.abs())
    }
}

impl core::ops::Add for Vec3x8 {
    type Output = Self;
    #[inline]
    fn add(self, o: Self) -> Self {
        Vec3x8 { x: self.x + o.x, y: self.y + o.y, z: self.z + o.z }
    }
}

impl core::ops::Sub for Vec3x8 {
    type Output = Self;
    #[inline]
    fn sub(self, o: Self) -> Self {
        Vec3x8 { x: self.x - o.x, y: self.y - o.y, z: self.z - o.z }
    }
}

impl core::ops::Neg for Vec3x8 {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        Vec3x8 { x: -self.x, y: -self.y, z: -self.z }
    }
}

impl core::ops::Mul<f32x8> for Vec3x8 {
    type Output = Self;
    #[inline]
    fn mul(self, s: f32x8) -> Self {
        Vec3x8 { x: self.x * s, y: self.y * s, z: self.z * s }
    }
}

impl core::ops::Div<f32x8> for Vec3x8 {
    type Output = Self;
    #[inline]
    fn div(self, s: f32x8) -> Self {
        Vec3x8 { x: self.x / s, y: self.y / s, z: self.z / s }
    }
}

/// Lane mask helpers (a mask lane is all ones or all zeros).
#[inline]
pub fn lt(a: f32x8, b: f32x8) -> f32x8 {
    a.simd_lt(b)
}

/// `a > b` per lane.
#[inline]
pub fn gt(a: f32x8, b: f32x8) -> f32x8 {
    a.simd_gt(b)
}

/// `a >= b` per lane.
#[inline]
pub fn ge(a: f32x8, b: f32x8) -> f32x8 {
    a.simd_ge(b)
}

/// The PCG hash of `prismatic_core::util::rng::pcg_hash`, on eight words.
#[inline]
pub fn pcg_hash(input: u32x8) -> u32x8 {
    let state = input * u32x8::splat(747_796_405) + u32x8::splat(2_891_336_453);
    let word = ((state >> ((state >> 28) + u32x8::splat(4))) ^ state) * u32x8::splat(277_803_737);
    (word >> 22) ^ word
}

/// `prismatic_core::util::rng::random_f32` for eight photon indices at once.
#[inline]
pub fn random_f32(seed: u32, index: u32x8, dimension: u32x8) -> f32x8 {
    let h = pcg_hash(pcg_hash(pcg_hash(u32x8::splat(seed)) ^ index) + dimension) >> 8;
    f32x8::from_i32x8(bytemuck::cast::<u32x8, i32x8>(h)) * f32x8::splat(1.0 / 16_777_216.0)
}

/// `prismatic_core::sampling::sobol::photon_f32` for eight photon indices at once
/// (the scrambled Sobol lanes one by one: a few per photon, beside its path).
#[inline]
pub fn photon_f32(sequence: PhotonSequence, seed: u32, index: u32x8, dimension: u32) -> f32x8 {
    match sobol::sobol_dimension(dimension) {
        Some(d) if sequence == PhotonSequence::Sobol => {
            f32x8::new(index.to_array().map(|i| sobol::sobol_f32(seed, i, d)))
        }
        _ => random_f32(seed, index, u32x8::splat(dimension)),
    }
}

/// `prismatic_core::util::math::sin_cos_turns` on eight values.
#[inline]
pub fn sin_cos_turns(u: f32x8) -> (f32x8, f32x8) {
    use prismatic_core::util::math::{COS_COEFFS as C, SIN_COEFFS as S};
    let k = |c: f32| f32x8::splat(c);
    let h = (u - (u + f32x8::splat(0.5)).floor()) * f32x8::splat(core::f32::consts::PI);
    let h2 = h * h;
    let s = h * (k(S[0]) + h2 * (k(S[1]) + h2 * (k(S[2]) + h2 * (k(S[3]) + h2 * (k(S[4]) + h2 * k(S[5]))))));
    let c = k(C[0]) + h2 * (k(C[1]) + h2 * (k(C[2]) + h2 * (k(C[3]) + h2 * (k(C[4]) + h2 * (k(C[5]) + h2 * k(C[6]))))));
    (f32x8::splat(2.0) * s * c, f32x8::ONE - f32x8::splat(2.0) * s * s)
}

/// `prismatic_core::geometry::primitive::basis` for eight unit vectors.
#[inline]
pub fn basis_x8(n: Vec3x8) -> (Vec3x8, Vec3x8) {
    // copysign(1, z): one with z's sign bit.
    let sign = f32x8::ONE | (n.z & f32x8::splat(-0.0));
    let a = f32x8::splat(-1.0) / (sign + n.z);
    let b = n.x * n.y * a;
    (
        Vec3x8 { x: f32x8::ONE + sign * n.x * n.x * a, y: sign * b, z: -sign * n.x },
        Vec3x8 { x: b, y: sign + n.y * n.y * a, z: -n.y },
    )
}

/// `prismatic_core::geometry::primitive::cone_direction` with the basis (t, b) of `axis` given.
#[inline]
pub fn cone_direction(axis: Vec3x8, t: Vec3x8, b: Vec3x8, cos_t: f32x8, u: f32x8) -> Vec3x8 {
    let sin_t = (f32x8::ONE - cos_t * cos_t).max(f32x8::ZERO).sqrt();
    let (sin_phi, cos_phi) = sin_cos_turns(u);
    (t * (sin_t * cos_phi) + b * (sin_t * sin_phi) + axis * cos_t).normalize()
}

#[cfg(test)]
mod tests {
    use super::*;
    use prismatic_core::util::rng;

    #[test]
    fn packet_rng_matches_the_scalar_rng_bit_for_bit() {
        for base in [0u32, 8, 1_000_000, u32::MAX - 8] {
            let idx: [u32; 8] = core::array::from_fn(|i| base.wrapping_add(i as u32));
            let dims: [u32; 8] = core::array::from_fn(|i| (i as u32) * 77);
            let got = random_f32(99, u32x8::new(idx), u32x8::new(dims)).to_array();
            for i in 0..8 {
                assert_eq!(got[i].to_bits(), rng::random_f32(99, idx[i], dims[i]).to_bits());
            }
        }
    }

    #[test]
    fn sin_cos_turns_matches_the_scalar_bit_for_bit() {
        for base in 0..1000 {
            let u: [f32; 8] = core::array::from_fn(|i| (base * 8 + i) as f32 / 8000.0);
            let (s, c) = sin_cos_turns(f32x8::new(u));
            for (i, &ui) in u.iter().enumerate() {
                let (ss, sc) = prismatic_core::util::math::sin_cos_turns(ui);
                assert_eq!((s.as_array()[i].to_bits(), c.as_array()[i].to_bits()), (ss.to_bits(), sc.to_bits()));
            }
        }
    }

    #[test]
    fn vector_ops_match_glam_bit_for_bit() {
        let a: [Vec3; 8] = core::array::from_fn(|i| Vec3::new(0.1 * i as f32 - 0.3, 1.7, -(i as f32).sqrt() - 0.01));
        let b: [Vec3; 8] = core::array::from_fn(|i| Vec3::new(2.0, -0.3 * i as f32, 0.77));
        let (pa, pb) = (Vec3x8::from_lanes(&a), Vec3x8::from_lanes(&b));
        for i in 0..8 {
            assert_eq!(pa.dot(pb).as_array()[i].to_bits(), a[i].dot(b[i]).to_bits());
            assert_eq!(pa.cross(pb).lane(i), a[i].cross(b[i]));
            assert_eq!(pa.normalize().lane(i), a[i].normalize());
        }
    }
}
