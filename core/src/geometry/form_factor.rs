//! How much of a point's cosine-weighted hemisphere a triangle covers:
//! Lambert's closed form for a polygon, clipped to the hemisphere.

use crate::util::math::{atan2, sqrt};
use crate::util::tolerance::surface_offset;
use glam::Vec3;

/// What a point sees of a triangle: the projected solid angle of its part
/// above the point's tangent plane, and that part's centre.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriangleView {
    /// ∫ cos θ dω over the visible part (0 to π): a Lambertian emitter of
    /// radiance L there gives irradiance L times this (π times the
    /// point-to-polygon form factor).
    pub projected_solid_angle: f32,
    /// The mean of the visible part's corners (where a shadow ray aims).
    pub centre: Vec3,
}

/// Is `p` in front of triangle `v` (on the side its winding faces, by
/// more than a ray origin's offset: a point on the triangle itself is not)?
#[inline]
pub fn in_front_of(p: Vec3, v: [Vec3; 3]) -> bool {
    let front = (v[1] - v[0]).cross(v[2] - v[0]).normalize();
    (p - v[0]).dot(front) > surface_offset(p)
}

/// [`TriangleView`] of triangle `v` from `p` with unit normal `n`, by
/// Lambert's formula ½ Σ Θᵢ (n · γ̂ᵢ) over the edges of the triangle clipped
/// to the half-space above p's tangent plane (at most four corners), where
/// Θᵢ is the angle an edge subtends at p and γ̂ᵢ the unit normal of the
/// plane through p and the edge. Exact for any triangle and either winding.
pub fn triangle_view(p: Vec3, n: Vec3, v: [Vec3; 3]) -> TriangleView {
    let mut corners = [Vec3::ZERO; 4];
    let mut count = 0;
    for i in 0..3 {
        let (a, b) = (v[i] - p, v[(i + 1) % 3] - p);
        let (ha, hb) = (a.dot(n), b.dot(n));
        if ha > 0.0 {
            corners[count] = a;
            count += 1;
        }
        if (ha > 0.0) != (hb > 0.0) {
            corners[count] = a + (b - a) * (ha / (ha - hb));
            count += 1;
        }
    }
    if count < 3 {
        return TriangleView { projected_solid_angle: 0.0, centre: p };
    }
    let mut sum = 0.0;
    let mut centre = Vec3::ZERO;
    for i in 0..count {
        let (a, b) = (corners[i], corners[(i + 1) % count]);
        centre += a;
        let c = a.cross(b);
        let sin_len = sqrt(c.length_squared());
        if sin_len > 0.0 {
            sum += atan2(sin_len, a.dot(b)) * c.dot(n) / sin_len;
        }
    }
    TriangleView { projected_solid_angle: 0.5 * sum.abs(), centre: p + centre / count as f32 }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::util::rng::random_f32;
    use core::f32::consts::PI;

    /// A rectangle a × b parallel to the receiver at height h, the point
    /// under one corner: π F with F = (1/2π)[A/√(1+A²) atan(B/√(1+A²)) +
    /// B/√(1+B²) atan(A/√(1+B²))], A = a/h, B = b/h (the textbook form factor).
    fn corner_rectangle(a: f32, b: f32, h: f32) -> f32 {
        let (x, y) = (a / h, b / h);
        let (sx, sy) = (sqrt(1.0 + x * x), sqrt(1.0 + y * y));
        0.5 * (x / sx * (y / sx).atan() + y / sy * (x / sy).atan())
    }

    fn quad(p: Vec3, n: Vec3, q: [Vec3; 4]) -> f32 {
        let (a, b) = (triangle_view(p, n, [q[0], q[1], q[2]]), triangle_view(p, n, [q[0], q[2], q[3]]));
        a.projected_solid_angle + b.projected_solid_angle
    }

    #[test]
    fn a_rectangle_over_a_corner_matches_the_textbook_form_factor() {
        for (a, b, h) in [(1.0, 1.0, 1.0), (2.0, 0.5, 0.3), (0.1, 0.2, 5.0), (10.0, 10.0, 0.01)] {
            let q = [Vec3::new(0.0, 0.0, h), Vec3::new(a, 0.0, h), Vec3::new(a, b, h), Vec3::new(0.0, b, h)];
            let got = quad(Vec3::ZERO, Vec3::Z, q);
            let want = corner_rectangle(a, b, h);
            assert!((got - want).abs() <= 1e-5 * want.max(1e-3), "{a}×{b} at {h}: {got} vs {want}");
        }
    }

    #[test]
    fn a_huge_emitter_above_covers_the_whole_hemisphere() {
        let s = 1e4;
        let q = [Vec3::new(-s, -s, 1.0), Vec3::new(s, -s, 1.0), Vec3::new(s, s, 1.0), Vec3::new(-s, s, 1.0)];
        assert!((quad(Vec3::ZERO, Vec3::Z, q) - PI).abs() < 1e-3);
    }

    #[test]
    fn a_triangle_below_or_in_the_tangent_plane_is_not_seen() {
        let t = [Vec3::new(0.0, 0.0, -1.0), Vec3::new(1.0, 0.0, -1.0), Vec3::new(0.0, 1.0, -2.0)];
        assert_eq!(triangle_view(Vec3::ZERO, Vec3::Z, t).projected_solid_angle, 0.0);
        let flat = [Vec3::new(1.0, 0.0, 0.0), Vec3::new(2.0, 0.0, 0.0), Vec3::new(1.0, 1.0, 0.0)];
        assert_eq!(triangle_view(Vec3::ZERO, Vec3::Z, flat).projected_solid_angle, 0.0);
    }

    /// Does the ray from the origin along `d` cross triangle `v` (Möller–Trumbore)?
    fn hits_triangle(d: Vec3, v: [Vec3; 3]) -> bool {
        let (e1, e2) = (v[1] - v[0], v[2] - v[0]);
        let q = d.cross(e2);
        let det = e1.dot(q);
        let s = -v[0] / det;
        let (u, r) = (s.dot(q), s.cross(e1));
        let w = d.dot(r);
        u >= 0.0 && w >= 0.0 && u + w <= 1.0 && e2.dot(r) > 0.0
    }

    /// Clipped or not, the closed form agrees with a Monte-Carlo estimate
    /// of ∫ max(cos θ, 0) dω (cosine-weighted directions that hit the triangle, times π).
    #[test]
    fn random_triangles_straddling_the_horizon_match_a_monte_carlo_estimate() {
        let n = Vec3::new(0.3, -0.2, 1.0).normalize();
        let (t, b) = crate::geometry::primitive::basis(n);
        for k in 0..8u32 {
            let r = |d: u32| 2.0 * random_f32(7, k, d) - 1.0;
            let v = [0, 3, 6].map(|d| Vec3::new(r(d), r(d + 1), r(d + 2) * 0.8 + 0.3));
            let want = triangle_view(Vec3::ZERO, n, v).projected_solid_angle;
            let samples = 200_000u32;
            let mut hits = 0u32;
            for i in 0..samples {
                let (u1, u2) = (random_f32(11 + k, i, 0), random_f32(11 + k, i, 1));
                let (s, c) = crate::util::math::sin_cos_turns(u2);
                let rr = sqrt(u1);
                let d = t * (rr * c) + b * (rr * s) + n * sqrt(1.0 - u1);
                if hits_triangle(d, v) {
                    hits += 1;
                }
            }
            let got = PI * hits as f32 / samples as f32;
            let sigma = PI * sqrt((got / PI) * (1.0 - got / PI) / samples as f32);
            assert!((got - want).abs() <= 5.0 * sigma + 1e-4, "triangle {k}: closed form {want}, Monte Carlo {got}");
        }
    }
}
