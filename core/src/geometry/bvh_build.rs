//! Building a mesh's [`MeshBvh`]: with `std`, obvhs's PLOC builder with
//! reinsertion (multi-threaded, surface-area quality); without `std`, or
//! when a tree would be deeper than [`MAX_DEPTH`](crate::geometry::bvh::MAX_DEPTH), a median split on the
//! longest axis of the triangles' centres. A mesh whose vertices moved
//! keeps its tree, refitted. Every tree gets its four-wide form
//! ([`collapse`]).

use crate::geometry::bvh::{BvhNode, MeshBvh, WIDTH, WideNode};
use crate::geometry::triangle::{Triangle, numbered_mesh_triangles};
use alloc::vec::Vec;
use glam::Vec3;

/// Triangles per leaf of the median split.
const MEDIAN_LEAF: usize = 4;

/// The hierarchy over `triangles` (reordered into leaf order; `sources`
/// says where each came from).
pub fn build(triangles: Vec<Triangle>) -> MeshBvh {
    if triangles.is_empty() {
        return MeshBvh::default();
    }
    #[cfg(feature = "std")]
    {
        let bvh = sah::build(&triangles);
        if depth(&bvh.nodes) <= crate::geometry::bvh::MAX_DEPTH {
            return bvh;
        }
    }
    median_split(triangles)
}

/// The hierarchy over a mesh's triangles that have an area; its `sources`
/// index `triangles`.
pub fn build_mesh(positions: &[Vec3], triangles: &[[u32; 3]]) -> MeshBvh {
    let (numbers, kept): (Vec<u32>, Vec<Triangle>) = numbered_mesh_triangles(positions, triangles).unzip();
    let mut bvh = build(kept);
    for s in &mut bvh.sources {
        *s = numbers[*s as usize];
    }
    bvh
}

/// `bvh` over its mesh with the vertices moved to `positions`: every
/// triangle recomputed through its source, every box refitted from the
/// leaves up. The tree keeps its shape, so a large deformation slows the
/// traversal, never changes a hit. `None` when the triangles that have an
/// area are not the ones the tree holds (a triangle collapsed or unfolded):
/// build anew.
pub fn refit(bvh: &MeshBvh, positions: &[Vec3], triangles: &[[u32; 3]]) -> Option<MeshBvh> {
    let mut moved: Vec<Option<Triangle>> = alloc::vec![None; triangles.len()];
    let mut kept = 0;
    for (k, t) in numbered_mesh_triangles(positions, triangles) {
        moved[k as usize] = Some(t);
        kept += 1;
    }
    if kept != bvh.sources.len() {
        return None;
    }
    let tris: Vec<Triangle> = bvh.sources.iter().map(|&k| moved[k as usize]).collect::<Option<_>>()?;
    // Parents before children in `order`: refit in reverse, children first.
    let mut order = Vec::with_capacity(bvh.nodes.len());
    let mut stack = Vec::from([0u32]);
    while let Some(i) = stack.pop() {
        order.push(i);
        let n = bvh.nodes[i as usize];
        if n.count == 0 {
            stack.extend([n.first, n.first + 1]);
        }
    }
    let mut nodes = bvh.nodes.clone();
    for &i in order.iter().rev() {
        let n = nodes[i as usize];
        let (lo, hi) = if n.count > 0 {
            bounds(tris[n.first as usize..(n.first + n.count) as usize].iter())
        } else {
            let (a, b) = (nodes[n.first as usize], nodes[n.first as usize + 1]);
            (a.lo.min(b.lo), a.hi.max(b.hi))
        };
        nodes[i as usize] = BvhNode { lo, hi, ..n };
    }
    Some(tree(nodes, tris, bvh.sources.clone()))
}

/// The tree of binary `nodes` over `triangles` (in leaf order, each from
/// `sources` in the list it was built from), with its wide form.
fn tree(nodes: Vec<BvhNode>, triangles: Vec<Triangle>, sources: Vec<u32>) -> MeshBvh {
    let wide = collapse(&nodes);
    MeshBvh { nodes, triangles, sources, wide }
}

