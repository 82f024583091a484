//! A small Wavefront OBJ reader: vertices and faces (polygons are fan-triangulated).

use glam::DVec3;
use std::path::Path;

/// Vertex positions (world coordinates, f64 as written) and triangles
/// (indices into the positions).
pub type MeshData = (Vec<DVec3>, Vec<[u32; 3]>);

/// Reads `path` into positions and triangles; the error names the file and line.
pub fn load(path: &Path) -> Result<MeshData, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("cannot read OBJ file {}: {e}", path.display()))?;
    parse(&text).map_err(|(line, reason)| format!("{}:{line}: {reason}", path.display()))
}

/// Parses OBJ text; errors carry the 1-based line.
pub fn parse(text: &str) -> Result<MeshData, (usize, String)> {
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let line_no = n + 1;
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => {
                let c: Vec<f64> = words
                    .take(3)
                    .map(|w| w.parse::<f64>().map_err(|_| (line_no, format!("bad vertex coordinate \"{w}\""))))
                    .collect::<Result<_, _>>()?;
                if c.len() != 3 {
                    return Err((line_no, "a vertex needs three coordinates".into()));
                }
                positions.push(DVec3::new(c[0], c[1], c[2]));
            }
            Some("f") => {
                let idx: Vec<u32> = words
                    .map(|w| {
                        let first = w.split('/').next().unwrap_or("");
                        let i: i64 = first.parse().map_err(|_| (line_no, format!("bad face index \"{w}\"")))?;
                        let resolved = if i < 0 { positions.len() as i64 + i } else { i - 1 };
                        if resolved < 0 || resolved >= positions.len() as i64 {
                            return Err((line_no, format!("face index {i} refers to a vertex that does not exist")));
                        }
                        Ok(resolved as u32)
                    })
                    .collect::<Result<_, _>>()?;
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
    Ok((positions, triangles))
}
