//! Packet ray–scene intersection: the core's `Primitive::intersect` and
//! `PreparedScene::intersect`, eight rays at a time, operation for operation.

use crate::bvh::{intersect_mesh, mesh_hits_any};
use crate::ray::{RayX8, in_range, surface_skin};
use crate::simd::{Vec3x8, ge, gt, lt};
use prismatic_core::Vec3;
use prismatic_core::geometry::primitive::{HalfSpace, Primitive};
use prismatic_core::plan::prepared::PreparedScene;
use wide::f32x8;

/// The nearest hits of eight rays: `object` is −1 where a ray hit nothing.
#[derive(Clone, Copy, Debug)]
pub struct HitX8 {
    /// Distance (the search limit where nothing was hit).
    pub t: f32x8,
    /// Outward unit normal.
    pub normal: Vec3x8,
    /// Object index as a float (exact for any realistic scene), −1 for none.
    pub object: f32x8,
    /// A mesh's triangle hit as a float (exact up to `MAX_MESH_TRIANGLES`), else 0.
    pub triangle: f32x8,
}

/// Nearest hit of each ray with the scene closer than `t_max` (per lane).
#[inline]
pub fn intersect_scene(scene: &PreparedScene, ray: &RayX8, t_max: f32x8) -> HitX8 {
    let mut hit = HitX8 { t: t_max, normal: Vec3x8::ZERO, object: f32x8::splat(-1.0), triangle: f32x8::ZERO };
    for (k, prim) in scene.primitives.iter().enumerate() {
        let (mask, t, normal, triangle) = intersect_primitive(prim, ray, hit.t);
        if mask.any() {
            hit.t = mask.select(t, hit.t);
            hit.normal = Vec3x8::select(mask, normal, hit.normal);
            hit.object = mask.select(f32x8::splat(k as f32), hit.object);
            hit.triangle = mask.select(triangle, hit.triangle);
        }
    }
    hit
}

/// The normals that the rays of `mask`, arriving along `dir` at `point`,
/// scatter about at `hit`'s mirrors, metals and glass (and that diffuse
/// surfaces take their lights' cosines with): the core's
/// `PreparedScene::scattering_normal_at` for the lanes on meshes with
/// vertex normals or a normal map, the hit's normal elsewhere.
pub fn scattering_normals(scene: &PreparedScene, hit: &HitX8, point: Vec3x8, dir: Vec3x8, mask: f32x8) -> Vec3x8 {
    let (objects, bits) = (hit.object.to_array(), mask.to_bitmask());
    let smooth = |i: usize| bits & (1 << i) != 0 && objects[i] >= 0.0 && scene.bends_normals(objects[i] as usize);
    if !(0..8).any(smooth) {
        return hit.normal;
    }
    let triangles = hit.triangle.to_array();
    let normals: [Vec3; 8] = core::array::from_fn(|i| {
        let n = hit.normal.lane(i);
        if !smooth(i) {
            return n;
        }
        scene.scattering_normal_at(objects[i] as usize, triangles[i] as u32, point.lane(i), n, dir.lane(i))
    });
    Vec3x8::from_lanes(&normals)
}

/// Lanes with something on the segment from `origin` along `dir` before `dist`.
#[inline]
pub fn occluded(scene: &PreparedScene, ray: &RayX8, dist: f32x8) -> f32x8 {
    let mut blocked = f32x8::ZERO;
    for prim in &scene.primitives {
        blocked |= match prim {
            Primitive::Mesh(bvh) => mesh_hits_any(bvh, ray, dist),
            _ => intersect_primitive(prim, ray, dist).0,
        };
        if blocked.all() {
            break;
        }
    }
    blocked
}

/// Hits with `0 < t < t_max`: (mask, t, outward normal, a mesh's triangle as a float, else 0).
#[inline]
fn intersect_primitive(prim: &Primitive, ray: &RayX8, t_max: f32x8) -> (f32x8, f32x8, Vec3x8, f32x8) {
    let (mask, t, normal) = match prim {
        Primitive::Sphere { center, radius } => sphere(ray, Vec3x8::splat(*center), *radius, t_max),
        Primitive::Plane { point, normal } => {
            let n = Vec3x8::splat(*normal);
            let (valid, t) = plane_t(ray, Vec3x8::splat(*point), n);
            (valid & in_range(t, t_max), t, n)
        }
        Primitive::Disk { center, normal, radius2, inner_radius2 } => {
            let (c, n) = (Vec3x8::splat(*center), Vec3x8::splat(*normal));
            let (valid, t) = plane_t(ray, c, n);
            let d2 = (ray.at(t) - c).length_squared();
            let inside = !gt(d2, f32x8::splat(*radius2)) & ge(d2, f32x8::splat(*inner_radius2));
            (valid & in_range(t, t_max) & inside, t, n)
        }
        Primitive::Convex { faces } => convex(ray, faces, t_max),
        Primitive::Mesh(bvh) => return intersect_mesh(bvh, ray, t_max),
    };
    (mask, t, normal, f32x8::ZERO)
}

