//! The four-wide form of a mesh's hierarchy: each node holds up to four of
//! the binary tree's nodes as slots (its children, with the largest inner
//! child opened into its own two until four are held), so a traversal
//! tests four boxes per step and goes half as deep. The boxes are the
//! binary nodes' own, so every box test a wide traversal makes is one the
//! binary traversal could make; which triangle a ray hits is still decided
//! by [`NearestTriangle`](crate::triangle::NearestTriangle).

use crate::bvh::BvhNode;
use alloc::vec::Vec;
use glam::Vec3;

/// Slots per wide node.
pub const WIDTH: usize = 4;

/// One wide node: `slots` boxes, each either a wide child node (`count ==
/// 0`: node `first`) or a leaf of `count` triangles from `first`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WideNode {
    /// Box minima.
    pub lo: [Vec3; WIDTH],
    /// Box maxima.
    pub hi: [Vec3; WIDTH],
    /// Child wide node, or first triangle of a leaf.
    pub first: [u32; WIDTH],
    /// Triangles in a leaf slot; 0 for a child node.
    pub count: [u32; WIDTH],
    /// Slots in use, from the first (1 to [`WIDTH`]).
    pub slots: u32,
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bvh_build::build;
    use crate::triangle::mesh_triangles;

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
    fn holds_every_leaf_of_the_binary_tree_once() {
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
            let wide = collapse(&bvh.nodes);
            let mut binary: Vec<(u32, u32)> =
                bvh.nodes.iter().filter(|b| b.count > 0).map(|b| (b.first, b.count)).collect();
            let mut held = Vec::new();
            leaves(&wide, 0, &mut held);
            binary.sort_unstable();
            held.sort_unstable();
            assert_eq!(held, binary, "{n} triangles");
            assert!(wide.iter().all(|w| (1..=WIDTH as u32).contains(&w.slots)));
            // Inner nodes hold four slots unless the tree runs out of inner nodes to open.
            assert!(wide.len() <= bvh.nodes.len() / 3 + 1, "{n} triangles: {} wide nodes", wide.len());
        }
        assert!(collapse(&[]).is_empty());
    }
}
