//! Tangents for a normal-mapped mesh that has vertex normals but no
//! `TANGENT`: MikkTSpace's, as glTF asks of a reader ("client
//! implementations SHOULD calculate tangents using default MikkTSpace
//! algorithms"), so a normal map baked against them reads back as baked.

use bevy_mikktspace::{Geometry, TangentSpace, generate_tangents};
use glam::{Vec2, Vec3, Vec4};
use prismatic_core::model::scene::Shape;
use std::collections::HashMap;

/// The mesh read face by face, and MikkTSpace's answer per corner.
struct Corners<'a> {
    positions: &'a [Vec3],
    triangles: &'a [[u32; 3]],
    normals: &'a [Vec3],
    uvs: &'a [Vec2],
    tangents: Vec<Vec4>,
}

impl Corners<'_> {
    fn vertex(&self, face: usize, corner: usize) -> usize {
        self.triangles[face][corner] as usize
    }
}

impl Geometry for Corners<'_> {
    fn num_faces(&self) -> usize {
        self.triangles.len()
    }

    fn num_vertices_of_face(&self, _face: usize) -> usize {
        3
    }

    fn position(&self, face: usize, corner: usize) -> [f32; 3] {
        self.positions[self.vertex(face, corner)].to_array()
    }

    fn normal(&self, face: usize, corner: usize) -> [f32; 3] {
        self.normals[self.vertex(face, corner)].to_array()
    }

    /// With v turned up: MikkTSpace's bitangent follows growing v, and
    /// glTF's points up the image, where its v (down the image) falls.
    fn tex_coord(&self, face: usize, corner: usize) -> [f32; 2] {
        let uv = self.uvs[self.vertex(face, corner)];
        [uv.x, 1.0 - uv.y]
    }

    fn set_tangent(&mut self, tangent: Option<TangentSpace>, face: usize, corner: usize) {
        // A corner of degenerate faces only gets none: any frame does there.
        let encoded = tangent.map_or([1.0, 0.0, 0.0, 1.0], |t| t.tangent_encoded());
        self.tangents[3 * face + corner] = Vec4::from_array(encoded);
    }
}

/// Gives `mesh` MikkTSpace tangents when it has vertex normals and texture
/// coordinates but no tangents (otherwise leaves it as it is). A vertex
/// whose faces get different tangents (where the image is mirrored) is
/// split, one copy per tangent, as MikkTSpace's users re-index.
pub fn add_mikktspace_tangents(mesh: &mut Shape) {
    let Shape::Mesh { positions, triangles, uvs, normals, tangents } = mesh else { return };
    if !tangents.is_empty() || normals.is_empty() || uvs.is_empty() {
        return;
    }
    let mut corners = Corners { positions, triangles, normals, uvs, tangents: vec![Vec4::ZERO; 3 * triangles.len()] };
    // It has no failure yet; were one added, each triangle's own frame stands in.
    if generate_tangents(&mut corners).is_err() {
        return;
    }
    let per_corner = corners.tangents;
    let mut per_vertex: Vec<Option<Vec4>> = vec![None; positions.len()];
    let mut copies: HashMap<(u32, [u32; 4]), u32> = HashMap::new();
    for (face, triangle) in triangles.iter_mut().enumerate() {
        for (corner, vertex) in triangle.iter_mut().enumerate() {
            let tangent = per_corner[3 * face + corner];
            let i = *vertex as usize;
            match per_vertex[i] {
                None => per_vertex[i] = Some(tangent),
                Some(t) if t == tangent => {}
                Some(_) => {
                    *vertex = *copies.entry((*vertex, tangent.to_array().map(f32::to_bits))).or_insert_with(|| {
                        positions.push(positions[i]);
                        normals.push(normals[i]);
                        uvs.push(uvs[i]);
                        per_vertex.push(Some(tangent));
                        (positions.len() - 1) as u32
                    });
                }
            }
        }
    }
    // A vertex no triangle uses keeps a unit tangent (validation wants one).
    *tangents = per_vertex.into_iter().map(|t| t.unwrap_or(Vec4::new(1.0, 0.0, 0.0, 1.0))).collect();
}

