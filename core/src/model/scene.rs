//! The scene model: what a scene file or an engine describes, as plain
//! data. [`crate::model::validate`] checks it; [`crate::plan::prepared`] derives what
//! tracing needs from it.

use crate::model::bands::BandSpec;
use crate::model::color::{Display, ToneMap};
use crate::model::dispersion::Dispersion;
pub use crate::model::environment::EnvironmentMap;
use crate::model::metalness::Metalness;
use crate::model::metals::MetalColor;
use crate::model::spectrum::Illuminant;
pub use crate::model::spectrum::Spectrum;
use alloc::string::String;
use alloc::sync::Arc;
use alloc::vec::Vec;
use core::fmt;
use glam::{Vec2, Vec3, Vec4};

/// Most triangles one mesh may have: the CPU backend carries a hit's
/// triangle index in f32 lanes (the tie rule of
/// [`NearestTriangle`](crate::geometry::triangle::NearestTriangle)), exact up to 2²⁴.
pub const MAX_MESH_TRIANGLES: usize = 1 << 24;

/// The most white photons one render may emit (each may store up to N band
/// photons of 32 bytes: beyond this the map would not fit in memory).
pub const MAX_PHOTONS: u32 = 100_000_000;

/// The largest allowed trace depth (specular bounces per path).
pub const MAX_DEPTH: u32 = 64;

/// The largest image side.
pub const MAX_IMAGE_SIDE: u32 = 16_384;

/// The largest texture side: 4096² texels of 4 bytes are 64 MiB, half of
/// what a GPU storage binding holds by default (128 MiB).
pub const MAX_TEXTURE_SIDE: u32 = 4_096;
/// The thickest thin film a scene may state, in nanometres: beyond tens of
/// micrometres its fringes are finer than any band resolves.
pub const MAX_FILM_NM: f32 = 20_000.0;

/// A problem found in a scene: the key it belongs to and why it is wrong.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{key}: {reason}")]
pub struct SceneError {
    /// Dotted key of the offending value, as in the scene file (`light[0].cone_deg`).
    pub key: String,
    /// What is wrong with it.
    pub reason: String,
}

impl SceneError {
    /// A new error for `key`.
    pub fn new(key: impl Into<String>, reason: impl Into<String>) -> Self {
        SceneError { key: key.into(), reason: reason.into() }
    }
}

/// Which gather estimator turns caustic photons into colour.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Estimator {
    /// The paper's: hue from band counts (W/Total), strength from photon density.
    Paper,
    /// Per-band flux density Σ Φ / (π r²) through the band weights.
    Density,
}

impl Estimator {
    /// The scene-file name.
    pub fn name(self) -> &'static str {
        match self {
            Estimator::Paper => "paper",
            Estimator::Density => "density",
        }
    }
}

/// How a white photon's spectrum is sampled at the first dispersive glass.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum WavelengthSampling {
    /// Split into all N bands, each with 1/N of the flux (the paper's method).
    #[default]
    Split,
    /// Continue as one band chosen uniformly at random, carrying the whole
    /// flux (1/N × N): N times fewer paths, more colour noise.
    RandomBand,
    /// One random band as in `RandomBand`, traced at a wavelength drawn
    /// uniformly from the band's interval: stripes become continuous while
    /// colours keep the band's weight.
    Continuous,
    /// Hero wavelengths (Wilkie et al. 2014) for photons: the white photon
    /// splits into [`HERO_WAVELENGTHS`] paths (at most N) at continuous
    /// wavelengths, one in each equal share of the spectrum, all rotated by
    /// one number per photon, each with 1/M of the flux. Converges to the
    /// continuous spectrum like `Continuous`, with M stratified wavelengths
    /// a photon instead of one: far less colour noise for M paths, not N.
    Hero,
}

/// Wavelengths a white photon carries on with [`WavelengthSampling::Hero`]
/// (fewer when the band table has fewer bands): four, as in Wilkie et al.
pub const HERO_WAVELENGTHS: u32 = 4;

impl WavelengthSampling {
    /// The scene-file name.
    pub fn name(self) -> &'static str {
        match self {
            WavelengthSampling::Split => "split",
            WavelengthSampling::RandomBand => "random_band",
            WavelengthSampling::Continuous => "continuous",
            WavelengthSampling::Hero => "hero",
        }
    }

    /// Parses a scene-file name.
    pub fn from_name(name: &str) -> Option<Self> {
        WavelengthSampling::ALL.into_iter().find(|w| w.name() == name)
    }

    /// Every sampling, in the order the documentation lists them.
    pub const ALL: [WavelengthSampling; 4] = [
        WavelengthSampling::Split,
        WavelengthSampling::RandomBand,
        WavelengthSampling::Continuous,
        WavelengthSampling::Hero,
    ];

    /// The paths a white photon continues as at dispersive glass, with a
    /// table of `bands` bands: all of them, [`HERO_WAVELENGTHS`] (at most
    /// `bands`), or one.
    pub fn paths(self, bands: usize) -> u32 {
        match self {
            WavelengthSampling::Split => bands as u32,
            WavelengthSampling::Hero => HERO_WAVELENGTHS.min(bands as u32),
            WavelengthSampling::RandomBand | WavelengthSampling::Continuous => 1,
        }
    }

    /// Whether a photon is traced at its own wavelength (within its band).
    pub fn continuous(self) -> bool {
        matches!(self, WavelengthSampling::Continuous | WavelengthSampling::Hero)
    }
}

