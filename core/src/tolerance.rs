//! Named numerical tolerances of the core, each with the reason for its size.
//!
//! Shaders and backends take these constants from here so that every
//! implementation offsets rays and compares floats the same way.

/// Distance a new ray's origin is pushed off the surface it leaves, relative
/// to the magnitude of the hit point: f32 has 2^-23 ≈ 1.2e-7 relative
/// precision, and intersection error grows to a few hundred ulps at grazing
/// angles, so 2^-14 ≈ 6e-5 clears it with margin while staying far below any
/// feature size in a scene (thinnest wall we expect: 1e-3).
pub const SURFACE_OFFSET_REL: f32 = 6.1e-5;

/// Absolute floor of the surface offset, for points near the origin.
pub const SURFACE_OFFSET_ABS: f32 = 1e-5;

/// Photon throughput below which a view ray's contribution is dropped
/// (1/1000 of the pixel: below the 8-bit quantisation step of the output).
pub const MIN_VIEW_WEIGHT: f32 = 1e-3;

/// Offset for a point `p` on a surface: large enough to clear f32 error at
/// the magnitude of `p`.
#[inline]
pub fn surface_offset(p: glam::Vec3) -> f32 {
    SURFACE_OFFSET_ABS + SURFACE_OFFSET_REL * p.abs().max_element()
}
