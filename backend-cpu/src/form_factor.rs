//! Packet twin of `prismatic_core::geometry::form_factor`: what eight
//! points see of one triangle, by Lambert's formula over the triangle
//! clipped to each point's hemisphere.
//!
//! Lanes keep no corner lists: the clipped polygon's edges are each
//! original edge's part above the tangent plane, plus the horizon edge
//! from where the outline leaves the hemisphere to where it comes back, so
//! every lane sums the same four masked terms. The order of the sum
//! differs from the scalar twin's, so results agree to rounding.

use crate::simd::{Vec3x8, gt};
use glam::Vec3;
use prismatic_core::util::tolerance::{SURFACE_OFFSET_ABS, SURFACE_OFFSET_REL};
use wide::f32x8;

/// `triangle_view` for eight points `p` (unit normals `n`): each lane's
/// projected solid angle of the triangle's part above its tangent plane,
/// zero where the point is not in front of the triangle
/// (`form_factor::in_front_of`), and that part's centre.
pub fn triangle_view(p: Vec3x8, n: Vec3x8, v: [Vec3; 3]) -> (f32x8, Vec3x8) {
    let front = (v[1] - v[0]).cross(v[2] - v[0]).normalize();
    let offset = f32x8::splat(SURFACE_OFFSET_ABS) + f32x8::splat(SURFACE_OFFSET_REL) * p.abs_max_element();
    let in_front = gt((p - Vec3x8::splat(v[0])).dot(Vec3x8::splat(front)), offset);
    let corner = v.map(|c| Vec3x8::splat(c) - p);
    let height = corner.map(|c| c.dot(n));
    let above = height.map(|h| gt(h, f32x8::ZERO));
    let (mut sum, mut centre, mut count) = (f32x8::ZERO, Vec3x8::ZERO, f32x8::ZERO);
    let (mut exit, mut entry) = (Vec3x8::ZERO, Vec3x8::ZERO);
    for i in 0..3 {
        let j = (i + 1) % 3;
        let (x, y) = (corner[i], corner[j]);
        let crossing = x + (y - x) * (height[i] / (height[i] - height[j]));
        let (leaves, enters) = (above[i] & !above[j], !above[i] & above[j]);
        exit = Vec3x8::select(leaves, crossing, exit);
        entry = Vec3x8::select(enters, crossing, entry);
        // The edge's part above the plane.
        let start = Vec3x8::select(above[i], x, crossing);
        let end = Vec3x8::select(above[j], y, crossing);
        sum += (above[i] | above[j]).select(edge_term(start, end, n), f32x8::ZERO);
        centre = centre
            + Vec3x8::select(above[i], x, Vec3x8::ZERO)
            + Vec3x8::select(leaves | enters, crossing, Vec3x8::ZERO);
        count += (above[i] & f32x8::ONE) + ((leaves | enters) & f32x8::ONE);
    }
    let crosses = !(above[0] & above[1] & above[2]) & (above[0] | above[1] | above[2]);
    sum += crosses.select(edge_term(exit, entry, n), f32x8::ZERO);
    let seen = in_front & gt(count, f32x8::splat(2.0));
    let angle = seen.select(f32x8::splat(0.5) * sum.abs(), f32x8::ZERO);
    (angle, Vec3x8::select(seen, p + centre / count.max(f32x8::ONE), p))
}

/// Θ (n · γ̂) of the edge x → y seen from the origin: masked to zero where
/// the edge has no length or points at the origin.
#[inline]
fn edge_term(x: Vec3x8, y: Vec3x8, n: Vec3x8) -> f32x8 {
    let c = x.cross(y);
    let sin_len = c.length_squared().sqrt();
    let term = sin_len.atan2(x.dot(y)) * c.dot(n) / sin_len;
    gt(sin_len, f32x8::ZERO).select(term, f32x8::ZERO)
}

#[cfg(test)]
mod tests {
    use super::*;
    use prismatic_core::geometry::form_factor::{in_front_of, triangle_view as scalar};
    use prismatic_core::util::rng::random_f32;

    /// Random triangles over random points and normals, straddling the
    /// horizon, behind and in front: the packet agrees with the scalar twin.
    #[test]
    fn eight_lanes_agree_with_the_scalar_twin() {
        for k in 0..200u32 {
            let r = |d: u32| 2.0 * random_f32(3, k, d) - 1.0;
            let v = [0, 3, 6].map(|d| Vec3::new(r(d), r(d + 1), r(d + 2)) * 2.0);
            let p: [Vec3; 8] = core::array::from_fn(|i| Vec3::new(r(10 + 4 * i as u32), r(11 + 4 * i as u32), r(12)));
            let n: [Vec3; 8] = core::array::from_fn(|i| Vec3::new(r(40 + i as u32), r(50 + i as u32), 0.5).normalize());
            let (angle, centre) = triangle_view(Vec3x8::from_lanes(&p), Vec3x8::from_lanes(&n), v);
            let angle = angle.to_array();
            for i in 0..8 {
                let want = scalar(p[i], n[i], v);
                let want_angle = if in_front_of(p[i], v) { want.projected_solid_angle } else { 0.0 };
                // Terms of order 1 that cancel to a small angle: a floor of a few ulps of π.
                let tol = 1e-5 * want_angle + 2e-6;
                assert!((angle[i] - want_angle).abs() <= tol, "{k}/{i}: {} vs {want_angle}", angle[i]);
                if want_angle > 0.0 {
                    assert!((centre.lane(i) - want.centre).length() < 1e-5 * (1.0 + want.centre.length()), "{k}/{i}");
                }
            }
        }
    }
}
