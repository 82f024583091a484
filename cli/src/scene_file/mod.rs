//! The TOML scene-file format: parsing into a core [`Scene`](prismatic_core::Scene),
//! with errors that name the file, the key, its line and the reason.
//!
//! Parsing keeps the source span of every key it reads, so that problems the
//! core's validation finds later (`object[1].radius: must be greater than 0`)
//! are reported at the right line too. Unknown keys are errors. The files
//! split the work: `document` (what reading gives), `reader` (spanned TOML
//! values), `schema` (the scene's keys), `names` (setting names, shared with
//! the command line).

pub(crate) mod document;
mod names;
mod reader;
mod schema;

pub use document::{SceneDocument, SceneFileError};
pub use names::{
    parse_bands, parse_estimator, parse_photon_sequence, parse_radius_mode, parse_tone_map, parse_view_paths,
    parse_wavelengths, parse_white_point,
};
pub use reader::LOCAL_FRAME_RADIUS;

use glam::DVec3;
use reader::Reader;
use std::collections::HashMap;
use std::path::Path;
use toml::de::DeTable;

/// Reads and parses a scene file; OBJ meshes are resolved relative to it.
pub fn load(path: &Path) -> Result<SceneDocument, SceneFileError> {
    let label = path.display().to_string();
    let source = std::fs::read_to_string(path).map_err(|e| SceneFileError {
        file: label.clone(),
        line: None,
        key: String::new(),
        reason: format!("cannot read the file: {e}"),
    })?;
    parse(&source, &label, path.parent())
}

/// Parses scene-file text. `file` names it in errors; `base` resolves mesh paths.
pub fn parse(source: &str, file: &str, base: Option<&Path>) -> Result<SceneDocument, SceneFileError> {
    let mut p = Reader {
        source,
        file,
        base: base.map(Path::to_path_buf),
        lines: HashMap::new(),
        origin: DVec3::ZERO,
        warnings: Vec::new(),
    };
    let root = DeTable::parse(source).map_err(|e| SceneFileError {
        file: file.to_string(),
        line: e.span().map(|s| p.line_of(s.start)),
        key: String::new(),
        reason: format!("TOML syntax error: {}", e.message()),
    })?;
    let scene = p.scene(root.get_ref(), root.span())?;
    Ok(SceneDocument::read(scene, p.origin, p.warnings, file, p.lines))
}

/// Parses, validates and prepares `source` (no file access beyond OBJ
/// paths, no rendering): what the fuzz target and its proptest twin run.
/// Rejects bad input with a [`SceneFileError`]; never panics.
pub fn check_source(source: &str) -> Result<prismatic_core::PreparedScene, SceneFileError> {
    let doc = parse(source, "fuzz.toml", None)?;
    doc.validate()?;
    prismatic_core::PreparedScene::new(doc.scene.clone()).map_err(|e| doc.error(e))
}
