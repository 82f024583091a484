//! A render's settings over a scene's own (`--photons`, `--bands`, … on
//! the command line; keyword arguments in Python), applied and validated
//! in one place so that every front end renders the same scene from the
//! same words, and a bad value is blamed on the setting that gave it.

use crate::scene_file::{SceneDocument, SceneFileError};
use prismatic_core::PreparedScene;
use prismatic_core::model::bands::BandSpec;
use prismatic_core::model::scene::{Estimator, PhotonSequence, RadiusMode, ViewPaths, WavelengthSampling};

/// Settings that override the scene's `[render]` table (`None`: the scene's).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Settings {
    /// Band table.
    pub bands: Option<BandSpec>,
    /// White photons a pass.
    pub photons: Option<u32>,
    /// Gather radius (with progressive radii: the largest first radius).
    pub radius: Option<f32>,
    /// Gather radii: progressive or fixed.
    pub radius_mode: Option<RadiusMode>,
    /// RNG seed.
    pub seed: Option<u32>,
    /// Gather estimator.
    pub estimator: Option<Estimator>,
    /// Light tracing of the caustics the camera sees directly.
    pub light_tracing: Option<bool>,
    /// Wavelength sampling at dispersive glass.
    pub wavelengths: Option<WavelengthSampling>,
    /// Where photons' emission and wavelength numbers come from.
    pub photon_sequence: Option<PhotonSequence>,
    /// How view rays sample the pixels.
    pub view_paths: Option<ViewPaths>,
    /// Image width.
    pub width: Option<u32>,
    /// Image height.
    pub height: Option<u32>,
}

/// Where settings come from, for error messages: the "file" an error names
/// and how a setting is spelled there.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SettingsSource {
    /// Command-line flags (`--radius-mode`).
    CommandLine,
    /// Python keyword arguments (`radius_mode`).
    Keywords,
}

impl SettingsSource {
    fn file(self) -> &'static str {
        match self {
            SettingsSource::CommandLine => "command line",
            SettingsSource::Keywords => "keyword arguments",
        }
    }

    fn spell(self, setting: &str) -> String {
        match self {
            SettingsSource::CommandLine => format!("--{}", setting.replace('_', "-")),
            SettingsSource::Keywords => setting.to_string(),
        }
    }
}

impl Settings {
    /// Applies the settings to `doc`'s scene, validates it and prepares it.
    /// An invalid value that a setting gave is reported against that
    /// setting (`source`), any other against the scene file.
    pub fn prepare(&self, mut doc: SceneDocument, source: SettingsSource) -> Result<PreparedScene, SceneFileError> {
        let r = &mut doc.scene.render;
        r.bands = self.bands.unwrap_or(r.bands);
        r.photons = self.photons.unwrap_or(r.photons);
        r.radius = self.radius.unwrap_or(r.radius);
        r.radius_mode = self.radius_mode.unwrap_or(r.radius_mode);
        r.seed = self.seed.unwrap_or(r.seed);
        r.estimator = self.estimator.unwrap_or(r.estimator);
        r.light_tracing = self.light_tracing.unwrap_or(r.light_tracing);
        r.wavelengths = self.wavelengths.unwrap_or(r.wavelengths);
        r.photon_sequence = self.photon_sequence.unwrap_or(r.photon_sequence);
        r.view_paths = self.view_paths.unwrap_or(r.view_paths);
        r.width = self.width.unwrap_or(r.width);
        r.height = self.height.unwrap_or(r.height);
        doc.validate().map_err(|e| self.blame(e, source))?;
        PreparedScene::new(doc.scene.clone()).map_err(|e| self.blame(doc.error(e), source))
    }

    /// A value that came from a setting is reported against the setting, not the scene file.
    fn blame(&self, e: SceneFileError, source: SettingsSource) -> SceneFileError {
        let given = [
            ("bands", self.bands.is_some()),
            ("photons", self.photons.is_some()),
            ("radius", self.radius.is_some()),
            ("radius_mode", self.radius_mode.is_some()),
            ("seed", self.seed.is_some()),
            ("estimator", self.estimator.is_some()),
            ("light_tracing", self.light_tracing.is_some()),
            ("wavelengths", self.wavelengths.is_some()),
            ("photon_sequence", self.photon_sequence.is_some()),
            ("view_paths", self.view_paths.is_some()),
            ("width", self.width.is_some()),
            ("height", self.height.is_some()),
        ];
        match given.iter().find(|(setting, set)| *set && e.key.strip_prefix("render.") == Some(setting)) {
            Some((setting, _)) => {
                SceneFileError { file: source.file().into(), line: None, key: source.spell(setting), reason: e.reason }
            }
            None => e,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_bad_setting_is_blamed_on_the_setting_as_its_source_spells_it() {
        let settings = Settings { radius_mode: Some(RadiusMode::Fixed), width: Some(0), ..Settings::default() };
        let doc = || crate::load_scene("sphere").unwrap();
        let e = settings.prepare(doc(), SettingsSource::CommandLine).unwrap_err();
        assert_eq!((e.file.as_str(), e.key.as_str()), ("command line", "--width"), "{e}");
        let e = settings.prepare(doc(), SettingsSource::Keywords).unwrap_err();
        assert_eq!((e.file.as_str(), e.key.as_str()), ("keyword arguments", "width"), "{e}");
    }

    #[test]
    fn settings_left_out_keep_the_scenes_values() {
        let doc = crate::load_scene("sphere").unwrap();
        let own = doc.scene.render.clone();
        let scene = Settings { photons: Some(1234), ..Settings::default() }.prepare(doc, SettingsSource::Keywords);
        let r = scene.unwrap().scene.render;
        assert_eq!((r.photons, r.width, r.bands, r.seed), (1234, own.width, own.bands, own.seed));
    }
}
