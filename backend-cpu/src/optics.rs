//! Packet optics: the core's reflection, refraction, Fresnel and
//! interface functions (`prismatic_core::optics`) on eight lanes at once,
//! operation for operation, so that a packet scatters as the scalar
//! reference does (the twin tests compare them lane by lane).

use crate::simd::{Vec3x8, ge, lt};
use prismatic_core::tolerance::{SURFACE_OFFSET_ABS, SURFACE_OFFSET_REL};
use wide::f32x8;

/// Mirror reflection, `d − n·(2·(d·n))`.
#[inline]
pub fn reflect(d: Vec3x8, n: Vec3x8) -> Vec3x8 {
    d - n * (f32x8::splat(2.0) * d.dot(n))
}

/// `prismatic_core::prepared::offset_origin` per lane.
#[inline]
pub fn offset_origin(p: Vec3x8, n: Vec3x8, dir: Vec3x8) -> Vec3x8 {
    let eps = f32x8::splat(SURFACE_OFFSET_ABS) + f32x8::splat(SURFACE_OFFSET_REL) * p.abs_max_element();
    let ne = n * eps;
    Vec3x8::select(ge(dir.dot(n), f32x8::ZERO), p + ne, p - ne)
}

/// `prismatic_core::trace::scatter_dielectric` per lane: returns the facing
/// normal and the new direction (reflected where `u < R` or under total
/// internal reflection, refracted otherwise).
#[inline]
pub fn scatter_dielectric(d: Vec3x8, outward: Vec3x8, ior: f32x8, u: f32x8) -> (Vec3x8, Vec3x8) {
    let (n, n1, n2) = interface(d, outward, ior);
    let r = fresnel(-d.dot(n), n1, n2);
    let (tir, refracted) = refract(d, n, n1, n2);
    (n, Vec3x8::select(lt(u, r) | tir, reflect(d, n), refracted))
}

/// `prismatic_core::optics::interface`: facing normal and the indices on either side.
#[inline]
pub fn interface(d: Vec3x8, outward: Vec3x8, ior: f32x8) -> (Vec3x8, f32x8, f32x8) {
    let entering = lt(d.dot(outward), f32x8::ZERO);
    (Vec3x8::select(entering, outward, -outward), entering.select(f32x8::ONE, ior), entering.select(ior, f32x8::ONE))
}

/// `prismatic_core::optics::cos2_transmitted` per lane.
#[inline]
pub fn cos2_transmitted(cos_i: f32x8, eta: f32x8) -> f32x8 {
    let eta2 = eta * eta;
    (f32x8::ONE - eta2) + eta2 * cos_i * cos_i
}

/// `prismatic_core::optics::fresnel` per lane.
#[inline]
pub fn fresnel(cos_i: f32x8, n1: f32x8, n2: f32x8) -> f32x8 {
    let cos_i = cos_i.max(f32x8::ZERO).min(f32x8::ONE);
    let cos2_t = cos2_transmitted(cos_i, n1 / n2);
    let tir = !cos2_t.simd_gt(f32x8::ZERO);
    let cos_t = cos2_t.max(f32x8::ZERO).sqrt();
    let rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
    let rp = (n1 * cos_t - n2 * cos_i) / (n1 * cos_t + n2 * cos_i);
    let r = (f32x8::splat(0.5) * (rs * rs + rp * rp)).max(f32x8::ZERO).min(f32x8::ONE);
    n1.simd_eq(n2).select(f32x8::ZERO, tir.select(f32x8::ONE, r))
}

/// `prismatic_core::optics::refract` per lane: (total internal reflection mask, direction).
#[inline]
pub fn refract(d: Vec3x8, n: Vec3x8, n1: f32x8, n2: f32x8) -> (f32x8, Vec3x8) {
    let eta = n1 / n2;
    let cos_i = (-d.dot(n)).max(f32x8::ZERO).min(f32x8::ONE);
    let cos2_t = cos2_transmitted(cos_i, eta);
    let cos_t = cos2_t.max(f32x8::ZERO).sqrt();
    (lt(cos2_t, f32x8::ZERO), (d * eta + n * (eta * cos_i - cos_t)).normalize())
}
