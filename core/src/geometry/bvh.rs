//! A bounding volume hierarchy over a mesh's triangles: the flat binary
//! node layout the reference and the WGSL shaders traverse, its four-wide
//! form the CPU's packets traverse, and the scalar traversal the others
//! mirror. Which triangle a ray hits is decided by
//! [`NearestTriangle`], whatever order the nodes are visited in, so the
//! tree's shape changes speed, never a hit.

use crate::geometry::ray::Ray;
use crate::geometry::triangle::{NearestTriangle, Triangle, intersect_triangle};
use crate::util::tolerance::surface_skin;
use alloc::vec::Vec;
use glam::Vec3;

/// Deepest tree any traversal accepts: the size of their node stacks.
/// Builders that would go deeper fall back to a median split (depth
/// log₂ of the triangle count).
pub const MAX_DEPTH: usize = 64;

/// A box slab test passes when the box starts no farther than this factor
/// times the search limit: a margin for the rounding of the slab distances
/// against the triangle test's own.
pub const BOX_MARGIN: f32 = 1.0 + 1e-4;

/// One node: a box and either two children (`count == 0`: nodes `first` and
/// `first + 1`) or `count` triangles from `first`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BvhNode {
    /// Box minimum.
    pub lo: Vec3,
    /// Box maximum.
    pub hi: Vec3,
    /// First child node, or first triangle of a leaf.
    pub first: u32,
    /// Triangles in a leaf; 0 for an inner node.
    pub count: u32,
}

/// Slots per wide node.
pub const WIDTH: usize = 4;

/// A node of the tree's four-wide form: `slots` boxes, each either a wide
/// child node (`count == 0`: node `first`) or a leaf of `count` triangles
/// from `first`. A wide node holds up to four of the binary tree's nodes
/// (a node's children, the largest inner one opened into its own two until
/// four are held), so a traversal tests four boxes per step and goes half
/// as deep. The boxes are the binary nodes' own: every box test a wide
/// traversal makes is one the binary traversal could make, and which
/// triangle a ray hits is still decided by [`NearestTriangle`].
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

/// A mesh's triangles in leaf order and the tree over them (node 0 is the
/// root; empty when the mesh has no triangle).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MeshBvh {
    /// Nodes, root first.
    pub nodes: Vec<BvhNode>,
    /// Triangles, each leaf's contiguous.
    pub triangles: Vec<Triangle>,
    /// For each of `triangles`, its index in the list the tree was built
    /// from (texture coordinates and refits look the corners up by it).
    pub sources: Vec<u32>,
    /// The same tree four-wide (each node four of `nodes`' boxes, see
    /// [`WideNode`]), for traversals that test four boxes at once (the
    /// CPU's packets).
    pub wide: Vec<WideNode>,
}

/// A ray's reciprocal direction for slab tests: components of magnitude
/// below 1e-30 count as ±1e-30, so no product is NaN.
#[inline]
pub fn inverse_direction(d: Vec3) -> Vec3 {
    let guard = |c: f32| if c.abs() < 1e-30 { 1e-30f32.copysign(c) } else { c };
    Vec3::new(1.0 / guard(d.x), 1.0 / guard(d.y), 1.0 / guard(d.z))
}

/// Where a ray enters a box if it meets it with `0 ≤ t ≤ limit · BOX_MARGIN`.
#[inline]
pub fn box_entry(origin: Vec3, inv: Vec3, lo: Vec3, hi: Vec3, limit: f32) -> Option<f32> {
    let (a, b) = ((lo - origin) * inv, (hi - origin) * inv);
    let near = a.min(b).max_element().max(0.0);
    let far = a.max(b).min_element();
    (near <= far && near <= limit * BOX_MARGIN).then_some(near)
}

impl MeshBvh {
    /// Memory of the nodes (binary and wide), triangles and their sources, in bytes.
    pub fn bytes(&self) -> usize {
        self.nodes.len() * core::mem::size_of::<BvhNode>()
            + self.wide.len() * core::mem::size_of::<WideNode>()
            + self.triangles.len() * (core::mem::size_of::<Triangle>() + core::mem::size_of::<u32>())
    }

    /// The nearest hit with `t_min < t < t_max`: (t, index into `triangles`).
    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<(f32, u32)> {
        let mut nearest = NearestTriangle::new(surface_skin(ray.origin));
        self.visit(ray, t_max, |tri, index| {
            if let Some(t) = intersect_triangle(ray, tri, t_min, t_max, nearest.skin) {
                nearest.offer(t, index, tri.normal.dot(ray.direction) < 0.0);
            }
            nearest.reach().min(t_max)
        });
        nearest.result()
    }

    /// Whether any triangle is hit with `t_min < t < t_max`.
    pub fn hits_any(&self, ray: &Ray, t_min: f32, t_max: f32) -> bool {
        let skin = surface_skin(ray.origin);
        let mut hit = false;
        self.visit(ray, t_max, |tri, _| {
            hit = intersect_triangle(ray, tri, t_min, t_max, skin).is_some();
            if hit { -1.0 } else { t_max }
        });
        hit
    }

    /// Visits the leaves' triangles whose boxes the ray meets before the
    /// search limit, nearer child first. `test` returns the new limit
    /// (negative stops the traversal).
    #[inline]
    fn visit(&self, ray: &Ray, t_max: f32, mut test: impl FnMut(&Triangle, u32) -> f32) {
        let Some(root) = self.nodes.first() else { return };
        let inv = inverse_direction(ray.direction);
        let mut limit = t_max;
        if box_entry(ray.origin, inv, root.lo, root.hi, limit).is_none() {
            return;
        }
        let mut stack = [0u32; MAX_DEPTH];
        let mut depth = 0usize;
        let mut node = *root;
        loop {
            if node.count > 0 {
                for index in node.first..node.first + node.count {
                    limit = test(&self.triangles[index as usize], index);
                    if limit < 0.0 {
                        return;
                    }
                }
            } else {
                let (a, b) = (node.first, node.first + 1);
                let (na, nb) = (self.nodes[a as usize], self.nodes[b as usize]);
                let ta = box_entry(ray.origin, inv, na.lo, na.hi, limit);
                let tb = box_entry(ray.origin, inv, nb.lo, nb.hi, limit);
                match (ta, tb) {
                    (Some(ta), Some(tb)) => {
                        let (near, far) = if tb < ta { (b, a) } else { (a, b) };
                        stack[depth] = far;
                        depth += 1;
                        node = self.nodes[near as usize];
                        continue;
                    }
                    (Some(_), None) => {
                        node = na;
                        continue;
                    }
                    (None, Some(_)) => {
                        node = nb;
                        continue;
                    }
                    (None, None) => {}
                }
            }
            // Pop the next node still within reach.
            loop {
                if depth == 0 {
                    return;
                }
                depth -= 1;
                let next = self.nodes[stack[depth] as usize];
                if box_entry(ray.origin, inv, next.lo, next.hi, limit).is_some() {
                    node = next;
                    break;
                }
            }
        }
    }
}
