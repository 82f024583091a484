//! Packet traversal of a mesh's hierarchy: the core's `MeshBvh::intersect`
//! and `hits_any` for eight rays. A node is visited while any lane can still
//! hit inside it; each lane offers its triangle hits to the core's
//! order-free nearest rule (`NearestTriangle`), so it finds the same hit as
//! the scalar traversal, whatever the other lanes made the packet visit.

use crate::ray::{RayX8, in_range, surface_skin};
use crate::simd::{Vec3x8, ge, gt, lt};
use prismatic_core::bvh::{BOX_MARGIN, BvhNode, MAX_DEPTH, MeshBvh};
use prismatic_core::geometry::Triangle;
use prismatic_core::tolerance::BARYCENTRIC_EPS;
use wide::f32x8;

/// `prismatic_core::bvh::inverse_direction` per lane.
#[inline]
fn inverse_direction(d: Vec3x8) -> Vec3x8 {
    let guard = |c: f32x8| {
        let tiny = f32x8::splat(1e-30);
        lt(c.abs(), tiny).select(tiny.flip_signs(c), c)
    };
    Vec3x8 { x: f32x8::ONE / guard(d.x), y: f32x8::ONE / guard(d.y), z: f32x8::ONE / guard(d.z) }
}

/// `prismatic_core::bvh::box_entry` per lane: (lanes that meet the box, entry distance).
#[inline]
fn box_entry(origin: Vec3x8, inv: Vec3x8, node: &BvhNode, limit: f32x8) -> (f32x8, f32x8) {
    let (lo, hi) = (Vec3x8::splat(node.lo), Vec3x8::splat(node.hi));
    let (a, b) = ((lo.x - origin.x) * inv.x, (hi.x - origin.x) * inv.x);
    let (c, d) = ((lo.y - origin.y) * inv.y, (hi.y - origin.y) * inv.y);
    let (e, f) = ((lo.z - origin.z) * inv.z, (hi.z - origin.z) * inv.z);
    let near = a.min(b).max(c.min(d)).max(e.min(f)).max(f32x8::ZERO);
    let far = a.max(b).min(c.max(d)).min(e.max(f));
    // As the scalar `near <= far && near <= limit`: false for NaN lanes (rays
    // from a point at infinity, in lanes a packet does not use).
    (ge(far, near) & ge(limit * f32x8::splat(BOX_MARGIN), near), near)
}

/// Visits the leaves any lane may hit before its limit, nearer child first
/// (by the nearest entry over the lanes). `leaf` tests a leaf's triangles
/// and returns the lanes' new limits (negative: the lane is done).
#[inline]
fn visit(bvh: &MeshBvh, ray: &RayX8, t_max: f32x8, mut leaf: impl FnMut(&BvhNode) -> f32x8) {
    let Some(root) = bvh.nodes.first() else { return };
    let inv = inverse_direction(ray.dir);
    let mut limit = t_max;
    if !box_entry(ray.origin, inv, root, limit).0.any() {
        return;
    }
    let nearest = |mask: f32x8, t: f32x8| {
        mask.select(t, f32x8::splat(f32::INFINITY)).as_array().iter().fold(f32::INFINITY, |m, &x| m.min(x))
    };
    let mut stack = [0u32; MAX_DEPTH];
    let mut depth = 0usize;
    let mut node = *root;
    loop {
        if node.count > 0 {
            limit = leaf(&node);
        } else {
            let (a, b) = (node.first, node.first + 1);
            let (na, nb) = (bvh.nodes[a as usize], bvh.nodes[b as usize]);
            let (ha, ta) = box_entry(ray.origin, inv, &na, limit);
            let (hb, tb) = box_entry(ray.origin, inv, &nb, limit);
            match (ha.any(), hb.any()) {
                (true, true) => {
                    let (near, far) = if nearest(hb, tb) < nearest(ha, ta) { (b, a) } else { (a, b) };
                    stack[depth] = far;
                    depth += 1;
                    node = bvh.nodes[near as usize];
                    continue;
                }
                (true, false) => {
                    node = na;
                    continue;
                }
                (false, true) => {
                    node = nb;
                    continue;
                }
                (false, false) => {}
            }
        }
        loop {
            if depth == 0 {
                return;
            }
            depth -= 1;
            let next = bvh.nodes[stack[depth] as usize];
            if box_entry(ray.origin, inv, &next, limit).0.any() {
                node = next;
                break;
            }
        }
    }
}

