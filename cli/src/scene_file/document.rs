//! What reading a scene file gives: the scene with the source positions of
//! its keys ([`SceneDocument`]), and the error every reader reports
//! ([`SceneFileError`]: the file, the key, its line and the reason).

use glam::DVec3;
use prismatic_core::{Scene, SceneError};
use std::collections::HashMap;
use std::fmt;

/// A problem with a scene file.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub struct SceneFileError {
    /// The file (or built-in scene name).
    pub file: String,
    /// 1-based line of the offending key, where known.
    pub line: Option<usize>,
    /// Dotted key (`object[2].radius`); empty for syntax errors.
    pub key: String,
    /// What is wrong.
    pub reason: String,
}

impl fmt::Display for SceneFileError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.file)?;
        if let Some(line) = self.line {
            write!(f, ":{line}")?;
        }
        if !self.key.is_empty() {
            write!(f, ": {}", self.key)?;
        }
        write!(f, ": {}", self.reason)
    }
}

/// A parsed (not yet validated) scene with the source positions of its keys.
#[derive(Clone, Debug)]
pub struct SceneDocument {
    /// The scene, before validation (command-line overrides go here).
    pub scene: Scene,
    /// World position of the scene's local frame: every position in `scene`
    /// is relative to it (see [`super::LOCAL_FRAME_RADIUS`]).
    pub origin: DVec3,
    /// What the reader left out of the file (glTF elements prismatic cannot
    /// represent), one line each, for the user to see.
    pub warnings: Vec<String>,
    file: String,
    lines: HashMap<String, usize>,
    /// For files that are not scene files: what the file calls the element
    /// behind a scene key (`object[2]` → `meshes[1].primitives[0]`).
    elements: Vec<(String, String)>,
}

impl SceneDocument {
    /// A scene read from a scene file: positions relative to `origin`, what
    /// the reader left out (`warnings`) and the line of each key (`lines`).
    pub(crate) fn read(
        scene: Scene,
        origin: DVec3,
        warnings: Vec<String>,
        file: &str,
        lines: HashMap<String, usize>,
    ) -> Self {
        SceneDocument { scene, origin, warnings, file: file.to_string(), lines, elements: Vec::new() }
    }

    /// A scene read from `file` by another reader, which has no lines to
    /// point at but names its elements: errors about the scene key in the
    /// first of a pair of `elements` name the second instead.
    pub fn from_scene(scene: Scene, file: &str, warnings: Vec<String>, elements: Vec<(String, String)>) -> Self {
        SceneDocument { scene, origin: DVec3::ZERO, warnings, file: file.to_string(), lines: HashMap::new(), elements }
    }

    /// Whether the file wrote scene key `key` (`render.ambient`), rather
    /// than leaving it to its default.
    pub fn names(&self, key: &str) -> bool {
        self.lines.contains_key(key)
    }

    /// Validates the scene, reporting problems at their key's line.
    pub fn validate(&self) -> Result<(), SceneFileError> {
        self.scene.validate().map_err(|e| self.error(e))
    }

    /// Turns a core error into a file error with the key's line.
    pub fn error(&self, e: SceneError) -> SceneFileError {
        // Nested keys (`ior.bands[3]`) fall back to their nearest recorded parent.
        let mut key = e.key.as_str();
        let line = loop {
            if let Some(&l) = self.lines.get(key) {
                break Some(l);
            }
            match key.rfind(['.', '[']) {
                Some(i) => key = &key[..i],
                None => break None,
            }
        };
        SceneFileError { file: self.file.clone(), line, key: self.element(e.key), reason: e.reason }
    }

    /// `key` with the file's name for its element, where the reader gave one.
    fn element(&self, key: String) -> String {
        let named = self.elements.iter().find_map(|(scene_key, name)| {
            let rest = key.strip_prefix(scene_key.as_str())?;
            (rest.is_empty() || rest.starts_with(['.', '['])).then(|| format!("{name}{rest}"))
        });
        named.unwrap_or(key)
    }
}
