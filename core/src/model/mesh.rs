//! Whether a triangle mesh encloses a volume: every edge shared by exactly
//! two triangles that cross it in opposite directions (an oriented
//! 2-manifold). Glass needs it: a ray that enters must find a way out.
//! Triangles of no area are left out of the count: rays never hit them.

use alloc::vec;
use alloc::vec::Vec;
use glam::Vec3;

/// The first edge (its two end points) that does not join exactly two
/// triangles of opposite winding, or `None` when the mesh is closed.
/// Vertices at the same position count as one (exporters duplicate them
/// for normals and texture seams). "First" is in the order of the edges'
/// welded end points; sorting, not a map, keeps this fast for meshes of
/// 10⁵–10⁶ triangles.
pub fn open_edge(positions: &[Vec3], triangles: &[[u32; 3]]) -> Option<(Vec3, Vec3)> {
    // Weld: a vertex's id is the first index holding the same bits (so
    // -0.0 ≠ 0.0 is possible but harmless: such a mesh is reported, not
    // traced wrongly).
    let mut by_bits: Vec<([u32; 3], u32)> =
        positions.iter().enumerate().map(|(i, p)| (p.to_array().map(f32::to_bits), i as u32)).collect();
    by_bits.sort_unstable();
    let mut welded = vec![0u32; positions.len()];
    let mut first = 0;
    for (k, &(bits, i)) in by_bits.iter().enumerate() {
        if k == 0 || bits != by_bits[k - 1].0 {
            first = i;
        }
        welded[i as usize] = first;
    }
    // Directed edges by their welded ends, then by occurrence: each must
    // appear once, and its reverse once.
    let key = |a: u32, b: u32| u64::from(a) << 32 | u64::from(b);
    let mut edges: Vec<(u64, u32, [u32; 2])> = Vec::with_capacity(3 * triangles.len());
    for t in triangles.iter().filter(|t| !degenerate(positions, &welded, t)) {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            edges.push((key(welded[a as usize], welded[b as usize]), edges.len() as u32, [a, b]));
        }
    }
    edges.sort_unstable_by_key(|e| (e.0, e.1));
    let count = |k: u64| edges.partition_point(|e| e.0 <= k) - edges.partition_point(|e| e.0 < k);
    let mut start = 0;
    while start < edges.len() {
        let (k, _, [pa, pb]) = edges[start];
        let run = edges[start..].partition_point(|e| e.0 == k);
        let twin = count(key(k as u32, (k >> 32) as u32));
        if run != 1 || twin != 1 {
            return Some((positions[pa as usize], positions[pb as usize]));
        }
        start += run;
    }
    None
}

/// A triangle with a repeated vertex, or whose corners lie on one line.
fn degenerate(positions: &[Vec3], welded: &[u32], t: &[u32; 3]) -> bool {
    let [a, b, c] = t.map(|i| i as usize);
    if welded[a] == welded[b] || welded[b] == welded[c] || welded[c] == welded[a] {
        return true;
    }
    let (u, v) = (positions[b] - positions[a], positions[c] - positions[a]);
    u.cross(v).length_squared() <= 1e-12 * u.length_squared() * v.length_squared()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tetrahedron() -> (Vec<Vec3>, Vec<[u32; 3]>) {
        let p = vec![Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z];
        (p, vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    }

    #[test]
    fn a_tetrahedron_is_closed_and_stays_closed_with_duplicated_vertices() {
        let (p, t) = tetrahedron();
        assert_eq!(open_edge(&p, &t), None);
        // Every face with its own three vertices, as exporters write flat faces.
        let (mut q, mut u) = (Vec::new(), Vec::new());
        for tri in &t {
            let base = q.len() as u32;
            q.extend(tri.map(|i| p[i as usize]));
            u.push([base, base + 1, base + 2]);
        }
        assert_eq!(open_edge(&q, &u), None);
    }

    #[test]
    fn a_missing_face_a_flipped_face_or_a_fin_opens_it() {
        let (p, t) = tetrahedron();
        assert!(open_edge(&p, &t[..3]).is_some(), "missing face");
        let mut flipped = t.clone();
        flipped[3] = [1, 3, 2];
        assert!(open_edge(&p, &flipped).is_some(), "flipped face");
        let mut fin = t.clone();
        fin.push([0, 1, 3]);
        assert!(open_edge(&p, &fin).is_some(), "three triangles on an edge");
        // Triangles of no area change nothing.
        let mut slivers = t.clone();
        let mut q = p.clone();
        q.push((p[0] + p[1]) * 0.5);
        slivers.extend([[0, 0, 1], [0, 4, 1], [1, 4, 0], [2, 2, 2]]);
        assert_eq!(open_edge(&q, &slivers), None, "degenerate triangles");
    }
}
