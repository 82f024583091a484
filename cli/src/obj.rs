//! A small Wavefront OBJ reader: vertices, texture coordinates, normals
//! and faces (polygons are fan-triangulated).

use glam::{DVec3, Vec2, Vec3};
use std::collections::HashMap;
use std::path::Path;

/// A mesh as read from an OBJ file.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MeshData {
    /// Vertex positions (world coordinates, f64 as written).
    pub positions: Vec<DVec3>,
    /// Triangles as indices into `positions`.
    pub triangles: Vec<[u32; 3]>,
    /// Texture coordinates per position (v down the image, as glTF has
    /// it: OBJ's v runs up), or empty when the faces name none.
    pub uvs: Vec<Vec2>,
    /// Normals per position, or empty when the faces name none.
    pub normals: Vec<Vec3>,
}

/// Reads `path`; the error names the file and line.
pub fn load(path: &Path) -> Result<MeshData, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("cannot read OBJ file {}: {e}", path.display()))?;
    parse(&text).map_err(|(line, reason)| format!("{}:{line}: {reason}", path.display()))
}

/// A face corner: its position, texture coordinate and normal (indices).
type Corner = (u32, Option<u32>, Option<u32>);

/// Parses OBJ text; errors carry the 1-based line. Each distinct corner
/// (`v`, `v/vt`, `v//vn` or `v/vt/vn`) gets a vertex of its own, so that
/// seams and creases keep both sides' coordinates and normals. The mesh
/// has texture coordinates when every corner names one, and normals when
/// every corner names one; otherwise it keeps the file's vertices.
pub fn parse(text: &str) -> Result<MeshData, (usize, String)> {
    let mut vertices: Vec<DVec3> = Vec::new();
    let mut coords: Vec<Vec2> = Vec::new();
    let mut normals: Vec<Vec3> = Vec::new();
    // Face corners, numbered in order of appearance.
    let mut corner_ids: HashMap<Corner, u32> = HashMap::new();
    let mut corners: Vec<Corner> = Vec::new();
    let mut triangles = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let line_no = n + 1;
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => {
                let c = numbers(words.take(3), line_no, "vertex coordinate")?;
                if c.len() != 3 {
                    return Err((line_no, "a vertex needs three coordinates".into()));
                }
                vertices.push(DVec3::new(c[0], c[1], c[2]));
            }
            Some("vt") => {
                let c = numbers(words.take(2), line_no, "texture coordinate")?;
                if c.is_empty() {
                    return Err((line_no, "a texture coordinate needs u (and v)".into()));
                }
                let v = c.get(1).copied().unwrap_or(0.0);
                coords.push(Vec2::new(c[0] as f32, (1.0 - v) as f32));
            }
            Some("vn") => {
                let c = numbers(words.take(3), line_no, "normal coordinate")?;
                if c.len() != 3 {
                    return Err((line_no, "a normal needs three coordinates".into()));
                }
                normals.push(Vec3::new(c[0] as f32, c[1] as f32, c[2] as f32));
            }
            Some("f") => {
                let mut idx = Vec::new();
                for w in words {
                    let mut parts = w.split('/');
                    let position = resolve(parts.next().unwrap_or(""), vertices.len(), line_no, w, "vertex")?;
                    let coord = match parts.next() {
                        Some(t) if !t.is_empty() => Some(resolve(t, coords.len(), line_no, w, "texture coordinate")?),
                        _ => None,
                    };
                    let normal = match parts.next() {
                        Some(t) if !t.is_empty() => Some(resolve(t, normals.len(), line_no, w, "normal")?),
                        _ => None,
                    };
                    let next = corners.len() as u32;
                    idx.push(*corner_ids.entry((position, coord, normal)).or_insert_with(|| {
                        corners.push((position, coord, normal));
                        next
                    }));
                }
                if idx.len() < 3 {
                    return Err((line_no, "a face needs at least three vertices".into()));
                }
                for k in 1..idx.len() - 1 {
                    triangles.push([idx[0], idx[k], idx[k + 1]]);
                }
            }
            _ => {}
        }
    }
    if triangles.is_empty() {
        return Err((text.lines().count().max(1), "the OBJ file has no faces".into()));
    }
    let (with_uvs, with_normals) = (corners.iter().all(|c| c.1.is_some()), corners.iter().all(|c| c.2.is_some()));
    if !with_uvs && !with_normals {
        // No attribute on every corner: the mesh keeps the file's vertices.
        let triangles = triangles.iter().map(|t: &[u32; 3]| t.map(|c| corners[c as usize].0)).collect();
        return Ok(MeshData { positions: vertices, triangles, uvs: Vec::new(), normals: Vec::new() });
    }
    let uvs =
        if with_uvs { corners.iter().filter_map(|c| c.1).map(|t| coords[t as usize]).collect() } else { Vec::new() };
    let normals = if with_normals {
        corners.iter().filter_map(|c| c.2).map(|n| normals[n as usize]).collect()
    } else {
        Vec::new()
    };
    Ok(MeshData { positions: corners.iter().map(|&(p, _, _)| vertices[p as usize]).collect(), triangles, uvs, normals })
}

