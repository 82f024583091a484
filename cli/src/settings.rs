//! A render's settings over a scene's own (`--photons`, `--bands`, … on
//! the command line; keyword arguments in Python), each written once in
//! the `settings!` list below: that one entry is the CLI flag (its help,
//! its parser), the scene file's key under `[render]`, the Python keyword,
//! how the setting is applied and how a bad value is blamed on it.

use crate::scene_file::{
    SceneDocument, SceneFileError, parse_bands, parse_estimator, parse_photon_sequence, parse_radius_mode,
    parse_tone_map, parse_view_paths, parse_wavelengths, parse_white_point,
};
use prismatic_core::PreparedScene;
use prismatic_core::model::bands::BandSpec;
use prismatic_core::model::color::ToneMap;
use prismatic_core::model::scene::{
    Estimator, PhotonSequence, RadiusMode, RenderSettings, ViewPaths, WavelengthSampling, WhitePoint, default_ambient,
};
use std::fmt;

/// A setting's value as a front end other than the command line hands it
/// over (Python's keywords): typed where the caller's language types it.
#[derive(Clone, Debug, PartialEq)]
pub enum SettingValue {
    /// A boolean.
    Bool(bool),
    /// A whole number.
    Int(i64),
    /// A number with a fraction.
    Float(f64),
    /// Anything else, as text (names such as `"paper7"` or `"fixed"`).
    Text(String),
}

impl fmt::Display for SettingValue {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SettingValue::Bool(true) => f.write_str("True"),
            SettingValue::Bool(false) => f.write_str("False"),
            SettingValue::Int(n) => write!(f, "{n}"),
            SettingValue::Float(x) => write!(f, "{x}"),
            SettingValue::Text(s) => f.write_str(s),
        }
    }
}

/// A type a setting can hold, read from a [`SettingValue`].
trait FromSetting: Sized {
    fn from_setting(value: &SettingValue) -> Result<Self, String>;
}

impl FromSetting for u32 {
    fn from_setting(value: &SettingValue) -> Result<Self, String> {
        match value {
            SettingValue::Int(n) => u32::try_from(*n).ok(),
            _ => None,
        }
        .ok_or_else(|| format!("must be a whole number ≥ 0, got {value}"))
    }
}

impl FromSetting for f32 {
    fn from_setting(value: &SettingValue) -> Result<Self, String> {
        match value {
            SettingValue::Int(n) => Ok(*n as f32),
            SettingValue::Float(x) => Ok(*x as f32),
            _ => Err(format!("must be a number, got {value}")),
        }
    }
}

impl FromSetting for bool {
    fn from_setting(value: &SettingValue) -> Result<Self, String> {
        match value {
            SettingValue::Bool(b) => Ok(*b),
            _ => Err(format!("must be True or False, got {value}")),
        }
    }
}

/// Named values (`"paper7"`, `16`, `"fixed"`): read from their text with
/// the scene file's parser.
macro_rules! from_name {
    ($($ty:ty = $parse:path),* $(,)?) => {$(
        impl FromSetting for $ty {
            fn from_setting(value: &SettingValue) -> Result<Self, String> {
                $parse(&value.to_string())
            }
        }
    )*};
}

from_name!(
    BandSpec = parse_bands,
    RadiusMode = parse_radius_mode,
    Estimator = parse_estimator,
    WavelengthSampling = parse_wavelengths,
    PhotonSequence = parse_photon_sequence,
    ViewPaths = parse_view_paths,
    WhitePoint = parse_white_point,
    ToneMap = parse_tone_map,
);