/// Where the numbers of a photon's emission and wavelength come from.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum PhotonSequence {
    /// Independent counter-based random numbers ([`crate::util::rng`]).
    Random,
    /// Owen-scrambled Sobol points, one scramble per pass ([`crate::sampling::sobol`]):
    /// a pass's directions and wavelengths are stratified jointly, so each
    /// pass is less noisy; the photon paths' later decisions stay random.
    #[default]
    Sobol,
}

impl PhotonSequence {
    /// The scene-file name.
    pub fn name(self) -> &'static str {
        match self {
            PhotonSequence::Random => "random",
            PhotonSequence::Sobol => "sobol",
        }
    }

    /// Parses a scene-file name.
    pub fn from_name(name: &str) -> Option<Self> {
        [PhotonSequence::Random, PhotonSequence::Sobol].into_iter().find(|s| s.name() == name)
    }
}

/// How a pass's view rays sample each pixel.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ViewPaths {
    /// One ray through each pixel's centre, traced once per render: both
    /// Fresnel branches at glass, one ray per band at the first dispersive
    /// glass (the paper's view rays; exact for what a pixel centre sees,
    /// staircases at edges).
    Centre,
    /// Each pass traces its own view rays ([`crate::render::view`]) as
    /// [`ViewPaths::Centre`] does (through the pixel centres, both Fresnel
    /// branches at glass), but at the first dispersive glass a ray takes
    /// 4 hero wavelengths, not every band (their shift stratified across
    /// passes, each at its own index with continuous wavelengths). The
    /// passes' mean converges to what the pixel centre sees of the
    /// continuous spectrum, whatever the band count, and the first image
    /// does not wait for every band's rays.
    #[default]
    Hero,
    /// As [`ViewPaths::Hero`], through a point jittered inside the pixel
    /// (stratified across passes), one Fresnel branch at glass chosen with
    /// its probability. The passes' mean converges to the
    /// box-filtered image: edges, textures and the view through glass
    /// anti-aliased, the same filter as light tracing's splats.
    Sampled,
}

impl ViewPaths {
    /// Every kind, in the order the scene reference lists them.
    pub const ALL: [ViewPaths; 3] = [ViewPaths::Centre, ViewPaths::Hero, ViewPaths::Sampled];

    /// The scene-file name.
    pub fn name(self) -> &'static str {
        match self {
            ViewPaths::Centre => "centre",
            ViewPaths::Hero => "hero",
            ViewPaths::Sampled => "sampled",
        }
    }

    /// Parses a scene-file name.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|v| v.name() == name)
    }

    /// Whether each pass traces its own view paths (with
    /// [`crate::sampling::pixel_sample::PixelSampler`]'s numbers).
    pub fn per_pass(self) -> bool {
        self != ViewPaths::Centre
    }

    /// Whether a pass's path starts at a point jittered inside its pixel
    /// and takes one Fresnel branch at glass (rather than the centre and both).
    pub fn jittered(self) -> bool {
        self == ViewPaths::Sampled
    }
}

/// The spectrum a render shows as neutral: the image's channels are
/// scaled so that light of this spectrum on a grey surface is grey.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum WhitePoint {
    /// The equal-energy spectrum: the paper's white, and what every light
    /// without a spectrum emits, so white light stays (1, 1, 1) exactly.
    #[default]
    E,
    /// CIE D65, the white point sRGB defines (a display's white): daylight
    /// renders neutral, equal-energy light slightly warm.
    D65,
}

impl WhitePoint {
    /// The scene-file name.
    pub fn name(self) -> &'static str {
        match self {
            WhitePoint::E => "E",
            WhitePoint::D65 => "D65",
        }
    }

    /// Parses a scene-file name.
    pub fn from_name(name: &str) -> Option<Self> {
        [WhitePoint::E, WhitePoint::D65].into_iter().find(|w| w.name() == name)
    }

    /// The spectrum that renders neutral.
    pub fn spectrum(self) -> Spectrum {
        match self {
            WhitePoint::E => Spectrum::EqualEnergy,
            WhitePoint::D65 => Spectrum::Illuminant(Illuminant::D65),
        }
    }
}

/// Hachisuka et al.'s recommended fraction of photons kept per pass: how
/// fast progressive radii shrink by default.
pub const DEFAULT_ALPHA: f32 = 0.7;

/// Independent photon paths a visible point's first radius should hold
/// by default (Jensen's caustic gathers use 50–100 nearest photons).
pub const DEFAULT_NEIGHBOURS: u32 = 32;

/// Directional lights an environment is drawn as by default: its median
/// cut into 32 regions (a constant sky's irradiance exact on a floor, within
/// 5 % on a tilted plane; 32 shadow rays per visible point).
pub const DEFAULT_ENVIRONMENT_LIGHTS: u32 = 32;

