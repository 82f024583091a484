//! Eight rays as a packet, and the per-lane tolerances every packet
//! intersection test shares.

use crate::simd::{Vec3x8, gt, lt};
use prismatic_core::util::tolerance::{SURFACE_OFFSET_ABS, SURFACE_OFFSET_REL, SURFACE_SKIN_FACTOR};
use wide::f32x8;

/// Eight rays.
#[derive(Clone, Copy, Debug)]
pub struct RayX8 {
    /// Origins.
    pub origin: Vec3x8,
    /// Unit directions.
    pub dir: Vec3x8,
}

impl RayX8 {
    /// Points at parameter `t`.
    #[inline]
    pub fn at(&self, t: f32x8) -> Vec3x8 {
        self.origin + self.dir * t
    }
}

/// `prismatic_core::util::tolerance::surface_skin` per lane.
#[inline]
pub fn surface_skin(origin: Vec3x8) -> f32x8 {
    let offset = f32x8::splat(SURFACE_OFFSET_ABS) + f32x8::splat(SURFACE_OFFSET_REL) * origin.abs_max_element();
    f32x8::splat(SURFACE_SKIN_FACTOR) * offset
}

/// Search limits: `limit` in the lanes of `mask`, −1 in the others. A
/// negative limit finds nothing and enters no box, so a lane with nothing
/// to look for (an ended path, an unlit point) costs a traversal nothing.
#[inline]
pub fn limit_where(mask: f32x8, limit: f32x8) -> f32x8 {
    mask.select(limit, f32x8::splat(-1.0))
}

#[inline]
pub fn in_range(t: f32x8, t_max: f32x8) -> f32x8 {
    gt(t, f32x8::ZERO) & lt(t, t_max)
}