#[cfg(test)]
mod tests {
    use super::*;
    use prismatic_core::geometry::normal_map::TriangleTangents;
    use prismatic_core::geometry::primitive::mesh_triangles;
    use prismatic_core::geometry::texture::TriangleUv;

    /// A unit square in the xy-plane facing +z, its image upright (u along
    /// +x, v down the image along −y) or mirrored left to right.
    fn square(mirrored: bool) -> Shape {
        let corners = [Vec2::new(0.0, 0.0), Vec2::new(1.0, 0.0), Vec2::new(1.0, 1.0), Vec2::new(0.0, 1.0)];
        Shape::Mesh {
            positions: corners.iter().map(|c| c.extend(0.0)).collect(),
            triangles: vec![[0, 1, 2], [0, 2, 3]],
            uvs: corners.iter().map(|c| Vec2::new(if mirrored { 1.0 - c.x } else { c.x }, 1.0 - c.y)).collect(),
            normals: vec![Vec3::Z; 4],
            tangents: Vec::new(),
        }
    }

    #[test]
    fn mikktspace_agrees_with_the_frame_of_the_texture_coordinates() {
        for mirrored in [false, true] {
            let mut mesh = square(mirrored);
            add_mikktspace_tangents(&mut mesh);
            let Shape::Mesh { positions, triangles, uvs, tangents, .. } = &mesh else { unreachable!() };
            assert_eq!(tangents.len(), 4, "no vertex split on a plain square");
            let want = if mirrored { Vec4::new(-1.0, 0.0, 0.0, -1.0) } else { Vec4::new(1.0, 0.0, 0.0, 1.0) };
            for t in tangents {
                assert!((*t - want).abs().max_element() < 1e-6, "mirrored {mirrored}: {t}, want {want}");
            }
            // The core's frame from each triangle's coordinates is the same one.
            for (tri, corners) in mesh_triangles(positions, triangles).iter().zip(triangles) {
                let frame = TriangleTangents::from_uvs(tri, &TriangleUv::new(corners.map(|i| uvs[i as usize])));
                assert_eq!((frame.t0.normalize(), frame.sign), (want.truncate(), want.w));
            }
        }
    }

    #[test]
    fn a_vertex_on_a_mirror_seam_is_split_and_meshes_with_tangents_are_left_alone() {
        // Two squares side by side sharing an edge, the right one's image mirrored.
        let corners = [(0.0, 0.0), (1.0, 0.0), (2.0, 0.0), (0.0, 1.0), (1.0, 1.0), (2.0, 1.0)];
        let mut mesh = Shape::Mesh {
            positions: corners.iter().map(|&(x, y)| Vec3::new(x, y, 0.0)).collect(),
            triangles: vec![[0, 1, 4], [0, 4, 3], [1, 2, 5], [1, 5, 4]],
            uvs: corners.iter().map(|&(x, y)| Vec2::new(1.0 - (x - 1.0f32).abs(), 1.0 - y)).collect(),
            normals: vec![Vec3::Z; 6],
            tangents: Vec::new(),
        };
        add_mikktspace_tangents(&mut mesh);
        let Shape::Mesh { positions, triangles, tangents, .. } = &mesh else { unreachable!() };
        assert_eq!(positions.len(), 8, "the seam's two vertices are split");
        for (face, want) in [(0, 1.0), (1, 1.0), (2, -1.0), (3, -1.0)] {
            for &v in &triangles[face] {
                assert_eq!(tangents[v as usize], Vec4::new(want, 0.0, 0.0, want), "face {face}");
            }
        }
        let before = mesh.clone();
        add_mikktspace_tangents(&mut mesh);
        assert_eq!(mesh, before);
    }
}