/// The most directional lights an environment may be drawn as.
pub const MAX_ENVIRONMENT_LIGHTS: u32 = 4_096;

/// Pieces emissive triangles are cut into by default for direct light:
/// 16 shadow rays per visible point; the unblocked irradiance is exact at
/// any count, so the count sets only how finely soft shadows are drawn.
pub const DEFAULT_AREA_LIGHTS: u32 = 16;

/// The most pieces emissive triangles are cut into (more emissive
/// triangles than the setting: a choice of that many by power, carrying
/// the whole flux, anew each pass; [`crate::plan::drawn_triangles`]).
pub const MAX_AREA_LIGHTS: u32 = 4_096;

/// The ambient irradiance factor a scene gets when it names none: 0.03 of
/// the albedo as a stand-in for indirect light, none when indirect light
/// is simulated (`indirect_photons` > 0).
pub fn default_ambient(indirect_photons: u32) -> f32 {
    if indirect_photons > 0 { 0.0 } else { 0.03 }
}

/// How a render's gather radii behave from pass to pass.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum RadiusMode {
    /// Progressive photon mapping: a pilot pass gives each visible point
    /// its own first radius (at most `radius`), and the radii shrink with
    /// `alpha` from pass to pass, so the mean converges to the caustic.
    #[default]
    Progressive,
    /// The paper's fixed radius: every pass gathers within `radius` at
    /// every point. One pass is the paper's frame; more passes average
    /// independent frames (less noise, the same blur).
    Fixed,
}

impl RadiusMode {
    /// The scene-file name.
    pub fn name(self) -> &'static str {
        match self {
            RadiusMode::Progressive => "progressive",
            RadiusMode::Fixed => "fixed",
        }
    }

    /// Parses a scene-file name.
    pub fn from_name(name: &str) -> Option<Self> {
        [RadiusMode::Progressive, RadiusMode::Fixed].into_iter().find(|m| m.name() == name)
    }
}

/// Image and photon-pass settings (`[render]`).
#[derive(Clone, Debug, PartialEq)]
pub struct RenderSettings {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// White photons emitted (over all lights).
    pub photons: u32,
    /// Photons a pass traces for indirect light (0: none), besides the
    /// caustic `photons`: emitted over the lights' whole distributions,
    /// each at one wavelength, bouncing off diffuse surfaces and stored at
    /// every diffuse hit after its first ([`crate::photons::indirect`]).
    pub indirect_photons: u32,
    /// Gather radius in world units (with progressive radii: the largest first radius).
    pub radius: f32,
    /// Fixed or progressive gather radii.
    pub radius_mode: RadiusMode,
    /// The band table.
    pub bands: BandSpec,
    /// The gather estimator.
    pub estimator: Estimator,
    /// Light tracing: each caustic photon on a diffuse surface the camera
    /// sees directly is connected to the camera and added to its pixel
    /// (unbiased, no radius); only the diffuse surfaces seen through
    /// mirrors and glass gather photons (see [`crate::photons::light_tracing`]).
    pub light_tracing: bool,
    /// How white photons sample the spectrum at dispersive glass.
    pub wavelengths: WavelengthSampling,
    /// Where photons' emission and wavelength numbers come from.
    pub photon_sequence: PhotonSequence,
    /// How view rays sample the pixels: once through their centres, or
    /// anew each pass.
    pub view_paths: ViewPaths,
    /// Seed of the counter-based RNG.
    pub seed: u32,
    /// Most specular interactions on a photon path or view ray.
    pub max_depth: u32,
    /// Uniform ambient irradiance factor (fraction of albedo added
    /// everywhere), a stand-in for indirect light: scene files and glTF
    /// files default it to 0 when `indirect_photons` is on.
    pub ambient: f32,
    /// Multiplier applied to radiance before the sRGB encoding.
    pub exposure: f32,
    /// Radiance of rays that leave the scene.
    pub background: Vec3,
    /// How radiance becomes displayable.
    pub tone_map: ToneMap,
    /// Whether the displayed image is scaled so that its log-average
    /// luminance is middle grey ([`crate::model::color::auto_exposure`]),
    /// after `exposure`, as viewers show a file that brings no exposure.
    /// Only the picture changes (an EXR stays linear).
    pub auto_exposure: bool,
    /// The spectrum that renders neutral (white balance).
    pub white_point: WhitePoint,
    /// Aim caustic photons only at mirrors and glass (projection maps).
    pub projection_maps: bool,
    /// Photon passes a render runs by default (each emits `photons`).
    pub passes: u32,
    /// How fast progressive radii shrink: r_k² ∝ Π (j + α)/(j + 1), 0 < α ≤ 1
    /// (1 keeps them; smaller shrinks faster, less blur, more noise).
    pub alpha: f32,
    /// Independent photon paths a progressive render's first radius should
    /// hold (more: smoother early passes, more blur until the radii shrink).
    pub neighbours: u32,
    /// Directional lights an environment light is drawn as (its median
    /// cut: more, softer shadows and a closer irradiance, each a shadow ray
    /// per visible point).
    pub environment_lights: u32,
    /// Pieces the emissive meshes' triangles are cut into for direct light:
    /// each lights a point with its exact unblocked irradiance, seen or
    /// shadowed from its centre (more: finer soft shadows, each a shadow
    /// ray per visible point). With more emissive triangles than this, a
    /// choice of this many by power carries their whole flux, made anew
    /// each pass with per-pass view paths.
    pub area_lights: u32,
}

