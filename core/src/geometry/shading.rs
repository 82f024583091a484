//! Smooth shading: a mesh's vertex normals (glTF's `NORMAL`) interpolated
//! across each triangle, and the rule that bends the interpolated normal
//! where it disagrees with the flat triangle too much for a ray to scatter
//! about it. Mirrors, metals and glass scatter about this normal, so a
//! tessellated ball reflects and focuses as the round ball it stands for;
//! which side of the surface a ray is on stays the triangle's.
//!
//! The bend is the one Keller et al. use in Iray ("The Iray Light Transport
//! Simulation and Rendering System", 2017, §A.3): where the mirror image
//! of the incoming ray about the interpolated normal would go below the
//! triangle, that image is lifted to just above it and the normal becomes
//! the half vector between the ray's reverse and the lifted image. The
//! result faces the incoming ray as the triangle does, and a mirror
//! reflection about it never leaves through the surface.

use crate::geometry::triangle::Triangle;
use crate::util::math::sqrt;
use glam::Vec3;

/// The least cosine, with the triangle's normal, of a ray mirrored about a
/// bent normal: it leaves a little above the surface, not along it.
pub const MIN_REFLECTED_LIFT: f32 = 0.01;

/// A triangle's vertex normals, stored for interpolation: the first
/// corner's, and the differences to the other two (unit at the corners).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TriangleNormals {
    /// At the first corner.
    pub n0: Vec3,
    /// Second corner's minus the first's.
    pub d1: Vec3,
    /// Third corner's minus the first's.
    pub d2: Vec3,
}

impl TriangleNormals {
    /// From the three corners' normals (any length but zero).
    pub fn new(corners: [Vec3; 3]) -> Self {
        let [a, b, c] = corners.map(Vec3::normalize);
        TriangleNormals { n0: a, d1: b - a, d2: c - a }
    }

    /// The interpolated normal at `p`, a point on `tri`
    /// ([`Triangle::barycentrics`]); not of unit length.
    #[inline]
    pub fn at(&self, tri: &Triangle, p: Vec3) -> Vec3 {
        let (b1, b2) = tri.barycentrics(p);
        self.n0 + self.d1 * b1 + self.d2 * b2
    }
}

/// The normal a ray arriving along unit `direction` scatters about, at a
/// point whose triangle has outward unit normal `geometric` and whose
/// vertex normals interpolate to `interpolated` there: the interpolated
/// normal (unit), bent as the module says where the ray's mirror image
/// about it would rise less than [`MIN_REFLECTED_LIFT`] above the triangle.
/// Outward like `geometric`; `geometric` itself where the two point to
/// opposite sides (normals that disagree with the winding) or the
/// interpolation vanishes.
#[inline]
pub fn shading_normal(direction: Vec3, geometric: Vec3, interpolated: Vec3) -> Vec3 {
    let agreement = interpolated.dot(geometric);
    if agreement.is_nan() || agreement <= 0.0 {
        return geometric;
    }
    let length = interpolated.length();
    // Both normals turned to the side the ray comes from.
    let side = if direction.dot(geometric) < 0.0 { 1.0 } else { -1.0 };
    let (facing, smooth) = (geometric * side, interpolated * (side / length));
    let mirrored = direction - smooth * (2.0 * direction.dot(smooth));
    let lift = mirrored.dot(facing);
    if lift >= MIN_REFLECTED_LIFT {
        return smooth * side;
    }
    // The image turned up toward the triangle's normal until it rises by the least lift.
    let along = (mirrored - facing * lift).normalize_or(facing);
    let lifted = along * sqrt(1.0 - MIN_REFLECTED_LIFT * MIN_REFLECTED_LIFT) + facing * MIN_REFLECTED_LIFT;
    (lifted - direction).normalize() * side
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::util::rng::random_f32;

    fn reflect(d: Vec3, n: Vec3) -> Vec3 {
        d - n * (2.0 * d.dot(n))
    }

    #[test]
    fn normals_interpolate_across_a_triangle() {
        let tri = Triangle { v0: Vec3::ZERO, e1: Vec3::X, e2: Vec3::Y, normal: Vec3::Z };
        let normals = TriangleNormals::new([Vec3::Z, Vec3::new(1.0, 0.0, 1.0), Vec3::new(0.0, 2.0, 2.0)]);
        assert_eq!(normals.at(&tri, Vec3::ZERO), Vec3::Z);
        assert!((normals.at(&tri, Vec3::X) - Vec3::new(1.0, 0.0, 1.0).normalize()).length() < 1e-6);
        let middle = normals.at(&tri, Vec3::new(0.5, 0.5, 0.0));
        let want = (Vec3::new(1.0, 0.0, 1.0).normalize() + Vec3::new(0.0, 1.0, 1.0).normalize()) * 0.5;
        assert!((middle - want).length() < 1e-6);
    }

    #[test]
    fn an_agreeing_normal_is_used_as_interpolated_on_either_side() {
        let geometric = Vec3::Z;
        let smooth = Vec3::new(0.1, 0.0, 1.0);
        for direction in [Vec3::new(0.0, 0.0, -1.0), Vec3::new(0.0, 0.3, 1.0).normalize()] {
            let n = shading_normal(direction, geometric, smooth * 3.0);
            assert!((n - smooth.normalize()).length() < 1e-6, "{direction}: {n}");
        }
    }

    #[test]
    fn disagreeing_or_vanishing_normals_give_the_triangles() {
        let d = Vec3::new(0.0, 0.0, -1.0);
        assert_eq!(shading_normal(d, Vec3::Z, -Vec3::Z), Vec3::Z);
        assert_eq!(shading_normal(d, Vec3::Z, Vec3::X), Vec3::Z);
        assert_eq!(shading_normal(d, Vec3::Z, Vec3::ZERO), Vec3::Z);
        assert_eq!(shading_normal(d, Vec3::Z, Vec3::splat(f32::NAN)), Vec3::Z);
    }

    /// Any ray, any geometric normal, any interpolated normal on the same
    /// side: the normal is unit, faces the ray as the triangle does, and
    /// the ray mirrored about it leaves above the triangle (bent to exactly
    /// the least lift where it had to be).
    #[test]
    fn a_reflection_about_the_shading_normal_never_leaves_through_the_surface() {
        let unit = |k: u32| {
            let r = |d: u32| random_f32(7, k, d) * 2.0 - 1.0;
            Vec3::new(r(0), r(1), r(2)).normalize()
        };
        let mut bent = 0;
        for k in 0..20_000 {
            let (d, g) = (unit(3 * k), unit(3 * k + 1));
            let s = unit(3 * k + 2);
            let s = if s.dot(g) > 0.0 { s } else { -s };
            let n = shading_normal(d, g, s);
            assert!((n.length() - 1.0).abs() < 1e-5, "unit: {n}");
            assert!(n.dot(g) > 0.0, "outward like the triangle's: {n} vs {g}");
            let facing = if d.dot(g) < 0.0 { g } else { -g };
            assert!(d.dot(n) * d.dot(g) > 0.0 || d.dot(g) == 0.0, "the ray meets it from the triangle's side");
            let lift = reflect(d, n).dot(facing);
            assert!(lift >= MIN_REFLECTED_LIFT * 0.99, "d {d} g {g} s {s}: lift {lift}");
            if (n - s).length() > 1e-6 {
                bent += 1;
                assert!((lift - MIN_REFLECTED_LIFT).abs() < 1e-4, "bent only as far as needed: {lift}");
            }
        }
        assert!(bent > 1000, "random normals need bending often: {bent}");
    }
}
