//! Packet traversal of a mesh's hierarchy: the core's `MeshBvh::intersect`
//! and `hits_any` for eight rays, over the tree's four-wide form. A box is
//! entered while any lane can still hit inside it (lanes whose limit is
//! negative, ended paths, never can); each lane offers its triangle hits to
//! the core's order-free nearest rule (`NearestTriangle`), so it finds the
//! same hit as the scalar traversal, whatever the other lanes made the
//! packet visit.

use crate::ray::{RayX8, in_range, surface_skin};
use crate::simd::{Vec3x8, ge, gt, lt};
use prismatic_core::Vec3;
use prismatic_core::geometry::bvh::{BOX_MARGIN, MAX_DEPTH, MeshBvh, WIDTH};

use prismatic_core::geometry::primitive::Triangle;
use prismatic_core::util::tolerance::BARYCENTRIC_EPS;
use wide::f32x8;

/// Slots a traversal may hold: each level of the tree leaves at most
/// WIDTH − 1 behind.
const STACK: usize = MAX_DEPTH * (WIDTH - 1);

/// `prismatic_core::geometry::bvh::inverse_direction` per lane.
#[inline]
fn inverse_direction(d: Vec3x8) -> Vec3x8 {
    let guard = |c: f32x8| {
        let tiny = f32x8::splat(1e-30);
        lt(c.abs(), tiny).select(tiny.flip_signs(c), c)
    };
    Vec3x8 { x: f32x8::ONE / guard(d.x), y: f32x8::ONE / guard(d.y), z: f32x8::ONE / guard(d.z) }
}

/// `prismatic_core::geometry::bvh::box_entry` per lane, less the limit: where each
/// lane enters the box, NaN for lanes whose line misses it.
#[inline]
fn box_entry(origin: Vec3x8, inv: Vec3x8, lo: Vec3, hi: Vec3) -> f32x8 {
    let (lo, hi) = (Vec3x8::splat(lo), Vec3x8::splat(hi));
    let (a, b) = ((lo.x - origin.x) * inv.x, (hi.x - origin.x) * inv.x);
    let (c, d) = ((lo.y - origin.y) * inv.y, (hi.y - origin.y) * inv.y);
    let (e, f) = ((lo.z - origin.z) * inv.z, (hi.z - origin.z) * inv.z);
    // `fast_min`/`fast_max` equal the scalar `min`/`max` on the finite
    // distances of finite rays; they skip the NaN guard the others pay for.
    let near = a.fast_min(b).fast_max(c.fast_min(d)).fast_max(e.fast_min(f)).fast_max(f32x8::ZERO);
    let far = a.fast_max(b).fast_min(c.fast_max(d)).fast_min(e.fast_max(f));
    ge(far, near).select(near, f32x8::splat(f32::NAN))
}

/// The scalar test's `near <= limit · BOX_MARGIN` (false where `entry` is NaN).
#[inline]
fn within(entry: f32x8, limit: f32x8) -> f32x8 {
    ge(limit * f32x8::splat(BOX_MARGIN), entry)
}