/// The wide tree over binary `nodes` (root first); node 0 is the root's
/// slots. Empty for an empty tree.
pub fn collapse(nodes: &[BvhNode]) -> Vec<WideNode> {
    if nodes.is_empty() {
        return Vec::new();
    }
    let empty =
        WideNode { lo: [Vec3::ZERO; WIDTH], hi: [Vec3::ZERO; WIDTH], first: [0; WIDTH], count: [0; WIDTH], slots: 0 };
    let mut wide = Vec::with_capacity(nodes.len() / 3 + 1);
    wide.push(empty);
    // (binary node whose subtree a wide node holds, that wide node).
    let mut todo = Vec::from([(0u32, 0usize)]);
    while let Some((binary, at)) = todo.pop() {
        let root = nodes[binary as usize];
        let mut held = [binary; WIDTH];
        let mut len = 1;
        if root.count == 0 {
            held[..2].copy_from_slice(&[root.first, root.first + 1]);
            len = 2;
        }
        // Open the inner slot with the largest box until four are held.
        while len < WIDTH {
            let widest = (0..len)
                .filter(|&s| nodes[held[s] as usize].count == 0)
                .max_by(|&a, &b| area(&nodes[held[a] as usize]).total_cmp(&area(&nodes[held[b] as usize])));
            let Some(s) = widest else { break };
            let first = nodes[held[s] as usize].first;
            held[s] = first;
            held[len] = first + 1;
            len += 1;
        }
        let mut node = WideNode { slots: len as u32, ..empty };
        for (s, &b) in held[..len].iter().enumerate() {
            let n = nodes[b as usize];
            (node.lo[s], node.hi[s], node.count[s]) = (n.lo, n.hi, n.count);
            node.first[s] = if n.count > 0 {
                n.first
            } else {
                wide.push(empty);
                todo.push((b, wide.len() - 1));
                (wide.len() - 1) as u32
            };
        }
        wide[at] = node;
    }
    wide
}

/// Half a box's surface area.
fn area(n: &BvhNode) -> f32 {
    let d = (n.hi - n.lo).max(Vec3::ZERO);
    d.x * d.y + d.y * d.z + d.z * d.x
}

/// Inner nodes on the longest path from the root to a leaf.
#[cfg(any(feature = "std", test))]
fn depth(nodes: &[BvhNode]) -> usize {
    let mut deepest = 0;
    let mut stack = Vec::from([(0u32, 0usize)]);
    while let Some((i, d)) = stack.pop() {
        let n = nodes[i as usize];
        if n.count == 0 {
            stack.extend([(n.first, d + 1), (n.first + 1, d + 1)]);
        } else {
            deepest = deepest.max(d);
        }
    }
    deepest
}

fn bounds<'a>(tris: impl Iterator<Item = &'a Triangle>) -> (Vec3, Vec3) {
    tris.map(Triangle::padded_bounds)
        .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), (a, b)| (lo.min(a), hi.max(b)))
}

fn centre(t: &Triangle) -> Vec3 {
    t.v0 + (t.e1 + t.e2) / 3.0
}

/// Halves the centres' longest extent by count, down to [`MEDIAN_LEAF`]
/// triangles: depth ⌈log₂(n / 4)⌉, far below [`MAX_DEPTH`].
fn median_split(triangles: Vec<Triangle>) -> MeshBvh {
    let mut nodes = Vec::with_capacity(2 * triangles.len() / MEDIAN_LEAF + 1);
    let centres: Vec<Vec3> = triangles.iter().map(centre).collect();
    let mut order: Vec<u32> = (0..triangles.len() as u32).collect();
    let leaf_bounds = |order: &[u32]| bounds(order.iter().map(|&i| &triangles[i as usize]));
    let (lo, hi) = leaf_bounds(&order);
    nodes.push(BvhNode { lo, hi, first: 0, count: order.len() as u32 });
    let mut todo = Vec::from([0usize]);
    while let Some(i) = todo.pop() {
        let BvhNode { first, count, .. } = nodes[i];
        if (count as usize) <= MEDIAN_LEAF {
            continue;
        }
        let part = &mut order[first as usize..(first + count) as usize];
        let (clo, chi) = part.iter().fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), &k| {
            (lo.min(centres[k as usize]), hi.max(centres[k as usize]))
        });
        let axis = (chi - clo).max_position();
        let half = part.len() / 2;
        part.select_nth_unstable_by(half, |&a, &b| centres[a as usize][axis].total_cmp(&centres[b as usize][axis]));
        let child = nodes.len() as u32;
        for (start, len) in [(first, half as u32), (first + half as u32, count - half as u32)] {
            let (lo, hi) = leaf_bounds(&order[start as usize..(start + len) as usize]);
            nodes.push(BvhNode { lo, hi, first: start, count: len });
        }
        nodes[i].first = child;
        nodes[i].count = 0;
        todo.extend([child as usize, child as usize + 1]);
    }
    let triangles = order.iter().map(|&i| triangles[i as usize]).collect();
    tree(nodes, triangles, order)
}

#[cfg(feature = "std")]
mod sah {
    //! obvhs's builder over the triangles' padded boxes.
    use super::*;
    use obvhs::BvhBuildParams;
    use obvhs::aabb::Aabb;
    use obvhs::bvh2::builder::build_bvh2;