/// The default settings are the fastest configuration measured that
/// converges to the true spectrum (README, "What accuracy costs" and
/// "Against LuxCore, at equal error"): light tracing where the camera sees
/// the caustic, 32 physically based bands with hero wavelengths (the
/// continuous spectrum for 4 paths a photon, not 32 lines), the density
/// estimator, Sobol photons, progressive radii, hero view paths (each
/// pass's own, through the pixel centres), shown through Khronos PBR
/// Neutral (the glTF sample viewer's tone map: colours below 0.76 as they
/// are, caustic highlights rolled off instead of clipped).
/// [`RenderSettings::paper`] is the paper's method.
impl Default for RenderSettings {
    fn default() -> Self {
        RenderSettings {
            bands: BandSpec::Physical(32),
            estimator: Estimator::Density,
            light_tracing: true,
            wavelengths: WavelengthSampling::Hero,
            view_paths: ViewPaths::Hero,
            tone_map: ToneMap::PbrNeutral,
            ..RenderSettings::paper()
        }
    }
}

impl RenderSettings {
    /// How the image is shown.
    pub fn display(&self) -> Display {
        Display { tone_map: self.tone_map, auto_exposure: self.auto_exposure }
    }

    /// The paper's method at the default image size and photon count: the
    /// seven bands of its Table 3, every photon split into all of them at
    /// the glass and gathered everywhere with the paper's estimator (no
    /// light tracing), view rays through the pixel centres.
    pub fn paper() -> Self {
        RenderSettings {
            width: 400,
            height: 400,
            photons: 100_000,
            indirect_photons: 0,
            radius: 0.05,
            radius_mode: RadiusMode::Progressive,
            bands: BandSpec::Paper7,
            estimator: Estimator::Paper,
            light_tracing: false,
            wavelengths: WavelengthSampling::Split,
            photon_sequence: PhotonSequence::Sobol,
            view_paths: ViewPaths::Centre,
            seed: 1,
            max_depth: 12,
            ambient: default_ambient(0),
            exposure: 1.0,
            background: Vec3::ZERO,
            tone_map: ToneMap::Clamp,
            auto_exposure: false,
            white_point: WhitePoint::E,
            projection_maps: true,
            passes: 16,
            alpha: DEFAULT_ALPHA,
            neighbours: DEFAULT_NEIGHBOURS,
            environment_lights: DEFAULT_ENVIRONMENT_LIGHTS,
            area_lights: DEFAULT_AREA_LIGHTS,
        }
    }
}

/// A pinhole camera (`[camera]`).
#[derive(Clone, Debug, PartialEq)]
pub struct Camera {
    /// Eye position.
    pub position: Vec3,
    /// Point the camera looks at.
    pub look_at: Vec3,
    /// Up direction (need not be orthogonal to the view direction).
    pub up: Vec3,
    /// Vertical field of view in degrees.
    pub fov_deg: f32,
}