/// Visits the leaves any lane may hit before its limit, over the tree's
/// wide form: a node's four boxes are tested together, and the slots some
/// lane meets are taken nearest first (by the entry of the first lane that
/// meets each: cheaper than the nearest over the lanes, and as good for
/// packets whose lanes travel together). `leaf` tests a leaf's triangles
/// (first, count) and returns the lanes' new limits (negative: the lane is
/// done).
#[inline]
fn visit(bvh: &MeshBvh, ray: &RayX8, t_max: f32x8, mut leaf: impl FnMut(u32, u32) -> f32x8) {
    if bvh.wide.is_empty() {
        return;
    }
    let inv = inverse_direction(ray.dir);
    let mut limit = t_max;
    // Slots still to visit, as wide node × WIDTH + slot.
    let mut stack = [0u32; STACK];
    let mut depth = 0usize;
    let mut node = 0usize;
    loop {
        // Expand `node`: its slots that some lane meets, nearest first.
        let n = &bvh.wide[node];
        let mut met = [(0.0f32, 0u32); WIDTH];
        let mut len = 0;
        for s in 0..n.slots as usize {
            let entry = box_entry(ray.origin, inv, n.lo[s], n.hi[s]);
            let lanes = within(entry, limit).to_bitmask();
            if lanes != 0 {
                // The entry of the first lane that meets the box orders the slots.
                let nearest = entry.as_array()[lanes.trailing_zeros() as usize];
                // Insertion by entry, nearest first.
                let mut k = len;
                while k > 0 && met[k - 1].0 > nearest {
                    met[k] = met[k - 1];
                    k -= 1;
                }
                met[k] = (nearest, (node * WIDTH + s) as u32);
                len += 1;
            }
        }
        let mut next = None;
        if len > 0 {
            for &(_, slot) in met[1..len].iter().rev() {
                stack[depth] = slot;
                depth += 1;
            }
            next = Some(met[0].1);
        }
        // Take slots until one is a node to expand.
        loop {
            let slot = match next.take() {
                Some(slot) => slot,
                None => {
                    // Pop the next slot some lane can still reach.
                    if depth == 0 {
                        return;
                    }
                    depth -= 1;
                    let slot = stack[depth];
                    let w = &bvh.wide[slot as usize / WIDTH];
                    let s = slot as usize % WIDTH;
                    if !within(box_entry(ray.origin, inv, w.lo[s], w.hi[s]), limit).any() {
                        continue;
                    }
                    slot
                }
            };
            let w = &bvh.wide[slot as usize / WIDTH];
            let s = slot as usize % WIDTH;
            if w.count[s] == 0 {
                node = w.first[s] as usize;
                break;
            }
            limit = leaf(w.first[s], w.count[s]);
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
    visit(bvh, ray, t_max, |first, count| {
        for index in first..first + count {
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
    visit(bvh, ray, t_max, |first, count| {
        for tri in &bvh.triangles[first as usize..(first + count) as usize] {
            blocked |= triangle(ray, tri, t_max, skin).0;
            if blocked.all() {
                break;
            }
        }
        blocked.select(f32x8::splat(-1.0), t_max)
    });
    blocked
}

/// `prismatic_core::geometry::triangle::intersect_triangle` per lane: (mask, t).
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

#[cfg(test)]
mod tests {
    use super::*;
    use prismatic_conformance::scenes::sphere_mesh;
    use prismatic_core::geometry::bvh_build::build_mesh;
    use prismatic_core::geometry::ray::Ray;
    use prismatic_core::model::scene::Shape;
    use prismatic_core::optics::scatter::offset_origin;
    use prismatic_core::util::rng::random_f32;

    /// The conformance suite's closed sphere mesh, 4 · rings² triangles.
    fn sphere(rings: u32) -> MeshBvh {
        let Shape::Mesh { positions, triangles, .. } = sphere_mesh(Vec3::ZERO, 1.0, rings) else {
            unreachable!("sphere_mesh makes a mesh")
        };
        build_mesh(&positions, &triangles)
    }

    /// Packets of rays from outside (nearly parallel, as band packets are,
    /// or unrelated), from inside, and leaving the surface to either side,
    /// with unbounded, finite and ended (−1) limits: every lane's hit is the
    /// scalar traversal's, bit for bit.
    #[test]
    fn packet_hits_are_the_scalar_traversals_bit_for_bit() {
        let bvh = sphere(60);
        let mut hits = 0;
        for k in 0..3000u32 {
            let mut dimension = 0;
            let mut u = || {
                dimension += 1;
                random_f32(11, k, dimension) * 2.0 - 1.0
            };
            let mut origins = [Vec3::ZERO; 8];
            let mut dirs = [Vec3::ZERO; 8];
            let mut limits = [f32::INFINITY; 8];
            let shared = Vec3::new(u(), u(), u()).normalize() * 3.0;
            for i in 0..8 {
                let random_dir = Vec3::new(u(), u(), u()).normalize();
                (origins[i], dirs[i]) = match k % 4 {
                    0 => (shared, (-shared + 0.02 * random_dir).normalize()),
                    1 => (Vec3::new(u(), u(), u()) * 3.0, random_dir),
                    2 => (Vec3::new(u(), u(), u()) * 0.5, random_dir),
                    _ => {
                        let tri = &bvh.triangles[((u() * 0.5 + 0.5) * (bvh.triangles.len() - 1) as f32) as usize];
                        let (a, b) = ((u() * 0.5 + 0.5) * 0.5, (u() * 0.5 + 0.5) * 0.5);
                        let p = tri.v0 + a * tri.e1 + b * tri.e2;
                        (offset_origin(p, tri.normal, random_dir), random_dir)
                    }
                };
                limits[i] = match (u() * 4.0) as i32 {
                    0 => -1.0,
                    1 => (u() + 1.0) * 1.5,
                    _ => f32::INFINITY,
                };
            }
            let packet = RayX8 { origin: Vec3x8::from_lanes(&origins), dir: Vec3x8::from_lanes(&dirs) };
            let t_max = f32x8::new(limits);
            let (mask, t, normal, triangle) = intersect_mesh(&bvh, &packet, t_max);
            let blocked = mesh_hits_any(&bvh, &packet, t_max).to_bitmask();
            let (mask, t, triangle) = (mask.to_bitmask(), t.to_array(), triangle.to_array());
            for i in 0..8 {
                let ray = Ray { origin: origins[i], direction: dirs[i] };
                let want = bvh.intersect(&ray, 0.0, limits[i]);
                let got = (mask & (1 << i) != 0).then(|| (t[i], triangle[i] as u32));
                assert_eq!(
                    got.map(|(t, k)| (t.to_bits(), k)),
                    want.map(|(t, k)| (t.to_bits(), k)),
                    "packet {k} lane {i}"
                );
                if let Some((_, k)) = want {
                    assert_eq!(normal.lane(i), bvh.triangles[k as usize].normal);
                    hits += 1;
                }
                assert_eq!(blocked & (1 << i) != 0, bvh.hits_any(&ray, 0.0, limits[i]), "packet {k} lane {i}");
            }
        }
        assert!(hits > 8000, "{hits} hits: the rays must meet the mesh");
    }
}
