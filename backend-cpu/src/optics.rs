//! Packet optics: the core's reflection, refraction, Fresnel and
//! interface functions (`prismatic_core::optics::fresnel`) on eight lanes at once,
//! operation for operation, so that a packet scatters as the scalar
//! reference does (the twin tests compare them lane by lane).

use crate::simd::{Vec3x8, basis_x8, cone_direction, ge, lt};
use glam::Vec3;
use prismatic_core::util::tolerance::{SURFACE_OFFSET_ABS, SURFACE_OFFSET_REL};
use wide::f32x8;

/// Mirror reflection, `d − n·(2·(d·n))`.
#[inline]
pub fn reflect(d: Vec3x8, n: Vec3x8) -> Vec3x8 {
    d - n * (f32x8::splat(2.0) * d.dot(n))
}

/// `prismatic_core::optics::scatter::offset_origin` per lane.
#[inline]
pub fn offset_origin(p: Vec3x8, n: Vec3x8, dir: Vec3x8) -> Vec3x8 {
    let eps = f32x8::splat(SURFACE_OFFSET_ABS) + f32x8::splat(SURFACE_OFFSET_REL) * p.abs_max_element();
    let ne = n * eps;
    Vec3x8::select(ge(dir.dot(n), f32x8::ZERO), p + ne, p - ne)
}

/// `prismatic_core::optics::scatter::scatter_diffuse` per lane: Lambert's
/// law about the normal on the side each ray came from; the new origins
/// and directions.
#[inline]
pub fn scatter_diffuse(d: Vec3x8, point: Vec3x8, normal: Vec3x8, u1: f32x8, u2: f32x8) -> (Vec3x8, Vec3x8) {
    let n = Vec3x8::select(lt(d.dot(normal), f32x8::ZERO), normal, -normal);
    let (t, b) = basis_x8(n);
    let dir = cone_direction(n, t, b, (f32x8::ONE - u1).sqrt(), u2);
    (offset_origin(point, n, dir), dir)
}

/// `prismatic_core::optics::scatter::split_dielectric` per lane: both
/// branches at glass. Origins are pushed off the surface to each branch's
/// side; `tir` marks the lanes without a refracted ray.
#[derive(Clone, Copy)]
pub struct BranchesX8 {
    /// Fresnel reflectance R.
    pub reflectance: f32x8,
    /// The reflected ray: (origin, direction).
    pub reflected: (Vec3x8, Vec3x8),
    /// The refracted ray: (origin, direction), meaningless where `tir`.
    pub refracted: (Vec3x8, Vec3x8),
    /// Lanes under total internal reflection.
    pub tir: f32x8,
}

impl BranchesX8 {
    /// The branch `scatter_dielectric` takes in lane `i` for number `u`:
    /// (origin, direction), reflected where `u < R` or under total
    /// internal reflection.
    pub fn choose(&self, i: usize, u: f32) -> (Vec3, Vec3) {
        let reflect = u < self.reflectance.to_array()[i] || self.tir.to_bitmask() & (1 << i) != 0;
        let (origin, dir) = if reflect { self.reflected } else { self.refracted };
        (origin.lane(i), dir.lane(i))
    }
}

/// Both branches at glass for eight rays `d` at `point` (outward normal
/// `outward`); the lanes of `thin` are at a thin sheet.
#[inline]
pub fn split_dielectric(d: Vec3x8, point: Vec3x8, outward: Vec3x8, ior: f32x8, thin: f32x8) -> BranchesX8 {
    let (n, n1, n2) = interface(d, outward, ior);
    let cos_i = -d.dot(n);
    let reflectance = thin.select(sheet_reflectance(fresnel(cos_i, f32x8::ONE, ior)), fresnel(cos_i, n1, n2));
    let reflected = reflect(d, n);
    let (tir, refracted) = refract(d, n, n1, n2);
    let (tir, refracted) = (tir & !thin, Vec3x8::select(thin, d, refracted));
    BranchesX8 {
        reflectance,
        reflected: (offset_origin(point, n, reflected), reflected),
        refracted: (offset_origin(point, n, refracted), refracted),
        tir,
    }
}

