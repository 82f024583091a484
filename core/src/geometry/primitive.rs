//! Primitives ready for intersection and robust ray–primitive tests.
//!
//! Normals returned by intersections are geometric and point out of the
//! object (for planes and discs: along their stated normal); callers decide
//! the facing side with the sign of `dot(direction, normal)`.

use crate::geometry::bvh::MeshBvh;
use crate::util::math::{sin_cos_turns, sqrt};
use alloc::sync::Arc;
use alloc::vec::Vec;
use glam::Vec3;

pub use crate::geometry::ray::Ray;
pub use crate::geometry::triangle::{Triangle, mesh_triangles};

/// A plane `normal · x = offset` bounding a convex solid (inside where `<`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HalfSpace {
    /// Outward unit normal.
    pub normal: Vec3,
    /// Signed offset.
    pub offset: f32,
}

/// A shape prepared for intersection.
#[derive(Clone, Debug, PartialEq)]
pub enum Primitive {
    /// Sphere.
    Sphere {
        /// Centre.
        center: Vec3,
        /// Radius.
        radius: f32,
    },
    /// Two-sided infinite plane.
    Plane {
        /// A point on it.
        point: Vec3,
        /// Unit normal.
        normal: Vec3,
    },
    /// Disc with an optional hole.
    Disk {
        /// Centre.
        center: Vec3,
        /// Unit normal.
        normal: Vec3,
        /// Outer radius squared.
        radius2: f32,
        /// Hole radius squared.
        inner_radius2: f32,
    },
    /// Convex solid bounded by half-spaces (the prism): a ray entering
    /// through an edge hits exactly one of the faces that meet there, so no
    /// ray leaks between faces.
    Convex {
        /// Bounding planes.
        faces: Vec<HalfSpace>,
    },
    /// Triangle mesh (degenerate triangles removed) in a bounding volume
    /// hierarchy, shared: each pass's copy of the prepared scene and an
    /// unchanged mesh of an updated scene hold the same one.
    Mesh(Arc<MeshBvh>),
}

/// Nearest hit of a ray with a primitive: distance and outward unit normal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceHit {
    /// Ray parameter of the hit.
    pub t: f32,
    /// Outward geometric unit normal.
    pub normal: Vec3,
    /// A mesh's triangle hit (index into its hierarchy's `triangles`); 0 for other shapes.
    pub triangle: u32,
}

impl Primitive {
    /// The nearest hit with `t_min < t < t_max`.
    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<SurfaceHit> {
        match self {
            Primitive::Sphere { center, radius } => intersect_sphere(ray, *center, *radius, t_min, t_max),
            Primitive::Plane { point, normal } => {
                let t = plane_t(ray, *point, *normal)?;
                (t > t_min && t < t_max).then_some(SurfaceHit { t, normal: *normal, triangle: 0 })
            }
            Primitive::Disk { center, normal, radius2, inner_radius2 } => {
                let t = plane_t(ray, *center, *normal)?;
                if !(t > t_min && t < t_max) {
                    return None;
                }
                let d2 = (ray.at(t) - *center).length_squared();
                (d2 <= *radius2 && d2 >= *inner_radius2).then_some(SurfaceHit { t, normal: *normal, triangle: 0 })
            }
            Primitive::Convex { faces } => intersect_convex(ray, faces, t_min, t_max),
            Primitive::Mesh(bvh) => bvh.intersect(ray, t_min, t_max).map(|(t, triangle)| SurfaceHit {
                t,
                normal: bvh.triangles[triangle as usize].normal,
                triangle,
            }),
        }
    }

    /// Whether the ray meets the primitive with `t_min < t < t_max`
    /// (`intersect(..).is_some()`, stopping at a mesh's first triangle hit).
    pub fn hits(&self, ray: &Ray, t_min: f32, t_max: f32) -> bool {
        match self {
            Primitive::Mesh(bvh) => bvh.hits_any(ray, t_min, t_max),
            _ => self.intersect(ray, t_min, t_max).is_some(),
        }
    }