/// A light source (`[[light]]`). Power is radiant flux in watts.
#[derive(Clone, Debug, PartialEq)]
pub enum Light {
    /// The paper's spot light: uniform intensity inside a cone.
    Spot {
        /// Apex of the cone.
        position: Vec3,
        /// Axis of the cone.
        direction: Vec3,
        /// Half-angle of the cone in degrees.
        cone_deg: f32,
        /// Half-angle in degrees within which the intensity is full (glTF's
        /// `innerConeAngle`); between it and `cone_deg` it falls off
        /// smoothly ([`crate::sampling::spot_cone::SpotCone`]). Equal to
        /// `cone_deg`: a hard edge (the paper's spot).
        inner_cone_deg: f32,
        /// Flux in W.
        power: f32,
        /// What it emits across the spectrum.
        spectrum: Spectrum,
        /// The distance its light reaches ([`crate::model::light_range`]);
        /// `None`: every distance.
        range: Option<f32>,
    },
    /// Isotropic point light.
    Point {
        /// Position.
        position: Vec3,
        /// Flux in W.
        power: f32,
        /// What it emits across the spectrum.
        spectrum: Spectrum,
        /// The distance its light reaches ([`crate::model::light_range`]);
        /// `None`: every distance.
        range: Option<f32>,
    },
    /// Collimated beam leaving a disc (prism experiments, rainbows).
    Beam {
        /// Centre of the emitting disc.
        position: Vec3,
        /// Direction of travel (the disc's normal).
        direction: Vec3,
        /// Radius of the disc.
        radius: f32,
        /// Flux in W.
        power: f32,
        /// What it emits across the spectrum.
        spectrum: Spectrum,
    },
    /// Light from every direction: an environment map (HDR image-based
    /// lighting, or the built-in studio). Rays that leave the scene see it
    /// (through glass too, each wavelength along its own path); it lights
    /// diffuse surfaces and sends caustic photons as the directional
    /// lights of its median cut ([`crate::sampling::environment`]).
    Environment {
        /// Radiance per direction (before `strength`).
        map: EnvironmentMap,
        /// Multiplies the map's radiance.
        strength: f32,
        /// Turns the map about +y, in degrees (positive: counter-clockwise seen from above).
        rotation_deg: f32,
        /// The spectrum of a white texel: equal energy (the default) gives
        /// each part of the map the smooth spectrum of its colour; another
        /// spectrum is emitted at each part's luminance.
        spectrum: Spectrum,
    },
    /// A Lambertian emitting triangle, lit on the side its winding faces
    /// ((b − a) × (c − a)) with radiance `power` / (π · area). Not written
    /// in scene files: a mesh whose material has an `emission` becomes these
    /// ([`crate::plan::prepared::PreparedScene::lights`]).
    Area {
        /// Its corners a, b, c.
        vertices: [Vec3; 3],
        /// Flux in W (out of its front face).
        power: f32,
        /// What it emits across the spectrum.
        spectrum: Spectrum,
        /// Its shadows' point of the pass, a + s(b − a) + t(c − a) for
        /// `Some([s, t])` (drawn anew each pass, [`crate::plan::area_aims`]);
        /// `None`: shadow rays aim at the centre of the part a point sees.
        aim: Option<[f32; 2]>,
    },
    /// Parallel light from one direction (the sun, glTF's directional
    /// light): it lights everything it reaches, with `irradiance` on a
    /// surface that faces it. Its photons leave a disc over the scene's
    /// mirrors and glass ([`crate::plan::reach::sun_beam`]).
    Sun {
        /// Direction of travel (from the sun into the scene).
        direction: Vec3,
        /// Irradiance in W/m² on a surface facing the sun.
        irradiance: f32,
        /// What it emits across the spectrum.
        spectrum: Spectrum,
        /// For an environment's sun drawn anew each pass: the mean over the
        /// draws of its direction toward the light (shorter than 1), which
        /// makes its direct light a control variate
        /// ([`crate::plan::drawn_suns`]); `None` for any other sun.
        mean_toward: Option<Vec3>,
    },
}

impl Light {
    /// Whether no ray can meet it ([`Light::hidden_direction`]): its light
    /// reaches the camera off a rough surface only by a ray sent toward
    /// it, or by light tracing's photons
    /// ([`crate::photons::light_tracing`]).
    pub fn is_hidden(&self) -> bool {
        matches!(
            self,
            Light::Spot { .. } | Light::Point { .. } | Light::Beam { .. } | Light::Sun { mean_toward: None, .. }
        )
    }

    /// The direction from `p` toward a light that no ray can meet, whose
    /// light reaches a glossy surface only by a ray sent toward it: a
    /// spot's, a point's, a beam's and a sun's of its own. `None` for the
    /// lights that rays see: area lights, and environments with the suns
    /// they are drawn as.
    pub fn hidden_direction(&self, p: Vec3) -> Option<Vec3> {
        match self {
            Light::Spot { position, .. } | Light::Point { position, .. } => (*position - p).try_normalize(),
            Light::Beam { direction, .. } | Light::Sun { direction, mean_toward: None, .. } => {
                Some(-direction.normalize())
            }
            _ => None,
        }
    }

    /// The light's flux in W; a sun's (and an environment's) depends on
    /// how much of the scene it covers and is its beam's
    /// ([`crate::plan::prepared::PreparedScene::emitters`]), so 0 here.
    pub fn power(&self) -> f32 {
        match self {
            Light::Spot { power, .. }
            | Light::Point { power, .. }
            | Light::Beam { power, .. }
            | Light::Area { power, .. } => *power,
            Light::Sun { .. } | Light::Environment { .. } => 0.0,
        }
    }

    /// The distance its light reaches (spot and point lights with a range).
    pub fn range(&self) -> Option<f32> {
        match self {
            Light::Spot { range, .. } | Light::Point { range, .. } => *range,
            _ => None,
        }
    }

    /// What it emits across the spectrum.
    pub fn spectrum(&self) -> &Spectrum {
        match self {
            Light::Spot { spectrum, .. }
            | Light::Point { spectrum, .. }
            | Light::Beam { spectrum, .. }
            | Light::Area { spectrum, .. }
            | Light::Sun { spectrum, .. }
            | Light::Environment { spectrum, .. } => spectrum,
        }
    }

    /// What it emits across the spectrum, to change.
    pub fn spectrum_mut(&mut self) -> &mut Spectrum {
        match self {
            Light::Spot { spectrum, .. }
            | Light::Point { spectrum, .. }
            | Light::Beam { spectrum, .. }
            | Light::Area { spectrum, .. }
            | Light::Sun { spectrum, .. }
            | Light::Environment { spectrum, .. } => spectrum,
        }
    }
}

/// A checker texture on a diffuse material.
#[derive(Clone, Debug, PartialEq)]
pub struct Checker {
    /// Edge length of one square.
    pub size: f32,
    /// Albedo of the alternate squares.
    pub albedo: Vec3,
    /// Added to a point before the pattern is evaluated: a scene recentred
    /// on a new origin sets it to that origin modulo two squares, so the
    /// squares stay where they are in the world.
    pub offset: Vec3,
}

