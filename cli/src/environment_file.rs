//! Environment maps from HDR files (Radiance `.hdr`, OpenEXR `.exr`): the
//! equirectangular image as linear RGB radiance, the built-in names, and
//! the command line's `--environment` flags (Python's `environment`
//! keywords).

use crate::scene_file::{SceneDocument, SceneFileError};
use crate::settings::SettingsSource;
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

/// The command line's environment (and Python's keywords of the same
/// names): a map that lights the scene (in place of its own environment),
/// and its strength and turn (of the scene's own environment when no map
/// is given).
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
    /// The names, as Python's keywords spell them.
    pub const NAMES: [&str; 3] = ["environment", "environment_strength", "environment_rotation"];

    /// Sets the argument named `name` (one of [`EnvironmentArgs::NAMES`])
    /// from its text; the error says why the value is not one.
    pub fn set(&mut self, name: &str, value: &str) -> Result<(), String> {
        let number = || value.parse::<f32>().map_err(|_| format!("expected a number, not \"{value}\""));
        match name {
            "environment" => self.environment = Some(value.to_string()),
            "environment_strength" => self.environment_strength = Some(number()?),
            "environment_rotation" => self.environment_rotation = Some(number()?),
            _ => return Err(format!("not an environment argument: {name}")),
        }
        Ok(())
    }

    /// `doc` lit as these arguments say; an error names the argument as
    /// `source` spells it.
    pub fn apply(&self, mut doc: SceneDocument, source: SettingsSource) -> Result<SceneDocument, SceneFileError> {
        if let Some(name) = &self.environment {
            let map = match built_in(name) {
                Some(map) => map,
                None => load(Path::new(name)).map_err(|e| source.error("environment", e))?,
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
            [("environment_strength", self.environment_strength), ("environment_rotation", self.environment_rotation)]
        {
            let Some(value) = value else { continue };
            let Some(Light::Environment { strength, rotation_deg, .. }) =
                doc.scene.lights.iter_mut().find(|l| matches!(l, Light::Environment { .. }))
            else {
                let reason = format!("the scene has no environment (name one with {})", source.spell("environment"));
                return Err(source.error(name, reason));
            };
            match name {
                "environment_strength" => *strength = value,
                _ => *rotation_deg = value,
            }
        }
        Ok(doc)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory;

    /// The names Python's keywords take are the flags' (one list could
    /// drift from the other), and each one sets its own field.
    #[test]
    fn the_keyword_names_are_the_flags() {
        #[derive(clap::Parser)]
        struct Flags {
            #[command(flatten)]
            environment: EnvironmentArgs,
        }
        let flags: Vec<String> =
            Flags::command().get_arguments().filter_map(|a| a.get_long()).map(|f| f.replace('-', "_")).collect();
        assert_eq!(flags, EnvironmentArgs::NAMES);
        let mut args = EnvironmentArgs::default();
        for name in EnvironmentArgs::NAMES {
            args.set(name, "2").unwrap();
        }
        let set = EnvironmentArgs {
            environment: Some("2".into()),
            environment_strength: Some(2.0),
            environment_rotation: Some(2.0),
        };
        assert_eq!(args, set);
        assert_eq!(args.set("environment_strength", "bright").unwrap_err(), "expected a number, not \"bright\"");
    }
}
