//! Normal maps: a texel's tangent-space normal turned into the world by the
//! surface's tangent frame at a hit (glTF's `normalTexture`). The frame is
//! the mesh's vertex tangents (glTF's `TANGENT`, or MikkTSpace's, which the
//! readers compute) interpolated across the triangle, or, for a mesh without
//! them, the direction of growing u on each triangle with the handedness of
//! its texture coordinates. The tilted normal then goes to
//! [`crate::geometry::shading::shading_normal`], which keeps it scatterable.

use crate::geometry::texture::TriangleUv;
use crate::geometry::triangle::Triangle;
use glam::{Vec3, Vec4};

/// A triangle's tangents, stored for interpolation: the first corner's,
/// the differences to the other two, and the bitangent's handedness.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TriangleTangents {
    /// At the first corner.
    pub t0: Vec3,
    /// Second corner's minus the first's.
    pub d1: Vec3,
    /// Third corner's minus the first's.
    pub d2: Vec3,
    /// +1 or −1: the bitangent is `cross(normal, tangent) · sign`.
    pub sign: f32,
}

impl TriangleTangents {
    /// From the three corners' tangents (glTF's `TANGENT`: `w` is ±1, the
    /// same at a triangle's corners for any mesh a tool writes; the first
    /// corner's is taken).
    pub fn from_vertices(corners: [Vec4; 3]) -> Self {
        let [a, b, c] = corners.map(|t| t.truncate());
        let sign = if corners[0].w < 0.0 { -1.0 } else { 1.0 };
        TriangleTangents { t0: a, d1: b - a, d2: c - a, sign }
    }

    /// The flat frame of `tri` from its texture coordinates `uv`: the
    /// tangent is the direction in which u grows (∂p/∂u), and the
    /// bitangent `cross(normal, tangent) · sign` points where v falls, up
    /// the image as glTF's normal maps have it. Zero tangent (the map then
    /// leaves the normal alone) where the coordinates span no area.
    pub fn from_uvs(tri: &Triangle, uv: &TriangleUv) -> Self {
        let (a, b) = (uv.du1, uv.du2);
        let det = a.x * b.y - b.x * a.y;
        let dp_du = (tri.e1 * b.y - tri.e2 * a.y) / det;
        let dp_dv = (tri.e2 * a.x - tri.e1 * b.x) / det;
        if det == 0.0 || !dp_du.is_finite() || !dp_dv.is_finite() {
            return TriangleTangents { sign: 1.0, ..TriangleTangents::default() };
        }
        let sign = if tri.normal.cross(dp_du).dot(-dp_dv) < 0.0 { -1.0 } else { 1.0 };
        TriangleTangents { t0: dp_du, d1: Vec3::ZERO, d2: Vec3::ZERO, sign }
    }

    /// The interpolated tangent at `p`, a point on `tri`; not of unit length.
    #[inline]
    pub fn at(&self, tri: &Triangle, p: Vec3) -> Vec3 {
        let (b1, b2) = tri.barycentrics(p);
        self.t0 + self.d1 * b1 + self.d2 * b2
    }
}

/// The world normal a normal map's `texel` (linear channels in [0, 1])
/// stands for, on a surface of unit normal `normal` with tangent `tangent`
/// (any length) and handedness `sign`; `scale` multiplies the texel's X and
/// Y (glTF's `normalTexture.scale`). The tangent is first made
/// perpendicular to the normal. `normal` itself where the tangent lies along
/// it (within [`MIN_TANGENT_SHARE`] of its length) or vanishes, or the texel
/// encodes no direction ([`MIN_MAPPED_LENGTH`]).
#[inline]
pub fn mapped_normal(normal: Vec3, tangent: Vec3, sign: f32, texel: Vec3, scale: f32) -> Vec3 {
    let across = tangent - normal * normal.dot(tangent);
    let length = across.length();
    // Comparisons that a NaN fails too.
    let spans = length > MIN_TANGENT_SHARE * tangent.length();
    if !spans {
        return normal;
    }
    let t = across / length;
    let b = normal.cross(t) * sign;
    let m = texel * 2.0 - Vec3::ONE;
    let mapped = t * (m.x * scale) + b * (m.y * scale) + normal * m.z;
    let length = mapped.length();
    let points = length > MIN_MAPPED_LENGTH;
    if !points {
        return normal;
    }
    mapped / length
}

/// The least share of a tangent's length across the normal for it to
/// give a frame (below: the tangent lies along the normal).
pub const MIN_TANGENT_SHARE: f32 = 1e-4;