/// A base-colour image on a diffuse material (glTF's `baseColorTexture`),
/// read at a mesh's texture coordinates: the albedo is multiplied by it.
#[derive(Clone, Debug, PartialEq)]
pub struct Texture {
    /// Where the image came from (a file, a glTF image), for messages.
    pub name: String,
    /// Texels per row.
    pub width: u32,
    /// Rows.
    pub height: u32,
    /// Texels row by row from the top (v = 0, as in glTF), each the 8-bit
    /// sRGB-encoded channels packed as `r | g << 8 | b << 16`. Shared, so
    /// that cloning a scene does not copy images.
    pub texels: Arc<[u32]>,
    /// How texels are looked up.
    pub sampler: Sampler,
}

/// A tangent-space normal map (glTF's `normalTexture`), read at a mesh's
/// texture coordinates: each texel's channels, linear (not sRGB), encode a
/// normal's X, Y and Z in the surface's tangent frame, 0..255 for −1..1
/// (+X along the tangent, +Y along the bitangent, up the image; +Z the
/// surface's normal). The surface scatters light about the normal it gives
/// ([`crate::geometry::normal_map`]).
#[derive(Clone, Debug, PartialEq)]
pub struct NormalMap {
    /// The image (its `texels` hold the linear channels).
    pub texture: Texture,
    /// glTF's `scale`: multiplies X and Y, so 0 is the plain surface and
    /// larger values tilt its normals further.
    pub scale: f32,
}

/// How a texture is read between and beyond its texels (glTF's sampler).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Sampler {
    /// Between texels.
    pub filter: Filter,
    /// Beyond the image along u.
    pub wrap_u: Wrap,
    /// Beyond the image along v.
    pub wrap_v: Wrap,
}

/// Texture filtering (no mipmaps: a minified texture is read like a magnified one).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Filter {
    /// The texel the point falls in.
    Nearest,
    /// Bilinear interpolation of the four nearest texels, in linear light.
    #[default]
    Linear,
}

/// What a texture coordinate outside [0, 1] reads.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Wrap {
    /// The image tiles the plane.
    #[default]
    Repeat,
    /// The edge texels extend outward.
    ClampToEdge,
    /// The image tiles the plane, every other copy mirrored.
    MirroredRepeat,
}

/// How a surface scatters light.
#[derive(Clone, Debug, PartialEq)]
pub enum MaterialKind {
    /// Lambertian, optionally with a checker or an image texture. Caustic
    /// photons are stored here.
    Diffuse {
        /// Albedo (reflectance) per RGB channel.
        albedo: Vec3,
        /// Optional checker texture.
        checker: Option<Checker>,
        /// Optional image multiplying the albedo (on meshes with texture coordinates).
        texture: Option<Texture>,
        /// Radiance the surface emits from its front faces, per linear RGB
        /// channel (glTF's `emissiveFactor` × `KHR_materials_emissive_strength`;
        /// zero for most surfaces). A mesh with it is an area light: its
        /// triangles light the scene and emit photons
        /// ([`crate::plan::area::area_lights`]), and the camera sees it glow.
        emission: Vec3,
    },
    /// A dielectric with a dispersion model, clear or coloured, smooth or
    /// rough (frosted: its facets' normals spread by GGX, Walter et al. 2007).
    Dielectric {
        /// n(λ).
        dispersion: Dispersion,
        /// n(λ) of the medium the object sits in (`Constant(1.0)`: air). Only
        /// the ratio of the two indices matters at an interface, so glass in
        /// water is glass with the relative index n_glass/n_water.
        outside: Dispersion,
        /// Beer–Lambert absorption inside (`None`: clear glass).
        attenuation: Option<Attenuation>,
        /// A sheet of no thickness (glTF's thin-walled transmission, for
        /// glass without `KHR_materials_volume` or an open mesh): it
        /// reflects both faces' share ([`crate::optics::fresnel::sheet_reflectance`])
        /// and passes the rest straight on, so it may be any shape and
        /// spreads no colours apart. Its `attenuation` tints what crosses
        /// it: a crossing keeps `color` (glTF's base colour of thin-walled
        /// glass; `distance` is not used).
        thin: bool,
        /// A thin film on its surface (glTF's `KHR_materials_iridescence`,
        /// a coated lens, a soap film): its reflectance is the film's Airy
        /// sum at each path's wavelength instead of the bare Fresnel
        /// ([`crate::optics::thin_film`]), so even glass of one index
        /// reflects and passes light in colours. `None`: bare glass.
        film: Option<ThinFilm>,
        /// glTF's perceptual roughness in [0, 1]: the surface's microfacet
        /// normals spread by a GGX distribution of width roughness², and
        /// each path reflects or refracts at its own wavelength off one
        /// facet ([`crate::optics::scatter::scatter_rough_dielectric`]).
        /// 0 is polished glass.
        roughness: f32,
    },
    /// Perfect mirror.
    Mirror,
    /// A metal (a conductor, glTF's metallic material): its microfacets
    /// reflect with Schlick's Fresnel from the reflectance at normal
    /// incidence of an RGB `color` (glTF's base colour of a metal), each
    /// wavelength by that colour's reflectance spectrum, or a measured
    /// metal's exact Fresnel at each wavelength, and their normals spread
    /// by a GGX distribution of width roughness² ([`crate::optics::metal`]).
    /// Roughness 0 is a polished metal: a coloured mirror. Light goes on
    /// from a whole metal as from a mirror; no photon is stored on it. A
    /// metalness below 1 blends it with a diffuse surface of its colour
    /// at every hit (glTF's metallic-roughness model, less the specular
    /// layer of its non-metal base): photons are stored on it and go on
    /// from it as the metal with that probability, and the camera sees
    /// both parts ([`crate::optics::metal`]).
    Metal {
        /// Its colour: RGB reflectance at normal incidence, or a measured metal.
        color: MetalColor,
        /// glTF's perceptual roughness, in [0, 1].
        roughness: f32,
        /// An image multiplying an RGB colour texel by texel (glTF's
        /// `baseColorTexture` of a metal, sRGB-encoded): the reflectance at
        /// normal incidence where a ray meets it
        /// ([`crate::plan::prepared::PreparedScene::metal_at`]). A measured
        /// metal's colour is its optical constants and takes none.
        texture: Option<Texture>,
        /// A film on its surface (glTF's `KHR_materials_iridescence` on a
        /// metal: an oxide, a heat tint), its index an absolute one; its
        /// reflections interfere with the metal's at each wavelength
        /// ([`ThinFilm::reflectance_on`]).
        film: Option<ThinFilm>,
        /// How much of it is metal ([`Metalness::WHOLE`]: all of it).
        metalness: Metalness,
    },
}

