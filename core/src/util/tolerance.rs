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

/// A ray's origin lies up to one surface offset off the surface it leaves;
/// at an edge or a vertex that puts it just outside the neighbouring faces.
/// A face (or triangle) the ray would enter from less than this distance
/// outside its plane is taken to contain the origin already, so the ray does
/// not "enter" a second time through the face next to the one it just
/// crossed. Twice the offset: the offset is along one face's normal, and
/// its distance to any other face's plane is at most the offset itself.
pub const SURFACE_SKIN_FACTOR: f32 = 2.0;

/// How far outside a triangle (in barycentric coordinates) a hit still
/// counts. Möller–Trumbore computes u and v with a few ulps of error, so a
/// ray through a shared edge or vertex can miss every triangle there by
/// 1e-7 and slip into a closed mesh unseen. Widening each triangle by 1e-6
/// of its size (8 ulps of 1) closes those cracks; neighbours then overlap
/// by as much, which the nearest-hit rule resolves.
pub const BARYCENTRIC_EPS: f32 = 1e-6;

/// Photon throughput below which a view ray's contribution is dropped
/// (1/1000 of the pixel: below the 8-bit quantisation step of the output).
pub const MIN_VIEW_WEIGHT: f32 = 1e-3;

/// How far (relative to its distance from the eye) the camera's first hit
/// on the way to a stored photon may lie from the photon and still be the
/// surface it landed on. The photon's position and the camera ray's hit
/// each carry f32 error of a few ulps, growing as 1/cos at grazing angles
/// (1e-5 at 0.6° from the surface); 1e-4 clears that, and a different
/// surface 1e-4 of the distance in front of a lit one is below a pixel's
/// depth resolution in any scene we render.
pub const CONNECTION_REL: f32 = 1e-4;

/// How far (relative to the pixel's depth) a photon may lie from the plane
/// of the surface an engine's pixel sees and still count in the caustic
/// layer ([`crate::render::layer`]). Wider than [`CONNECTION_REL`]: the
/// engine's depth buffer and normals carry their own rounding (a 32-bit
/// depth buffer's reversed-Z keeps about 1e-6 of the depth; a normal
/// prepass stores 10 or 16 bits a channel, a plane tilted by 1e-3 rad),
/// and on a curved receiver the plane at the pixel's centre leaves the
/// surface by (footprint)²/2R within the pixel. An engine's occluder closer
/// than 2e-3 of the depth in front of a lit surface (2 mm at 1 m) does
/// not hide the caustic.
pub const LAYER_PLANE_REL: f32 = 2e-3;

/// The skin of [`SURFACE_SKIN_FACTOR`] around a ray starting at `origin`.
#[inline]
pub fn surface_skin(origin: glam::Vec3) -> f32 {
    SURFACE_SKIN_FACTOR * surface_offset(origin)
}

/// Offset for a point `p` on a surface: large enough to clear f32 error at
/// the magnitude of `p`.
#[inline]
pub fn surface_offset(p: glam::Vec3) -> f32 {
    SURFACE_OFFSET_ABS + SURFACE_OFFSET_REL * p.abs().max_element()
}