    /// A mesh primitive over `positions` and `triangles` (degenerate
    /// triangles left out); the hierarchy's `sources` index `triangles`.
    pub fn mesh(positions: &[Vec3], triangles: &[[u32; 3]]) -> Self {
        Primitive::Mesh(Arc::new(crate::geometry::bvh_build::build_mesh(positions, triangles)))
    }
}

#[inline]
fn plane_t(ray: &Ray, point: Vec3, normal: Vec3) -> Option<f32> {
    let denom = ray.direction.dot(normal);
    if denom.abs() < 1e-12 {
        return None;
    }
    Some((point - ray.origin).dot(normal) / denom)
}

/// Sphere intersection after Haines et al., "Precision Improvements for
/// Ray/Sphere Intersection" (Ray Tracing Gems, ch. 7): the discriminant is
/// computed from the distance of the centre to the ray, which keeps its
/// precision for far and for tangent rays. The normal is normalised, not
/// divided by the radius: a hit point a few ulps off the sphere gave a
/// normal a few ulps off unit length, the reflection a direction as far
/// off, and the next hit (solved for a unit direction) a point further off.
/// Inside a glass ball that grew about fivefold a bounce, so a view path
/// through its rim reached a false total internal reflection by its eighth
/// bounce, how soon depending on the rounding (an NVIDIA GPU lost 0.75 % of
/// the `sphere`'s visible points, see `docs/src/measurements/gpu.md`).
fn intersect_sphere(ray: &Ray, center: Vec3, radius: f32, t_min: f32, t_max: f32) -> Option<SurfaceHit> {
    let f = ray.origin - center;
    let b = f.dot(ray.direction);
    let perp = f - ray.direction * b;
    let disc = radius * radius - perp.length_squared();
    if disc < 0.0 {
        return None;
    }
    let c = f.length_squared() - radius * radius;
    let q = -b - crate::util::math::sqrt(disc).copysign(b);
    let (t0, t1) = if q == 0.0 { (0.0, 0.0) } else { (c / q, q) };
    let (near, far) = if t0 < t1 { (t0, t1) } else { (t1, t0) };
    let t = if near > t_min && near < t_max {
        near
    } else if far > t_min && far < t_max {
        far
    } else {
        return None;
    };
    Some(SurfaceHit { t, normal: (ray.at(t) - center).normalize(), triangle: 0 })
}

fn intersect_convex(ray: &Ray, faces: &[HalfSpace], t_min: f32, t_max: f32) -> Option<SurfaceHit> {
    let skin = crate::util::tolerance::surface_skin(ray.origin);
    let mut t_enter = f32::NEG_INFINITY;
    let mut t_exit = f32::INFINITY;
    let mut n_enter = Vec3::ZERO;
    let mut n_exit = Vec3::ZERO;
    for face in faces {
        let denom = face.normal.dot(ray.direction);
        let mut dist = face.offset - face.normal.dot(ray.origin);
        if denom < 0.0 && dist < 0.0 && dist > -skin {
            dist = 0.0; // within the skin: the face contains the origin (see `surface_skin`)
        }
        if denom == 0.0 {
            if dist < 0.0 {
                return None; // parallel and outside this face
            }
            continue;
        }
        let t = dist / denom;
        if denom < 0.0 {
            if t > t_enter {
                t_enter = t;
                n_enter = face.normal;
            }
        } else if t < t_exit {
            t_exit = t;
            n_exit = face.normal;
        }
    }
    if t_enter > t_exit {
        return None;
    }
    if t_enter > t_min && t_enter < t_max {
        Some(SurfaceHit { t: t_enter, normal: n_enter, triangle: 0 })
    } else if t_exit > t_min && t_exit < t_max {
        Some(SurfaceHit { t: t_exit, normal: n_exit, triangle: 0 })
    } else {
        None
    }
}