impl MaterialKind {
    /// The radiance its surface emits (zero but for an emissive diffuse material).
    pub fn emission(&self) -> Vec3 {
        match self {
            MaterialKind::Diffuse { emission, .. } => *emission,
            MaterialKind::Dielectric { .. } | MaterialKind::Mirror | MaterialKind::Metal { .. } => Vec3::ZERO,
        }
    }
}

/// A non-absorbing film on a dielectric's or metal's surface, thinner than the
/// coherence length of light, so its reflections interfere: its index (an
/// absolute one, as the scene's indices are), its thickness, and how much
/// of the surface's reflection is the film's.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ThinFilm {
    /// The film's index of refraction.
    pub ior: f32,
    /// Its thickness in nanometres (0: no film).
    pub thickness_nm: f32,
    /// glTF's `iridescenceFactor`, in [0, 1]: each interface reflects this
    /// share of the film's Airy sum and the rest of its bare Fresnel, as an
    /// interface patched with film over this share of its area would
    /// ([`ThinFilm::reflectance_on`]; a thin sheet takes the mix at each
    /// of its two faces). 1: a whole film; 0: no film.
    pub factor: f32,
}

/// Beer–Lambert absorption inside a dielectric, stated as glTF's
/// `KHR_materials_volume` states it: white light that travels `distance`
/// inside keeps the fraction `color` of each linear RGB channel, so the
/// absorption coefficient of channel c is −ln(color_c)/distance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Attenuation {
    /// Fraction of each channel left after `distance`, each in (0, 1].
    pub color: Vec3,
    /// The distance at which `color` is reached (world units, > 0).
    pub distance: f32,
}

/// A named material (`[material.NAME]`).
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// The name objects refer to.
    pub name: String,
    /// The scattering model.
    pub kind: MaterialKind,
    /// Tilts its normals by texel (a mesh's with texture coordinates); `None`: none.
    pub normal_map: Option<NormalMap>,
    /// Scales its roughness by texel (a mesh's with texture coordinates):
    /// a metal's or rough glass's roughness times the image's green
    /// channel, read as linear values (glTF's `metallicRoughnessTexture`;
    /// its blue channel scales a metal's metalness where
    /// [`Metalness::mapped`]); `None`: its roughness everywhere.
    pub roughness_map: Option<Texture>,
    /// Varies its film's thickness and factor by texel (a mesh's with
    /// texture coordinates; glTF's iridescence textures); `None`: the
    /// film is the same everywhere.
    pub film_map: Option<FilmMap>,
    /// Varies the specular layer of its diffuse base by texel (a mesh's
    /// with texture coordinates; glTF's `specularTexture` and
    /// `specularColorTexture`); `None`: the layer is the same everywhere.
    pub specular_map: Option<SpecularMap>,
}

impl Material {
    /// A material of `kind` named `name`, without a normal, roughness, film or specular map.
    pub fn new(name: impl Into<String>, kind: MaterialKind) -> Self {
        Material { name: name.into(), kind, normal_map: None, roughness_map: None, film_map: None, specular_map: None }
    }
}

