//! A spot light's cone: full intensity inside the inner angle, glTF's
//! smooth edge out to the outer one, the cone's integral and the polar
//! angle of a photon drawn in proportion to the intensity.

use crate::util::math::{cos, powf, radians};

/// A spot's cone by the cosines of its half-angles.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpotCone {
    /// cos of the outer half-angle (no light beyond it).
    pub cos_outer: f32,
    /// cos of the inner half-angle (full intensity within it); equal to
    /// `cos_outer` for a hard edge.
    pub cos_inner: f32,
}

impl SpotCone {
    /// The cone of half-angles `outer_deg` and `inner_deg` (≤ outer).
    pub fn new(outer_deg: f32, inner_deg: f32) -> Self {
        SpotCone { cos_outer: cos(radians(outer_deg)), cos_inner: cos(radians(inner_deg.min(outer_deg))) }
    }

    /// The intensity at polar cosine `c` relative to the axis: 1 inside the
    /// inner cone, 0 beyond the outer, and between them glTF's recommended
    /// edge x², x = (c − cos_outer)/(cos_inner − cos_outer).
    #[inline]
    pub fn falloff(&self, c: f32) -> f32 {
        if c < self.cos_outer {
            0.0
        } else if c >= self.cos_inner {
            1.0
        } else {
            let x = (c - self.cos_outer) / (self.cos_inner - self.cos_outer);
            x * x
        }
    }

    /// ∫ falloff dω / 2π over the sphere: (1 − cos_inner) + (cos_inner −
    /// cos_outer)/3 (a hard edge: 1 − cos_outer). A spot of power Φ has the
    /// intensity Φ / (2π · this) on its axis.
    #[inline]
    pub fn measure(&self) -> f32 {
        (1.0 - self.cos_inner) + (self.cos_inner - self.cos_outer) / 3.0
    }

    /// The polar cosine of a direction drawn with density ∝ falloff from
    /// the uniform number `u` (monotone in `u`, so a stratified `u` stays
    /// stratified): t = u · measure from the axis down, uniform inside the
    /// inner cone (c = 1 − t, the hard-edged spot's formula) and through
    /// the edge's inverse CDF beyond it, c = cos_outer + w ∛(1 − 3t′/w),
    /// w = cos_inner − cos_outer, t′ = t − (1 − cos_inner).
    #[inline]
    pub fn sample_cos(&self, u: f32) -> f32 {
        let t = u * self.measure();
        let core = 1.0 - self.cos_inner;
        if t <= core {
            return 1.0 - t;
        }
        let w = self.cos_inner - self.cos_outer;
        self.cos_outer + w * powf((1.0 - 3.0 * (t - core) / w).max(0.0), 1.0 / 3.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_hard_edge_is_the_uniform_cone() {
        let cone = SpotCone::new(30.0, 30.0);
        assert_eq!(cone.measure(), 1.0 - cone.cos_outer);
        for u in [0.0, 0.3, 0.999] {
            assert_eq!(cone.sample_cos(u), 1.0 - u * (1.0 - cone.cos_outer));
        }
        assert_eq!((cone.falloff(cone.cos_outer), cone.falloff(cone.cos_outer - 1e-6)), (1.0, 0.0));
    }

    /// Drawn cosines follow the falloff: the share below each cosine
    /// against the integral of the falloff, by a midpoint rule.
    #[test]
    fn drawn_directions_follow_the_soft_edge() {
        let cone = SpotCone::new(40.0, 25.0);
        let n = 20_000;
        let drawn: Vec<f32> = (0..n).map(|i| cone.sample_cos((i as f32 + 0.5) / n as f32)).collect();
        assert!(drawn.windows(2).all(|w| w[0] >= w[1]), "monotone in u");
        for k in 1..10 {
            let c = cone.cos_outer + (1.0 - cone.cos_outer) * k as f32 / 10.0;
            let share = drawn.iter().filter(|&&x| x < c).count() as f32 / n as f32;
            let steps = 2000;
            let h = (c - cone.cos_outer) / steps as f32;
            let below: f32 = (0..steps).map(|j| cone.falloff(cone.cos_outer + (j as f32 + 0.5) * h) * h).sum();
            assert!((share - below / cone.measure()).abs() < 2e-3, "below {c}: {share} vs {}", below / cone.measure());
        }
    }
}
