//! Mesh triangles stored for Möller–Trumbore, the robust ray–triangle test,
//! and the rule that picks one hit among triangles hit at nearly the same
//! distance (at shared edges and vertices).

use crate::geometry::ray::Ray;
use crate::util::tolerance::BARYCENTRIC_EPS;
use alloc::vec::Vec;
use glam::Vec3;

/// One triangle, stored for Möller–Trumbore.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Triangle {
    /// First corner.
    pub v0: Vec3,
    /// Edge v1 − v0.
    pub e1: Vec3,
    /// Edge v2 − v0.
    pub e2: Vec3,
    /// Unit face normal (counter-clockwise winding).
    pub normal: Vec3,
}

impl Triangle {
    /// The corners' bounds, widened to hold every hit the widened test of
    /// [`intersect_triangle`] accepts (by [`BARYCENTRIC_EPS`] of the edges,
    /// and by the rounding of coordinates of this size, with margin).
    pub fn padded_bounds(&self) -> (Vec3, Vec3) {
        let corners = [self.v0, self.v0 + self.e1, self.v0 + self.e2];
        let lo = corners[0].min(corners[1]).min(corners[2]);
        let hi = corners[0].max(corners[1]).max(corners[2]);
        let size = self.e1.abs().max_element() + self.e2.abs().max_element();
        let magnitude = lo.abs().max(hi.abs()).max_element();
        let pad = 8.0 * BARYCENTRIC_EPS * size + 4e-6 * magnitude + 1e-30;
        (lo - Vec3::splat(pad), hi + Vec3::splat(pad))
    }

    /// The weights (b1, b2) of the second and third corners at `p`, a point
    /// on the triangle, by least squares (so a point a rounding error off
    /// the plane reads as the nearest point in it). Texture coordinates and
    /// vertex normals interpolate with them.
    #[inline]
    pub fn barycentrics(&self, p: Vec3) -> (f32, f32) {
        let d = p - self.v0;
        let (d11, d12, d22) = (self.e1.dot(self.e1), self.e1.dot(self.e2), self.e2.dot(self.e2));
        let (d1, d2) = (d.dot(self.e1), d.dot(self.e2));
        let inv = 1.0 / (d11 * d22 - d12 * d12);
        ((d22 * d1 - d12 * d2) * inv, (d11 * d2 - d12 * d1) * inv)
    }
}

/// Mesh triangles without the degenerate (zero-area) ones.
pub fn mesh_triangles(positions: &[Vec3], triangles: &[[u32; 3]]) -> Vec<Triangle> {
    numbered_mesh_triangles(positions, triangles).map(|(_, t)| t).collect()
}

/// The mesh's triangles that have an area, each with its index in `triangles`.
pub fn numbered_mesh_triangles<'a>(
    positions: &'a [Vec3],
    triangles: &'a [[u32; 3]],
) -> impl Iterator<Item = (u32, Triangle)> + 'a {
    triangles.iter().enumerate().filter_map(|(k, t)| {
        let [v0, v1, v2] = t.map(|i| positions[i as usize]);
        let (e1, e2) = (v1 - v0, v2 - v0);
        let n = e1.cross(e2);
        let scale = e1.length_squared().max(e2.length_squared());
        (n.length() > 1e-7 * scale && scale > 0.0).then(|| (k as u32, Triangle { v0, e1, e2, normal: n.normalize() }))
    })
}

/// Möller–Trumbore, two-sided, on the triangle widened by
/// [`BARYCENTRIC_EPS`] so that shared edges have no cracks; a ray that would
/// enter the triangle from within `skin` outside its plane misses it (see
/// `tolerance::surface_skin`). Returns `t` with `t_min < t < t_max`.
#[inline]
pub fn intersect_triangle(ray: &Ray, tri: &Triangle, t_min: f32, t_max: f32, skin: f32) -> Option<f32> {
    let p = ray.direction.cross(tri.e2);
    let det = tri.e1.dot(p);
    if det.abs() < 1e-12 {
        return None;
    }
    let height = tri.normal.dot(ray.origin - tri.v0);
    if height > 0.0 && height < skin && tri.normal.dot(ray.direction) < 0.0 {
        return None;
    }
    let inv = 1.0 / det;
    let s = ray.origin - tri.v0;
    let u = s.dot(p) * inv;
    let (lo, hi) = (-BARYCENTRIC_EPS, 1.0 + BARYCENTRIC_EPS);
    if !(lo..=hi).contains(&u) {
        return None;
    }
    let q = s.cross(tri.e1);
    let v = ray.direction.dot(q) * inv;
    if v < lo || u + v > hi {
        return None;
    }
    let t = tri.e2.dot(q) * inv;
    (t > t_min && t < t_max).then_some(t)
}

/// The nearest hit among a mesh's triangles, by a rule that does not depend
/// on the order in which they are tested (so a hierarchy may visit them in
/// any order, per ray or per packet, and every backend finds the same one).
///
/// A ray through an edge or a vertex hits every triangle there at the same
/// `t` up to rounding. Within the skin, a triangle the ray *enters* wins
/// over one it *leaves*, so that a ray entering a closed mesh through a
/// vertex is not taken to be leaving it: the result is the nearest entering
/// hit if it lies less than `skin` beyond the nearest leaving hit, else the
/// nearest leaving hit. Equal distances go to the lower triangle index.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NearestTriangle {
    /// The skin of the ray's origin.
    pub skin: f32,
    /// Nearest entering hit: (t, triangle index).
    pub entering: Option<(f32, u32)>,
    /// Nearest leaving hit: (t, triangle index).
    pub leaving: Option<(f32, u32)>,
}

impl NearestTriangle {
    /// No hit yet.
    #[inline]
    pub fn new(skin: f32) -> Self {
        NearestTriangle { skin, entering: None, leaving: None }
    }

    /// No hit farther than this can change the result.
    #[inline]
    pub fn reach(&self) -> f32 {
        let e = self.entering.map_or(f32::INFINITY, |h| h.0);
        let l = self.leaving.map_or(f32::INFINITY, |h| h.0 + self.skin);
        e.min(l)
    }

    /// Offers triangle `index`, hit at `t`, `entering` when against its normal.
    #[inline]
    pub fn offer(&mut self, t: f32, index: u32, entering: bool) {
        if t > self.reach() {
            return;
        }
        let best = if entering { &mut self.entering } else { &mut self.leaving };
        if best.is_none_or(|(bt, bi)| t < bt || (t == bt && index < bi)) {
            *best = Some((t, index));
        }
    }

    /// The winner: (t, triangle index).
    #[inline]
    pub fn result(&self) -> Option<(f32, u32)> {
        match (self.entering, self.leaving) {
            (Some(e), Some(l)) => Some(if e.0 < l.0 + self.skin { e } else { l }),
            (e, l) => e.or(l),
        }
    }
}