/// The prism's five bounding planes, outward.
pub fn prism_faces(vertices: [Vec3; 3], extrude: Vec3) -> Vec<HalfSpace> {
    let [a, b, c] = vertices;
    let centroid = (a + b + c) / 3.0 + extrude * 0.5;
    let mut faces = Vec::with_capacity(5);
    let mut push = |p: Vec3, n: Vec3| {
        let n = n.normalize();
        let n = if (centroid - p).dot(n) > 0.0 { -n } else { n };
        faces.push(HalfSpace { normal: n, offset: n.dot(p) });
    };
    let cap = (b - a).cross(c - a);
    push(a, cap);
    push(a + extrude, cap);
    for (p, q) in [(a, b), (b, c), (c, a)] {
        push(p, (q - p).cross(extrude));
    }
    faces
}

/// An orthonormal basis around unit `n` (Duff et al. 2017, branchless).
#[inline]
pub fn basis(n: Vec3) -> (Vec3, Vec3) {
    let sign = 1.0f32.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    (Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x), Vec3::new(b, sign + n.y * n.y * a, -n.y))
}

/// A unit direction at polar cosine `cos_t` around `axis`, azimuth `u · 2π`
/// (an emitter's cone, a projection map's, a diffuse bounce's).
#[inline]
pub fn cone_direction(axis: Vec3, cos_t: f32, u: f32) -> Vec3 {
    let sin_t = sqrt((1.0 - cos_t * cos_t).max(0.0));
    let (sin_phi, cos_phi) = sin_cos_turns(u);
    let (t, b) = basis(axis);
    (t * (sin_t * cos_phi) + b * (sin_t * sin_phi) + axis * cos_t).normalize()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sphere_hit_from_outside_and_inside() {
        let s = Primitive::Sphere { center: Vec3::ZERO, radius: 1.0 };
        let hit = s.intersect(&Ray::new(Vec3::new(0.0, 0.0, -5.0), Vec3::Z), 0.0, f32::INFINITY).unwrap();
        assert!((hit.t - 4.0).abs() < 1e-5 && (hit.normal + Vec3::Z).length() < 1e-5);
        let hit = s.intersect(&Ray::new(Vec3::ZERO, Vec3::Z), 0.0, f32::INFINITY).unwrap();
        assert!((hit.t - 1.0).abs() < 1e-6 && (hit.normal - Vec3::Z).length() < 1e-5);
    }

    #[test]
    fn prism_edges_do_not_leak() {
        let faces = prism_faces(
            [Vec3::new(-1.0, 0.0, -1.0), Vec3::new(1.0, 0.0, -1.0), Vec3::new(0.0, 1.7, -1.0)],
            Vec3::new(0.0, 0.0, 2.0),
        );
        let prism = Primitive::Convex { faces };
        // Rays aimed exactly at the apex edge and the base corners all hit.
        for target in [Vec3::new(0.0, 1.7, 0.0), Vec3::new(-1.0, 0.0, 0.0), Vec3::new(1.0, 0.0, 0.3)] {
            let origin = target + Vec3::new(0.3, 2.0, 0.1) * 3.0;
            let hit = prism.intersect(&Ray::new(origin, target - origin), 0.0, f32::INFINITY);
            assert!(hit.is_some(), "ray at {target} leaked");
        }
    }

    #[test]
    fn basis_is_orthonormal() {
        for n in [Vec3::X, Vec3::Y, -Vec3::Z, Vec3::new(0.3, -0.4, 0.5).normalize(), Vec3::new(0.0, 0.0, -1.0)] {
            let (t, b) = basis(n);
            assert!(t.dot(n).abs() < 1e-6 && b.dot(n).abs() < 1e-6 && t.dot(b).abs() < 1e-6);
            assert!((t.length() - 1.0).abs() < 1e-6 && (b.length() - 1.0).abs() < 1e-6);
        }
    }
}