/// Where a glass's or metal's film varies over a mesh (glTF's
/// `iridescenceThicknessTexture` and `iridescenceTexture`), read as linear
/// values at the mesh's texture coordinates
/// ([`crate::plan::prepared::PreparedScene::film_at`]).
#[derive(Clone, Debug, PartialEq)]
pub struct FilmMap {
    /// Its green channel g makes the film `min_nm` + g (`thickness_nm` −
    /// `min_nm`) thick, `thickness_nm` the film's own (glTF's
    /// `iridescenceThicknessMaximum`); `None`: the film's thickness everywhere.
    pub thickness: Option<Texture>,
    /// The film's thickness where the thickness map's green channel is 0
    /// (glTF's `iridescenceThicknessMinimum`, in nanometres).
    pub min_nm: f32,
    /// Its red channel scales the film's factor; `None`: the factor everywhere.
    pub factor: Option<Texture>,
}

/// Where the specular layer of a metal's or diffuse surface's base
/// ([`crate::model::metalness::SpecularLayer`]) varies over a mesh, as
/// glTF's `KHR_materials_specular` textures vary it, read at the mesh's
/// texture coordinates ([`crate::plan::prepared::PreparedScene::layer_at`]):
/// the layer's weight w (F90) and colour c there make F0 = min(`color_f0`
/// · c, 1) · w and F90 = w.
#[derive(Clone, Debug, PartialEq)]
pub struct SpecularMap {
    /// Its red channel, read as a linear value, scales the layer's weight
    /// (glTF's `specularTexture`, whose alpha channel the loader puts in
    /// every channel); `None`: the layer's weight everywhere.
    pub weight: Option<Texture>,
    /// Its colour (sRGB decoded) scales the layer's colour (glTF's
    /// `specularColorTexture`); `None`: the layer's F0 everywhere.
    pub color: Option<Texture>,
    /// The layer's reflectance head on at weight 1 before the colour map
    /// scales it and it is clipped to 1: glTF's `specularColorFactor` ·
    /// ((n − 1)/(n + 1))² (read with a colour map only).
    pub color_f0: Vec3,
}

/// The geometry of an object.
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    /// A sphere.
    Sphere {
        /// Centre.
        center: Vec3,
        /// Radius.
        radius: f32,
    },
    /// An infinite plane (two-sided).
    Plane {
        /// A point on the plane.
        point: Vec3,
        /// Its normal.
        normal: Vec3,
    },
    /// A disc, optionally with a concentric hole (a screen with a hole).
    Disk {
        /// Centre.
        center: Vec3,
        /// Normal.
        normal: Vec3,
        /// Outer radius.
        radius: f32,
        /// Radius of the hole (0 for none).
        inner_radius: f32,
    },
    /// A triangular prism: one end's triangle extruded along a vector.
    Prism {
        /// The three corners of one end.
        vertices: [Vec3; 3],
        /// The vector from that end to the other.
        extrude: Vec3,
    },
    /// A triangle mesh; closed meshes used as dielectrics must wind
    /// counter-clockwise seen from outside.
    Mesh {
        /// Vertex positions.
        positions: Vec<Vec3>,
        /// Triangles as indices into `positions`.
        triangles: Vec<[u32; 3]>,
        /// Texture coordinates per vertex (glTF's `TEXCOORD_0`: v down the
        /// image), or empty when the mesh has none.
        uvs: Vec<Vec2>,
        /// Normals per vertex (glTF's `NORMAL`), which mirrors, metals and
        /// glass scatter about smoothly across each triangle
        /// ([`crate::geometry::shading`]), or empty: flat triangles.
        normals: Vec<Vec3>,
        /// Tangents per vertex (glTF's `TANGENT`): the direction of growing
        /// u in `xyz`, and in `w` (±1) which way the bitangent
        /// `cross(normal, tangent) · w` points. A normal map's tangent frame;
        /// empty: derived from each triangle's texture coordinates
        /// ([`crate::geometry::normal_map::TriangleTangents::from_uvs`]).
        tangents: Vec<Vec4>,
    },
}

impl Scene {
    /// Does `object` emit light (an emissive material on a mesh, the only
    /// shape that may have one)?
    pub fn emits(&self, object: &Object) -> bool {
        self.materials.get(object.material).is_some_and(|m| m.kind.emission() != Vec3::ZERO)
    }
}

impl Shape {
    /// The scene-file name of the shape.
    pub fn name(&self) -> &'static str {
        match self {
            Shape::Sphere { .. } => "sphere",
            Shape::Plane { .. } => "plane",
            Shape::Disk { .. } => "disk",
            Shape::Prism { .. } => "prism",
            Shape::Mesh { .. } => "mesh",
        }
    }

    /// True for shapes that enclose a volume (may be dielectrics).
    pub fn is_closed(&self) -> bool {
        matches!(self, Shape::Sphere { .. } | Shape::Prism { .. } | Shape::Mesh { .. })
    }
}

/// An object: a shape made of a material (`[[object]]`).
#[derive(Clone, Debug, PartialEq)]
pub struct Object {
    /// Geometry.
    pub shape: Shape,
    /// Index into [`Scene::materials`].
    pub material: usize,
}

/// A whole scene.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// `[render]`.
    pub render: RenderSettings,
    /// `[camera]`.
    pub camera: Camera,
    /// `[[light]]`.
    pub lights: Vec<Light>,
    /// `[material.NAME]`.
    pub materials: Vec<Material>,
    /// `[[object]]`.
    pub objects: Vec<Object>,
}

impl fmt::Display for Estimator {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}