/// The nearest hit of each lane with `0 < t < t_max`: (mask, t, outward
/// normal, triangle index as a float).
#[inline]
pub fn intersect_mesh(bvh: &MeshBvh, ray: &RayX8, t_max: f32x8) -> (f32x8, f32x8, Vec3x8, f32x8) {
    let inf = f32x8::splat(f32::INFINITY);
    let skin = surface_skin(ray.origin);
    // `NearestTriangle` per lane: infinity stands for "none".
    let (mut te, mut ie, mut ne) = (inf, inf, Vec3x8::ZERO);
    let (mut tl, mut il, mut nl) = (inf, inf, Vec3x8::ZERO);
    visit(bvh, ray, t_max, |node| {
        for index in node.first..node.first + node.count {
            let tri = &bvh.triangles[index as usize];
            let (mask, t) = triangle(ray, tri, t_max, skin);
            if mask.any() {
                let reach = te.min(tl + skin);
                let n = Vec3x8::splat(tri.normal);
                let entering = lt(n.dot(ray.dir), f32x8::ZERO);
                let k = f32x8::splat(index as f32);
                let offered = mask & !gt(t, reach);
                let take_e = offered & entering & (lt(t, te) | (t.simd_eq(te) & lt(k, ie)));
                let take_l = offered & !entering & (lt(t, tl) | (t.simd_eq(tl) & lt(k, il)));
                te = take_e.select(t, te);
                ie = take_e.select(k, ie);
                ne = Vec3x8::select(take_e, n, ne);
                tl = take_l.select(t, tl);
                il = take_l.select(k, il);
                nl = Vec3x8::select(take_l, n, nl);
            }
        }
        te.min(tl + skin).min(t_max)
    });
    let pick_e = lt(te, tl + skin);
    let hit = lt(te, inf) | lt(tl, inf);
    (hit, pick_e.select(te, tl), Vec3x8::select(pick_e, ne, nl), hit.select(pick_e.select(ie, il), f32x8::ZERO))
}

/// Lanes that hit any triangle with `0 < t < t_max`.
#[inline]
pub fn mesh_hits_any(bvh: &MeshBvh, ray: &RayX8, t_max: f32x8) -> f32x8 {
    let skin = surface_skin(ray.origin);
    let mut blocked = f32x8::ZERO;
    visit(bvh, ray, t_max, |node| {
        for tri in &bvh.triangles[node.first as usize..(node.first + node.count) as usize] {
            blocked |= triangle(ray, tri, t_max, skin).0;
            if blocked.all() {
                break;
            }
        }
        blocked.select(f32x8::splat(-1.0), t_max)
    });
    blocked
}

/// `prismatic_core::triangle::intersect_triangle` per lane: (mask, t).
#[inline]
fn triangle(ray: &RayX8, tri: &Triangle, t_max: f32x8, skin: f32x8) -> (f32x8, f32x8) {
    let (e1, e2) = (Vec3x8::splat(tri.e1), Vec3x8::splat(tri.e2));
    let p = ray.dir.cross(e2);
    let det = e1.dot(p);
    let valid = !lt(det.abs(), f32x8::splat(1e-12));
    let inv = f32x8::ONE / det;
    let s = ray.origin - Vec3x8::splat(tri.v0);
    let u = s.dot(p) * inv;
    let q = s.cross(e1);
    let v = ray.dir.dot(q) * inv;
    let t = e2.dot(q) * inv;
    let (lo, hi) = (f32x8::splat(-BARYCENTRIC_EPS), f32x8::splat(1.0 + BARYCENTRIC_EPS));
    let inside = ge(u, lo) & !gt(u, hi) & ge(v, lo) & !gt(u + v, hi);
    let n = Vec3x8::splat(tri.normal);
    let height = n.dot(ray.origin - Vec3x8::splat(tri.v0));
    let in_skin = gt(height, f32x8::ZERO) & lt(height, skin) & lt(n.dot(ray.dir), f32x8::ZERO);
    (valid & !in_skin & inside & in_range(t, t_max), t)
}