/// The least length of a texel's vector in the frame for it to give a
/// direction (mid grey, 128/255 in each channel, has about 0.007).
pub const MIN_MAPPED_LENGTH: f32 = 1e-3;

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec2;

    /// A unit square's lower triangle in the xy-plane, facing +z, with the
    /// image upright on it: u along +x, v down the image (along −y).
    fn upright() -> (Triangle, TriangleUv) {
        let tri = Triangle { v0: Vec3::ZERO, e1: Vec3::X, e2: Vec3::Y, normal: Vec3::Z };
        (tri, TriangleUv::new([Vec2::new(0.0, 1.0), Vec2::new(1.0, 1.0), Vec2::new(0.0, 0.0)]))
    }

    #[test]
    fn an_upright_image_has_its_tangent_along_u_and_its_bitangent_up_the_image() {
        let (tri, uv) = upright();
        let frame = TriangleTangents::from_uvs(&tri, &uv);
        assert_eq!((frame.t0, frame.sign), (Vec3::X, 1.0));
        // A mirrored image (u along −x) keeps the bitangent up by turning the sign.
        let mirrored = TriangleUv::new([Vec2::new(1.0, 1.0), Vec2::new(0.0, 1.0), Vec2::new(1.0, 0.0)]);
        let frame = TriangleTangents::from_uvs(&tri, &mirrored);
        assert_eq!((frame.t0, frame.sign), (-Vec3::X, -1.0));
        assert_eq!(Vec3::Z.cross(frame.t0) * frame.sign, Vec3::Y);
        // Coordinates on a line span nothing: no frame.
        let line = TriangleUv::new([Vec2::ZERO, Vec2::X, Vec2::X * 2.0]);
        assert_eq!(TriangleTangents::from_uvs(&tri, &line).t0, Vec3::ZERO);
    }

    #[test]
    fn texels_tilt_the_normal_toward_the_tangent_and_the_bitangent() {
        let flat = Vec3::new(0.5, 0.5, 1.0);
        assert_eq!(mapped_normal(Vec3::Z, Vec3::X, 1.0, flat, 1.0), Vec3::Z);
        // 45° toward +X (the tangent) and toward +Y (the bitangent, up the image).
        let tilt = 0.5 + 0.5 * core::f32::consts::FRAC_1_SQRT_2;
        let along_u = mapped_normal(Vec3::Z, Vec3::X, 1.0, Vec3::new(tilt, 0.5, tilt), 1.0);
        assert!((along_u - Vec3::new(1.0, 0.0, 1.0).normalize()).length() < 1e-6, "{along_u}");
        let up = mapped_normal(Vec3::Z, Vec3::X, 1.0, Vec3::new(0.5, tilt, tilt), 1.0);
        assert!((up - Vec3::new(0.0, 1.0, 1.0).normalize()).length() < 1e-6, "{up}");
        // The handedness turns the bitangent; scale 0 is the plain surface.
        let down = mapped_normal(Vec3::Z, Vec3::X, -1.0, Vec3::new(0.5, tilt, tilt), 1.0);
        assert!((down - Vec3::new(0.0, -1.0, 1.0).normalize()).length() < 1e-6, "{down}");
        assert_eq!(mapped_normal(Vec3::Z, Vec3::X, 1.0, Vec3::new(tilt, 0.5, tilt), 0.0), Vec3::Z);
    }

    #[test]
    fn a_tangent_off_the_surface_is_made_perpendicular_and_a_useless_one_is_ignored() {
        let tilt = 0.5 + 0.5 * core::f32::consts::FRAC_1_SQRT_2;
        let texel = Vec3::new(tilt, 0.5, tilt);
        let slanted = mapped_normal(Vec3::Z, Vec3::new(2.0, 0.0, 5.0), 1.0, texel, 1.0);
        assert!((slanted - Vec3::new(1.0, 0.0, 1.0).normalize()).length() < 1e-6, "{slanted}");
        assert_eq!(mapped_normal(Vec3::Z, Vec3::Z, 1.0, texel, 1.0), Vec3::Z);
        assert_eq!(mapped_normal(Vec3::Z, Vec3::ZERO, 1.0, texel, 1.0), Vec3::Z);
        assert_eq!(mapped_normal(Vec3::Z, Vec3::X, 1.0, Vec3::splat(0.5), 1.0), Vec3::Z);
    }

    #[test]
    fn vertex_tangents_interpolate_and_keep_the_first_corners_handedness() {
        let (tri, _) = upright();
        let frame = TriangleTangents::from_vertices([Vec4::new(1.0, 0.0, 0.0, -1.0), Vec4::Y.with_w(1.0), Vec4::X]);
        assert_eq!(frame.sign, -1.0);
        assert!((frame.at(&tri, Vec3::new(0.0, 0.5, 0.0)) - Vec3::new(1.0, 0.0, 0.0)).length() < 1e-6);
        assert!((frame.at(&tri, Vec3::new(0.5, 0.0, 0.0)) - Vec3::new(0.5, 0.5, 0.0)).length() < 1e-6);
    }
}