/// `prismatic_core::optics::scatter::scatter_dielectric` per lane: returns the facing
/// normal and the new direction (reflected where `u < R` or under total
/// internal reflection, refracted otherwise; at a sheet, the lanes of
/// `thin`, reflected where `u` is below its reflectance, else straight on).
#[inline]
pub fn scatter_dielectric(d: Vec3x8, outward: Vec3x8, ior: f32x8, thin: f32x8, u: f32x8) -> (Vec3x8, Vec3x8) {
    let (n, n1, n2) = interface(d, outward, ior);
    let cos_i = -d.dot(n);
    let r = thin.select(sheet_reflectance(fresnel(cos_i, f32x8::ONE, ior)), fresnel(cos_i, n1, n2));
    let (tir, refracted) = refract(d, n, n1, n2);
    let (tir, through) = (tir & !thin, Vec3x8::select(thin, d, refracted));
    (n, Vec3x8::select(lt(u, r) | tir, reflect(d, n), through))
}

/// `prismatic_core::optics::fresnel::sheet_reflectance` per lane.
#[inline]
pub fn sheet_reflectance(r: f32x8) -> f32x8 {
    f32x8::splat(2.0) * r / (f32x8::ONE + r)
}

/// `prismatic_core::optics::fresnel::interface`: facing normal and the indices on either side.
#[inline]
pub fn interface(d: Vec3x8, outward: Vec3x8, ior: f32x8) -> (Vec3x8, f32x8, f32x8) {
    let entering = lt(d.dot(outward), f32x8::ZERO);
    (Vec3x8::select(entering, outward, -outward), entering.select(f32x8::ONE, ior), entering.select(ior, f32x8::ONE))
}

/// `prismatic_core::optics::fresnel::cos2_transmitted` per lane.
#[inline]
pub fn cos2_transmitted(cos_i: f32x8, n1: f32x8, n2: f32x8) -> f32x8 {
    let eta = n1 / n2;
    (n2 - n1) * (n2 + n1) / (n2 * n2) + eta * eta * cos_i * cos_i
}

/// `prismatic_core::optics::fresnel::fresnel` per lane.
#[inline]
pub fn fresnel(cos_i: f32x8, n1: f32x8, n2: f32x8) -> f32x8 {
    let cos_i = cos_i.max(f32x8::ZERO).min(f32x8::ONE);
    let cos2_t = cos2_transmitted(cos_i, n1, n2);
    let tir = !cos2_t.simd_gt(f32x8::ZERO);
    let cos_t = cos2_t.max(f32x8::ZERO).sqrt();
    let rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
    let rp = (n1 * cos_t - n2 * cos_i) / (n1 * cos_t + n2 * cos_i);
    let r = (f32x8::splat(0.5) * (rs * rs + rp * rp)).max(f32x8::ZERO).min(f32x8::ONE);
    n1.simd_eq(n2).select(f32x8::ZERO, tir.select(f32x8::ONE, r))
}

/// `prismatic_core::optics::fresnel::refract` per lane: (total internal reflection mask, direction).
#[inline]
pub fn refract(d: Vec3x8, n: Vec3x8, n1: f32x8, n2: f32x8) -> (f32x8, Vec3x8) {
    let eta = n1 / n2;
    let cos_i = (-d.dot(n)).max(f32x8::ZERO).min(f32x8::ONE);
    let cos2_t = cos2_transmitted(cos_i, n1, n2);
    let cos_t = cos2_t.max(f32x8::ZERO).sqrt();
    (lt(cos2_t, f32x8::ZERO), (d * eta + n * (eta * cos_i - cos_t)).normalize())
}