/// The one list of settings. Each entry's doc comment is the CLI's help
/// text, its `#[arg]` the flag's parser, and its name the field of
/// [`RenderSettings`] it overrides, the scene file's key under `[render]`
/// and the Python keyword.
macro_rules! settings {
    ($( $(#[doc = $doc:literal])* #[arg($($arg:tt)*)] $name:ident: $ty:ty, )*) => {
        /// Settings that override the scene's `[render]` table (`None`: the scene's).
        #[derive(Clone, Debug, Default, PartialEq, clap::Args)]
        pub struct Settings {
            $( $(#[doc = $doc])* #[arg($($arg)*)] pub $name: Option<$ty>, )*
        }

        impl Settings {
            /// Every setting's name: the Python keyword and the key under `[render]`.
            pub const NAMES: &'static [&'static str] = &[$(stringify!($name)),*];

            /// Sets setting `name` from a front end's `value`; the reason
            /// when there is no such setting or the value is not one.
            pub fn set(&mut self, name: &str, value: &SettingValue) -> Result<(), String> {
                match name {
                    $( stringify!($name) => self.$name = Some(FromSetting::from_setting(value)?), )*
                    _ => return Err("no such setting".into()),
                }
                Ok(())
            }

            /// Overrides `render`'s values with the settings given.
            fn apply(&self, render: &mut RenderSettings) {
                $( if let Some(v) = self.$name { render.$name = v; } )*
            }

            /// The names of the settings given.
            fn given(&self) -> Vec<&'static str> {
                let mut given = Vec::new();
                $( if self.$name.is_some() { given.push(stringify!($name)); } )*
                given
            }
        }
    };
}

settings! {
    /// Band table: paper3, paper7 or a number of physically based bands.
    #[arg(long, value_parser = parse_bands)]
    bands: BandSpec,
    /// White photons to emit.
    #[arg(long)]
    photons: u32,
    /// Photons a pass traces for indirect light (0: none): light bounced
    /// off diffuse surfaces. Without an ambient in the scene file, on
    /// sets it to 0 and off to its default.
    #[arg(long)]
    indirect_photons: u32,
    /// Gather radius (with progressive radii: the largest first radius).
    #[arg(long)]
    radius: f32,
    /// Gather radii: progressive (per point, shrinking pass by pass) or
    /// fixed (the scene's radius everywhere, the paper's frame).
    #[arg(long, value_parser = parse_radius_mode)]
    radius_mode: RadiusMode,
    /// RNG seed.
    #[arg(long)]
    seed: u32,
    /// Gather estimator: paper or density.
    #[arg(long, value_parser = parse_estimator)]
    estimator: Estimator,
    /// Light tracing (true or false): connect the caustic photons on
    /// surfaces the camera sees directly to the camera; gather only behind
    /// mirrors and glass.
    #[arg(long)]
    light_tracing: bool,
    /// Wavelength sampling at dispersive glass: split, random_band, continuous or hero.
    #[arg(long, value_parser = parse_wavelengths)]
    wavelengths: WavelengthSampling,
    /// Where photons' emission directions and wavelengths come from: sobol
    /// (Owen-scrambled, stratified per pass) or random.
    #[arg(long, value_parser = parse_photon_sequence)]
    photon_sequence: PhotonSequence,
    /// How view rays sample the pixels: centre (once per render, through
    /// pixel centres, split into every band at dispersive glass), hero
    /// (each pass anew through pixel centres, 4 hero wavelengths at
    /// dispersive glass) or sampled (as hero, jittered in the pixel;
    /// anti-aliased).
    #[arg(long, value_parser = parse_view_paths)]
    view_paths: ViewPaths,
    /// The spectrum that renders neutral: E (equal energy, the paper's
    /// white; the default) or D65 (sRGB's white).
    #[arg(long, value_parser = parse_white_point)]
    white_point: WhitePoint,
    /// How the PNG shows the linear image: clamp, reinhard, pbr_neutral
    /// (Khronos PBR Neutral, the glTF sample viewer's) or agx. An EXR
    /// stays linear.
    #[arg(long, value_parser = parse_tone_map)]
    tone_map: ToneMap,
    /// Automatic exposure (true or false): the PNG is scaled so that the
    /// image's log-average luminance is middle grey (0.18).
    #[arg(long)]
    auto_exposure: bool,
    /// Suns an environment light is cut into (its median cut, 1 to 4096):
    /// each is one more shadow ray at every point the camera sees. With
    /// per-pass view paths (the default) each pass draws them anew inside
    /// their regions, so more lower the noise of the sky's shadows; with
    /// centre view paths they stay fixed, and more follow the sky's light
    /// and soft shadows more closely.
    #[arg(long)]
    environment_lights: u32,
    /// Pieces the emissive meshes' triangles are cut into for direct light
    /// (1 to 4096): more draw their soft shadows more finely, each one more
    /// shadow ray at every point the camera sees; with more emissive
    /// triangles than this, each pass chooses that many by power.
    #[arg(long)]
    area_lights: u32,
    /// Image width.
    #[arg(long)]
    width: u32,
    /// Image height.
    #[arg(long)]
    height: u32,
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

    /// `setting` as this source spells it (`--radius-mode`, `radius_mode`).
    pub fn spell(self, setting: &str) -> String {
        match self {
            SettingsSource::CommandLine => format!("--{}", setting.replace('_', "-")),
            SettingsSource::Keywords => setting.to_string(),
        }
    }

    /// An error in setting `setting` as this source spells it.
    pub fn error(self, setting: &str, reason: impl Into<String>) -> SceneFileError {
        SceneFileError { file: self.file().into(), line: None, key: self.spell(setting), reason: reason.into() }
    }
}

impl Settings {
    /// Applies the settings to `doc`'s scene, validates it and prepares it.
    /// An invalid value that a setting gave is reported against that
    /// setting (`source`), any other against the scene file.
    pub fn prepare(&self, mut doc: SceneDocument, source: SettingsSource) -> Result<PreparedScene, SceneFileError> {
        self.apply(&mut doc.scene.render);
        if let Some(indirect) = self.indirect_photons
            && !doc.names("render.ambient")
        {
            doc.scene.render.ambient = default_ambient(indirect);
        }
        doc.validate().map_err(|e| self.blame(e, source))?;
        PreparedScene::new(doc.scene.clone()).map_err(|e| self.blame(doc.error(e), source))
    }

    /// A value that came from a setting is reported against the setting, not the scene file.
    fn blame(&self, e: SceneFileError, source: SettingsSource) -> SceneFileError {
        match self.given().into_iter().find(|setting| e.key.strip_prefix("render.") == Some(setting)) {
            Some(setting) => source.error(setting, e.reason),
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

    #[test]
    fn every_setting_is_a_flag_and_a_keyword() {
        use clap::CommandFactory;
        #[derive(clap::Parser)]
        struct Flags {
            #[command(flatten)]
            settings: Settings,
        }
        let command = Flags::command();
        let flags: Vec<String> = command.get_arguments().filter_map(|a| a.get_long()).map(String::from).collect();
        let spelled: Vec<String> = Settings::NAMES.iter().map(|n| n.replace('_', "-")).collect();
        assert_eq!(flags, spelled);
        for name in Settings::NAMES {
            let mut settings = Settings::default();
            let value = match *name {
                "bands" => SettingValue::Text("paper7".into()),
                "radius" => SettingValue::Float(0.05),
                "radius_mode" => SettingValue::Text("fixed".into()),
                "estimator" => SettingValue::Text("density".into()),
                "light_tracing" => SettingValue::Bool(false),
                "wavelengths" => SettingValue::Text("split".into()),
                "photon_sequence" => SettingValue::Text("random".into()),
                "view_paths" => SettingValue::Text("sampled".into()),
                "white_point" => SettingValue::Text("D65".into()),
                "tone_map" => SettingValue::Text("agx".into()),
                "auto_exposure" => SettingValue::Bool(true),
                _ => SettingValue::Int(64),
            };
            settings.set(name, &value).unwrap_or_else(|e| panic!("{name}: {e}"));
            assert_eq!(settings.given(), [*name]);
        }
    }

    #[test]
    fn a_value_of_the_wrong_kind_says_what_the_setting_takes() {
        let mut s = Settings::default();
        assert_eq!(s.set("photon_count", &SettingValue::Int(1)).unwrap_err(), "no such setting");
        assert!(s.set("photons", &SettingValue::Int(-1)).unwrap_err().contains("whole number"));
        assert!(s.set("light_tracing", &SettingValue::Int(1)).unwrap_err().contains("True or False"));
        assert!(s.set("radius", &SettingValue::Text("far".into())).unwrap_err().contains("must be a number"));
        assert!(s.set("bands", &SettingValue::Int(16)).is_ok());
        assert_eq!(s.bands, Some(BandSpec::Physical(16)));
    }
}
