//! Environment maps from HDR files (Radiance `.hdr`, OpenEXR `.exr`): the
//! equirectangular image as linear RGB radiance, the built-in names, and
//! the command line's `--environment` flags.

use crate::scene_file::{SceneDocument, SceneFileError};
use prismatic_core::model::environment::{EnvironmentMap, MAX_ENVIRONMENT_SIDE};
use prismatic_core::model::scene::Light;
use std::path::Path;

/// The built-in maps a scene may name instead of a file.
pub const BUILT_IN: &[&str] = &["studio"];

/// The built-in map `name`, if there is one.
pub fn built_in(name: &str) -> Option<EnvironmentMap> {
    match name {
        "studio" => Some(EnvironmentMap::studio()),
        _ => None,
    }
}

/// Reads the equirectangular map at `path` (any size up to
/// [`MAX_ENVIRONMENT_SIDE`] a side; an image twice as wide as it is high
/// covers the sphere evenly); the error names the file and why.
pub fn load(path: &Path) -> Result<EnvironmentMap, String> {
    let reader = image::ImageReader::open(path)
        .and_then(|r| r.with_guessed_format())
        .map_err(|e| format!("cannot read environment map {}: {e}", path.display()))?;
    let (width, height) =
        reader.into_dimensions().map_err(|e| format!("cannot decode environment map {}: {e}", path.display()))?;
    if width > MAX_ENVIRONMENT_SIDE || height > MAX_ENVIRONMENT_SIDE {
        return Err(format!(
            "environment map {} is {width}×{height}; each side must be at most {MAX_ENVIRONMENT_SIDE}",
            path.display()
        ));
    }
    let image =
        image::open(path).map_err(|e| format!("cannot decode environment map {}: {e}", path.display()))?.into_rgb32f();
    let texels = image.pixels().map(|p| prismatic_core::Vec3::from(p.0).max(prismatic_core::Vec3::ZERO)).collect();
    Ok(EnvironmentMap { name: path.display().to_string(), width, height, texels })
}

/// The command line's environment: a map that lights the scene (in place
/// of its own environment), and its strength and turn (of the scene's own
/// environment when no map is given).
#[derive(Clone, Debug, Default, PartialEq, clap::Args)]
pub struct EnvironmentArgs {
    /// Light the scene by an environment map: an equirectangular .hdr or
    /// .exr file, or "studio" (the built-in neutral studio). It takes the
    /// place of the scene's own environment.
    #[arg(long)]
    pub environment: Option<String>,
    /// The environment's radiance multiplier.
    #[arg(long)]
    pub environment_strength: Option<f32>,
    /// Turns the environment about +y, in degrees.
    #[arg(long)]
    pub environment_rotation: Option<f32>,
}

impl EnvironmentArgs {
    /// `doc` lit as these arguments say; an error names the flag.
    pub fn apply(&self, mut doc: SceneDocument) -> Result<SceneDocument, SceneFileError> {
        let flag = |name: &str, reason: String| SceneFileError {
            file: "command line".into(),
            line: None,
            key: format!("--{name}"),
            reason,
        };
        if let Some(name) = &self.environment {
            let map = match built_in(name) {
                Some(map) => map,
                None => load(Path::new(name)).map_err(|e| flag("environment", e))?,
            };
            doc.scene.lights.retain(|l| !matches!(l, Light::Environment { .. }));
            doc.scene.lights.push(Light::Environment {
                map,
                strength: 1.0,
                rotation_deg: 0.0,
                spectrum: Default::default(),
            });
        }
        for (name, value) in
            [("environment-strength", self.environment_strength), ("environment-rotation", self.environment_rotation)]
        {
            let Some(value) = value else { continue };
            let Some(Light::Environment { strength, rotation_deg, .. }) =
                doc.scene.lights.iter_mut().find(|l| matches!(l, Light::Environment { .. }))
            else {
                return Err(flag(name, "the scene has no environment (name one with --environment)".into()));
            };
            match name {
                "environment-strength" => *strength = value,
                _ => *rotation_deg = value,
            }
        }
        Ok(doc)
    }
}