    pub fn build(triangles: &[Triangle]) -> MeshBvh {
        let boxes: Vec<Aabb> = triangles
            .iter()
            .map(|t| {
                let (lo, hi) = t.padded_bounds();
                Aabb::new(lo.into(), hi.into())
            })
            .collect();
        // Leaves of up to 8 triangles: the CPU's packets run 10 % faster on
        // them than on leaves of 4 (mesh_scaling, 100k triangles).
        let params = BvhBuildParams::medium_build();
        let bvh = build_bvh2(&boxes, params, &mut std::time::Duration::default());
        let nodes = bvh
            .nodes
            .iter()
            .map(|n| BvhNode {
                lo: n.aabb.min.into(),
                hi: n.aabb.max.into(),
                first: n.first_index,
                count: n.prim_count,
            })
            .collect();
        let triangles = bvh.primitive_indices.iter().map(|&i| triangles[i as usize]).collect();
        tree(nodes, triangles, bvh.primitive_indices)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::ray::Ray;
    use crate::geometry::triangle::{NearestTriangle, intersect_triangle, mesh_triangles};
    use crate::util::rng::random_f32;

    /// A closed, bumpy sphere of `2 · rings · segments` triangles.
    fn sphere_mesh(rings: u32, segments: u32) -> Vec<Triangle> {
        let (positions, tris) = sphere_positions(rings, segments);
        mesh_triangles(&positions, &tris)
    }

    /// The bumpy sphere's vertices and triangles.
    fn sphere_positions(rings: u32, segments: u32) -> (Vec<Vec3>, Vec<[u32; 3]>) {
        let mut positions = Vec::new();
        for r in 0..=rings {
            let theta = core::f32::consts::PI * r as f32 / rings as f32;
            for s in 0..segments {
                let phi = core::f32::consts::TAU * s as f32 / segments as f32;
                let radius = 1.0 + 0.05 * (5.0 * phi).sin() * (3.0 * theta).sin();
                // The poles exactly (sin π in f32 is not 0): their triangles have no area.
                let (sin, cos) = if r == rings { (0.0, -1.0) } else { theta.sin_cos() };
                positions.push(radius * Vec3::new(sin * phi.cos(), sin * phi.sin(), cos));
            }
        }
        let mut tris = Vec::new();
        for r in 0..rings {
            for s in 0..segments {
                let (a, b) = (r * segments + s, r * segments + (s + 1) % segments);
                let (c, d) = (a + segments, b + segments);
                tris.extend([[a, c, b], [b, c, d]]);
            }
        }
        (positions, tris)
    }

    /// Every triangle offered in order: the specification the tree must match.
    fn brute_force(tris: &[Triangle], ray: &Ray, t_max: f32) -> Option<(f32, Vec3)> {
        let mut nearest = NearestTriangle::new(crate::util::tolerance::surface_skin(ray.origin));
        for (i, tri) in tris.iter().enumerate() {
            if let Some(t) = intersect_triangle(ray, tri, 0.0, t_max, nearest.skin) {
                nearest.offer(t, i as u32, tri.normal.dot(ray.direction) < 0.0);
            }
        }
        nearest.result().map(|(t, i)| (t, tris[i as usize].normal))
    }

    fn check_against_brute_force(bvh: &MeshBvh, label: &str) {
        for k in 0..3000u32 {
            let mut dimension = 0;
            let mut u = || {
                dimension += 1;
                random_f32(7, k, dimension) * 2.0 - 1.0
            };
            // From outside, from inside, and from points on the surface.
            let origin = match k % 3 {
                0 => Vec3::new(u(), u(), u()).normalize_or(Vec3::X) * 3.0,
                1 => Vec3::new(u(), u(), u()) * 0.5,
                _ => {
                    let t = &bvh.triangles[(k as usize * 7919) % bvh.triangles.len()];
                    t.v0 + t.e1 * 0.3 + t.e2 * 0.3
                }
            };
            let target = Vec3::new(u(), u(), u()) * 0.9;
            let ray = Ray::new(origin, target - origin);
            let t_max = if k % 5 == 0 { 1.5 } else { f32::INFINITY };
            let tree = bvh.intersect(&ray, 0.0, t_max).map(|(t, i)| (t, bvh.triangles[i as usize].normal));
            assert_eq!(tree, brute_force(&bvh.triangles, &ray, t_max), "{label}: ray {k} {ray:?}");
            assert_eq!(bvh.hits_any(&ray, 0.0, t_max), tree.is_some(), "{label}: any hit, ray {k}");
        }
    }

    /// The leaves (first, count) under wide node `at`.
    fn leaves(wide: &[WideNode], at: usize, out: &mut Vec<(u32, u32)>) {
        let n = &wide[at];
        for s in 0..n.slots as usize {
            if n.count[s] > 0 {
                out.push((n.first[s], n.count[s]));
            } else {
                leaves(wide, n.first[s] as usize, out);
            }
        }
    }

    #[test]
    fn the_wide_form_holds_every_leaf_of_the_binary_tree_once() {
        // 500 small triangles on a 10 × 10 × 5 lattice.
        let positions: Vec<Vec3> = (0..500u32)
            .flat_map(|i| {
                let p = Vec3::new((i % 10) as f32, (i / 10 % 10) as f32, (i / 100) as f32);
                [p, p + Vec3::X * 0.5, p + Vec3::Y * 0.5]
            })
            .collect();
        let corners: Vec<[u32; 3]> = (0..500u32).map(|i| [3 * i, 3 * i + 1, 3 * i + 2]).collect();
        let tris = mesh_triangles(&positions, &corners);
        for n in [1, 3, 4, 5, 17, 500] {
            let bvh = build(tris[..n].to_vec());
            let wide = &bvh.wide;
            let mut binary: Vec<(u32, u32)> =
                bvh.nodes.iter().filter(|b| b.count > 0).map(|b| (b.first, b.count)).collect();
            let mut held = Vec::new();
            leaves(wide, 0, &mut held);
            binary.sort_unstable();
            held.sort_unstable();
            assert_eq!(held, binary, "{n} triangles");
            assert!(wide.iter().all(|w| (1..=WIDTH as u32).contains(&w.slots)));
            // Inner nodes hold four slots unless the tree runs out of inner nodes to open.
            assert!(wide.len() <= bvh.nodes.len() / 3 + 1, "{n} triangles: {} wide nodes", wide.len());
        }
        assert!(collapse(&[]).is_empty());
    }

    #[test]
    fn the_tree_finds_the_hit_that_testing_every_triangle_finds() {
        let tris = sphere_mesh(24, 40);
        check_against_brute_force(&build(tris.clone()), "default builder");
        check_against_brute_force(&median_split(tris), "median split");
    }

    #[test]
    fn a_refitted_tree_finds_what_testing_every_moved_triangle_finds() {
        // The bumpy sphere's vertices, then the same mesh stretched, twisted and moved.
        let (positions, tris) = sphere_positions(24, 40);
        let bvh = build_mesh(&positions, &tris);
        let moved: Vec<Vec3> = positions
            .iter()
            .map(|p| {
                let (s, c) = (p.y * 0.8).sin_cos();
                Vec3::new(p.x * c - p.z * s, p.y * 1.7, p.x * s + p.z * c) * 0.6 + Vec3::new(0.1, -0.2, 0.05)
            })
            .collect();
        let refitted = refit(&bvh, &moved, &tris).expect("no triangle collapsed");
        assert_eq!(refitted.sources, bvh.sources);
        check_against_brute_force(&refitted, "refitted");
        // A triangle that collapses changes which triangles the tree holds: build anew.
        let mut collapsed = moved.clone();
        let [a, b, _] = tris[tris.len() / 2];
        collapsed[b as usize] = collapsed[a as usize];
        assert_eq!(refit(&bvh, &collapsed, &tris), None);
    }

    #[test]
    fn trees_are_shallow_and_hold_every_triangle_once() {
        let tris = sphere_mesh(60, 90);
        for (label, bvh) in [("default", build(tris.clone())), ("median", median_split(tris.clone()))] {
            assert_eq!(bvh.triangles.len(), tris.len(), "{label}");
            assert!(depth(&bvh.nodes) <= crate::geometry::bvh::MAX_DEPTH, "{label}");
            let leaves: u32 = bvh.nodes.iter().map(|n| n.count).sum();
            assert_eq!(leaves as usize, tris.len(), "{label}: every triangle in exactly one leaf");
            // `sources` is the permutation from the input to leaf order.
            let mut seen = vec![false; tris.len()];
            for (t, &k) in bvh.triangles.iter().zip(&bvh.sources) {
                assert_eq!(*t, tris[k as usize], "{label}");
                assert!(!core::mem::replace(&mut seen[k as usize], true), "{label}: source {k} twice");
            }
            // Every triangle lies inside its leaf's box.
            for n in bvh.nodes.iter().filter(|n| n.count > 0) {
                for t in &bvh.triangles[n.first as usize..(n.first + n.count) as usize] {
                    let (lo, hi) = t.padded_bounds();
                    assert!(lo.cmpge(n.lo).all() && hi.cmple(n.hi).all(), "{label}");
                }
            }
        }
        assert_eq!(build(Vec::new()), MeshBvh::default());
    }
}