fn numbers<'a>(words: impl Iterator<Item = &'a str>, line: usize, what: &str) -> Result<Vec<f64>, (usize, String)> {
    words.map(|w| w.parse::<f64>().map_err(|_| (line, format!("bad {what} \"{w}\"")))).collect()
}

/// A 1-based (or negative, relative) OBJ index into a list of `len` items.
fn resolve(text: &str, len: usize, line: usize, word: &str, what: &str) -> Result<u32, (usize, String)> {
    let i: i64 = text.parse().map_err(|_| (line, format!("bad face index \"{word}\"")))?;
    let resolved = if i < 0 { len as i64 + i } else { i - 1 };
    if resolved < 0 || resolved >= len as i64 {
        return Err((line, format!("face index {i} refers to a {what} that does not exist")));
    }
    Ok(resolved as u32)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn faces_without_texture_coordinates_keep_their_vertices() {
        let m = parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 9 9 9\nf 1 2 4 3\n").unwrap();
        assert_eq!(m.positions.len(), 5);
        assert_eq!(m.triangles, [[0, 1, 3], [0, 3, 2]]);
        assert!(m.uvs.is_empty());
    }

    #[test]
    fn texture_coordinates_give_one_vertex_per_pair_with_v_flipped() {
        // Two triangles sharing an edge whose corners have different coordinates on each side (a seam).
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvt 0.5 0.25\n\
                    f 1/1 2/2 3/3\nf 2/4 3/3 1/1\n";
        let m = parse(text).unwrap();
        assert_eq!(m.positions.len(), 4, "vertex 2 with two coordinates becomes two vertices");
        assert_eq!(m.uvs.len(), 4);
        assert_eq!(m.uvs[0], Vec2::new(0.0, 1.0));
        assert_eq!(m.uvs[3], Vec2::new(0.5, 0.75));
        assert_eq!(m.triangles, [[0, 1, 2], [3, 2, 0]]);
        assert_eq!(m.positions[3], DVec3::X);
    }

    #[test]
    fn a_missing_coordinate_is_an_error_and_corners_without_any_leave_the_mesh_without() {
        let e = parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/2 2 3\n").unwrap_err();
        assert_eq!(e.0, 4);
        assert!(e.1.contains("texture coordinate that does not exist"), "{}", e.1);
        let m = parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nf 1/1 2 3//1\n").unwrap();
        assert_eq!((m.positions.len(), m.triangles[0], m.uvs.len(), m.normals.len()), (3, [0, 1, 2], 0, 0));
    }

    #[test]
    fn normals_give_one_vertex_per_position_and_normal() {
        // A crease: vertex 2 has one normal in each face.
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 0 0 1\nvn 0 0.6 0.8\n\
                    f 1//1 2//1 3//1\nf 2//2 4//2 3//1\n";
        let m = parse(text).unwrap();
        assert_eq!(m.positions.len(), 5, "vertex 2 with two normals becomes two vertices");
        assert_eq!(m.normals, [Vec3::Z, Vec3::Z, Vec3::Z, Vec3::new(0.0, 0.6, 0.8), Vec3::new(0.0, 0.6, 0.8)]);
        assert_eq!(m.triangles, [[0, 1, 2], [3, 4, 2]]);
        assert!(m.uvs.is_empty());
        let e = parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//1 2//1 3//1\n").unwrap_err();
        assert!(e.1.contains("normal that does not exist"), "{}", e.1);
    }
}
