//! The library behind the `prismatic` command: scene files, built-in scenes,
//! backend selection and output files. Tests and benches use it too.

pub mod args;
pub mod backends;
pub mod builtin;
pub mod dispersion_test;
pub mod environment_file;
pub mod gltf_scene;
pub mod gltf_write;
pub mod ior_table;
pub mod obj;
pub mod output;
pub mod partial;
pub mod patterns;
pub mod pool;
pub mod progress_bar;
pub mod render_job;
pub mod ring;
pub mod scene_file;
pub mod settings;
pub mod study;
pub mod sunlit_glass;
pub mod tangents;
pub mod texture_file;

use scene_file::{SceneDocument, SceneFileError};
use std::path::Path;

/// Loads a scene by built-in name, or else from a file path.
pub fn load_scene(name_or_path: &str) -> Result<SceneDocument, SceneFileError> {
    match builtin::find(name_or_path) {
        Some(b) => scene_file::parse(b.source, &format!("<built-in {}>", b.name), None),
        None if let Some(g) = builtin::find_generated(name_or_path) => {
            let mut doc =
                gltf_scene::load_slice((g.document)().to_json().as_bytes(), &format!("<built-in {}>", g.name))?;
            (g.settings)(&mut doc.scene.render);
            Ok(doc)
        }
        None if !Path::new(name_or_path).exists() && !name_or_path.contains(['/', '.']) => Err(SceneFileError {
            file: name_or_path.to_string(),
            line: None,
            key: String::new(),
            reason: format!("no such built-in scene or file; built-in scenes are: {}", builtin::names().join(", ")),
        }),
        None if is_gltf(Path::new(name_or_path)) => gltf_scene::load(Path::new(name_or_path)),
        None => scene_file::load(Path::new(name_or_path)),
    }
}

/// True for `.gltf` and `.glb` files (any case).
fn is_gltf(path: &Path) -> bool {
    path.extension().is_some_and(|e| e.eq_ignore_ascii_case("gltf") || e.eq_ignore_ascii_case("glb"))
}