#[inline]
fn plane_t(ray: &RayX8, point: Vec3x8, normal: Vec3x8) -> (f32x8, f32x8) {
    let denom = ray.dir.dot(normal);
    let valid = !lt(denom.abs(), f32x8::splat(1e-12));
    (valid, (point - ray.origin).dot(normal) / denom)
}

#[inline]
fn sphere(ray: &RayX8, center: Vec3x8, radius: f32, t_max: f32x8) -> (f32x8, f32x8, Vec3x8) {
    let f = ray.origin - center;
    let b = f.dot(ray.dir);
    let perp = f - ray.dir * b;
    let r = f32x8::splat(radius);
    let disc = r * r - perp.length_squared();
    let valid = !lt(disc, f32x8::ZERO);
    let c = f.length_squared() - r * r;
    let q = -b - disc.sqrt().flip_signs(b);
    let q_zero = q.simd_eq(f32x8::ZERO);
    let t0 = q_zero.select(f32x8::ZERO, c / q);
    let t1 = q_zero.select(f32x8::ZERO, q);
    let swap = lt(t0, t1);
    let (near, far) = (swap.select(t0, t1), swap.select(t1, t0));
    let near_ok = in_range(near, t_max);
    let t = near_ok.select(near, far);
    let mask = valid & (near_ok | in_range(far, t_max));
    (mask, t, (ray.at(t) - center).normalize())
}

#[inline]
fn convex(ray: &RayX8, faces: &[HalfSpace], t_max: f32x8) -> (f32x8, f32x8, Vec3x8) {
    let skin = surface_skin(ray.origin);
    let mut t_enter = f32x8::splat(f32::NEG_INFINITY);
    let mut t_exit = f32x8::splat(f32::INFINITY);
    // Which face limits each lane, as a float index: normals are looked up once at the end.
    let mut f_enter = f32x8::ZERO;
    let mut f_exit = f32x8::ZERO;
    let mut outside_parallel = f32x8::ZERO;
    for (k, face) in faces.iter().enumerate() {
        let n = Vec3x8::splat(face.normal);
        let denom = n.dot(ray.dir);
        let dist = f32x8::splat(face.offset) - n.dot(ray.origin);
        // Within the skin outside a face it would enter: the face contains the origin.
        let in_skin = lt(denom, f32x8::ZERO) & lt(dist, f32x8::ZERO) & gt(dist, -skin);
        let dist = in_skin.select(f32x8::ZERO, dist);
        let parallel = denom.simd_eq(f32x8::ZERO);
        outside_parallel |= parallel & lt(dist, f32x8::ZERO);
        let t = dist / denom;
        let entering = !parallel & lt(denom, f32x8::ZERO);
        let exiting = !parallel & !lt(denom, f32x8::ZERO);
        let k = f32x8::splat(k as f32);
        let new_enter = entering & gt(t, t_enter);
        t_enter = new_enter.select(t, t_enter);
        f_enter = new_enter.select(k, f_enter);
        let new_exit = exiting & lt(t, t_exit);
        t_exit = new_exit.select(t, t_exit);
        f_exit = new_exit.select(k, f_exit);
    }
    let valid = !outside_parallel & !gt(t_enter, t_exit);
    let enter_ok = in_range(t_enter, t_max);
    let exit_ok = in_range(t_exit, t_max);
    let mask = valid & (enter_ok | exit_ok);
    let face = enter_ok.select(f_enter, f_exit);
    let mut normal = Vec3x8::ZERO;
    for (k, f) in faces.iter().enumerate() {
        normal = Vec3x8::select(face.simd_eq(f32x8::splat(k as f32)), Vec3x8::splat(f.normal), normal);
    }
    (mask, enter_ok.select(t_enter, t_exit), normal)
}
