//! The render protocol, one for every backend and every caller: prepare
//! once, run passes, read out.
//!
//! ```text
//! backend.prepare(scene) ─► a live Render (host buffers, or device buffers)
//!     ├─ view pass, once per camera and scene state: direct light, visible points
//!     ├─ pilot pass (progressive radii): each visible point's first radius
//!     ├─ run_pass(k), any k, any order: photons seeded by k, gathered at the points
//!     ├─ update(scene): redo only what the change invalidates (see [`Change`])
//!     ├─ set_layer(frame): draw the caustic into an engine's frame instead
//!     │  (no view rays: photons splatted where its depth buffer sees them)
//!     └─ read out: exact sums (partials, merge), the image, a pass's photon map,
//!        statistics and stage times
//! ```
//!
//! A backend author implements [`Backend`] (which makes renders) and
//! [`Render`] (the live render), and runs the conformance suite
//! (`prismatic-conformance`) against them. Host backends need not write the
//! driver: [`crate::render::host::HostRender`] runs the protocol over three kernels
//! (view rays, photon trace, gather at the visible points).

use crate::model::image::Image;
use crate::model::photon::{PhotonMap, TraceStats};
use crate::model::scene::{RenderSettings, Scene};
use crate::plan::prepared::PreparedScene;
use crate::render::accumulation::Accumulation;
use crate::render::layer::LayerFrame;
use crate::util::progress::{Progress, StageTimes};
use alloc::boxed::Box;
use alloc::string::String;

/// Why a backend could not do its work.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum BackendError {
    /// No device could be found.
    #[error("no {what} found: {detail}")]
    NoDevice {
        /// What kind of device.
        what: &'static str,
        /// Details and advice.
        detail: String,
    },
    /// The device failed while working.
    #[error("device error: {0}")]
    Device(String),
    /// The work does not fit in memory.
    #[error("out of memory: {0}")]
    OutOfMemory(String),
    /// A pass was asked for twice: each pass is summed once.
    #[error("pass {0} is already in the image")]
    PassRepeated(u32),
    /// A caustic layer's frame does not fit the scene's image.
    #[error("the layer's frame is {frame} pixels, the scene's image {image}")]
    FrameSize {
        /// The frame's size and buffers.
        frame: String,
        /// The scene's image size.
        image: String,
    },
}

impl BackendError {
    /// A layer's `frame` that does not fit `scene`'s image ([`LayerFrame::fits`]).
    pub fn frame_size(frame: &LayerFrame, scene: &PreparedScene) -> Self {
        let r = &scene.scene.render;
        BackendError::FrameSize {
            frame: alloc::format!(
                "{}x{} ({} depths, {} normals)",
                frame.width,
                frame.height,
                frame.depth.len(),
                frame.normal.len()
            ),
            image: alloc::format!("{}x{}", r.width, r.height),
        }
    }
}

/// How a backend's floating-point operations round, which decides how
/// closely its paths can follow the reference's ([`Backend::arithmetic`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Arithmetic {
    /// Each operation rounded as the reference rounds it, or within an ulp
    /// or two: the reference, the CPU's packets, lavapipe (LLVM on the CPU).
    /// Paths agree to a few ulps a segment.
    Strict,
    /// A GPU's shader compiler: it fuses multiply-adds (WGSL allows it) and
    /// divides, takes square roots and transcendentals to Vulkan's precision
    /// (2.5 ulp for a division) rather than correctly rounded. Most paths
    /// still agree to 1e-6; an ill-conditioned one (a grazing hit, a ray
    /// through a caustic's focus, a wavelength one ulp apart through a
    /// dispersive prism) goes on from its own few-ulp difference.
    Relaxed,
}

/// Makes live renders: the scalar reference, the CPU's packets, the GPU.
pub trait Backend: Send {
    /// Short name (`reference`, `cpu`, `gpu`); partial renders carry it.
    fn name(&self) -> &'static str;

    /// How this backend's arithmetic rounds (the parity tests choose their
    /// tolerances by it).
    fn arithmetic(&self) -> Arithmetic {
        Arithmetic::Strict
    }

    /// A live render of `scene`: its buffers allocated, nothing traced yet
    /// (the first pass or read-out traces the view rays and the pilot).
    fn prepare(&mut self, scene: &PreparedScene) -> Result<Box<dyn Render>, BackendError>;
}

/// A scene being rendered: passes run, the scene changes, results are read.
///
/// The result of pass `k` is a pure function of the scene (its seed) and
/// `k`: a render of passes `0..4` and one of `4..8` sum to the bits of one
/// render of `0..8` on the same backend ([`Accumulation::merge`]). Backends
/// agree with each other within the parity tests' tolerances.
pub trait Render: Send {
    /// The backend's name.
    fn backend(&self) -> &'static str;

    /// The scene being rendered.
    fn scene(&self) -> &PreparedScene;

    /// Makes `scene` the render's scene and returns what the change
    /// invalidates; the next pass or read-out redoes it (a change of the
    /// photons or more empties the sums).
    fn update(&mut self, scene: &PreparedScene) -> Result<Change, BackendError>;

    /// From now on, draws the caustic as a layer in an engine's `frame`
    /// (its depth and normals seen by the scene's camera; see
    /// [`crate::render::layer`]): each pass's photons add their irradiance
    /// where the frame sees the surface they landed on; no view rays, a
    /// black base, and the image is the mean caustic irradiance (exposure
    /// applied) for the engine to light its own surfaces with. `None` draws
    /// prismatic's image again. Either starts the passes again (as
    /// [`Change::View`]); an error when the frame does not fit the scene's
    /// image (an update that resizes the image leaves the layer).
    fn set_layer(&mut self, frame: Option<&LayerFrame>) -> Result<(), BackendError>;

    /// Traces now what the next pass needs and an update invalidated: the
    /// view rays and the pilot pass (passes and read-outs do it themselves;
    /// callers that time the passes apart from it call this first).
    fn ready(&mut self, progress: &mut dyn Progress) -> Result<(), BackendError>;

    /// Runs photon pass `pass` and adds it to the sums. An error when the
    /// pass is summed already ([`BackendError::PassRepeated`]).
    fn run_pass(&mut self, pass: u32, progress: &mut dyn Progress) -> Result<(), BackendError>;

    /// The passes summed, as sorted, disjoint half-open ranges (known on the
    /// host: no read-out).
    fn passes(&self) -> &[(u32, u32)];

    /// Runs the lowest pass not summed yet (an engine's next frame).
    fn next_pass(&mut self, progress: &mut dyn Progress) -> Result<u32, BackendError> {
        let next = match self.passes() {
            [(0, end), ..] => *end,
            _ => 0,
        };
        self.run_pass(next, progress)?;
        Ok(next)
    }

    /// The part of the image every pass shares: direct light, ambient and
    /// background, exposure applied (read back from a device). With
    /// sampled view paths every pass traces its own view, which its sums
    /// hold, so the base is black.
    fn base(&mut self) -> Result<Image, BackendError>;

    /// The exact sums of the passes so far (read back from a device): what
    /// a partial render stores and [`Accumulation::merge`] adds.
    fn sums(&mut self) -> Result<Accumulation, BackendError>;

    /// The image of the passes so far: the base plus the mean caustic,
    /// computed from the sums on the host, so that a render and the merge
    /// of its partials give the same bits.
    fn image(&mut self) -> Result<Image, BackendError> {
        let base = self.base()?;
        Ok(self.sums()?.image(&base))
    }

    /// The caustic photon map of pass `pass` in canonical order, with what
    /// its trace did (the parity tests and `prismatic photons` read it).
    /// Traces the pass's photons again; the sums do not change.
    fn photon_map(&mut self, pass: u32, progress: &mut dyn Progress) -> Result<PhotonMap, BackendError>;

    /// What the render has done so far (read back from a device).
    fn stats(&mut self) -> Result<RenderStats, BackendError>;

    /// Time per stage of a recent pass, where the backend measures it (a
    /// GPU's timestamps come back a pass or two late); `None` before then
    /// or when it does not.
    fn stage_times(&self) -> Option<StageTimes> {
        None
    }
}

/// What a render has done: passes, photons, visible points and their
/// first radii, and for a device the bytes that crossed to and from it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RenderStats {
    /// Passes summed.
    pub passes: u32,
    /// The summed passes' photon traces (the pilot's not included).
    pub trace: TraceStats,
    /// Visible points (diffuse hits that gather caustics) of the last view
    /// traced: the render's, or with sampled view paths the last pass's.
    pub visible_points: u64,
    /// The smallest and largest first radius; `None` without visible points.
    pub first_radii: Option<(f32, f32)>,
    /// Pixels of the last view traced whose view paths the device stopped
    /// short of their end: a software device (lavapipe) stops an
    /// invocation's loops after 65,535 iterations in all, and a pixel whose
    /// paths split at glass and shade every diffuse hit with many lights
    /// goes past it; their light and visible points are missing. 0 on the
    /// host and on a GPU.
    pub view_paths_cut: u64,
    /// Bytes written to a device since the render was prepared (0 on the host).
    pub uploaded: u64,
    /// Bytes read back from a device since the render was prepared (0 on the host).
    pub read_back: u64,
}

/// What a scene update invalidates, from least to most; each level redoes
/// what the levels below it redo.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord)]
pub enum Change {
    /// Nothing the image depends on (tone mapping, the pass count of an
    /// offline render).
    #[default]
    None,
    /// The photons alone: photon count, seed, photon sequence, radius,
    /// radius mode, estimator, α, neighbours, projection maps. The passes start again (a
    /// new pilot pass, sums emptied); the view rays' image and visible
    /// points stay.
    Photons,
    /// What the view rays see: camera, objects, materials, lights (their
    /// direct light and shadows are the view pass's), bands, depth, light
    /// tracing (which diffuse hits gather), wavelength sampling, view paths
    /// (and the seed, which sampled view paths take their numbers from),
    /// exposure, ambient, background. The view rays are traced again, then
    /// as [`Change::Photons`].
    View,
    /// The image size: pixel and visible-point buffers are allocated
    /// again, then as [`Change::View`].
    Size,
}

impl Change {
    /// What going from scene `old` to scene `new` invalidates.
    ///
    /// Both scenes are destructured field by field, so a field added to
    /// [`Scene`] or [`RenderSettings`] does not compile here until it is
    /// classified.
    pub fn between(old: &Scene, new: &Scene) -> Change {
        let Scene { render: a, camera, lights, materials, objects } = old;
        let RenderSettings {
            width,
            height,
            photons,
            indirect_photons,
            radius,
            radius_mode,
            bands,
            estimator,
            light_tracing,
            wavelengths,
            photon_sequence,
            view_paths,
            seed,
            max_depth,
            ambient,
            exposure,
            white_point,
            background,
            // Applied when the image is read out: no pass redoes anything.
            tone_map: _,
            auto_exposure: _,
            projection_maps,
            // How many passes an offline render runs, not what one computes.
            passes: _,
            alpha,
            neighbours,
            environment_lights,
            area_lights,
        } = a;
        let b = &new.render;
        if (*width, *height) != (b.width, b.height) {
            Change::Size
        } else if *camera != new.camera
            || *objects != new.objects
            || *materials != new.materials
            || *lights != new.lights
            || *environment_lights != b.environment_lights
            || *area_lights != b.area_lights
            || *bands != b.bands
            || *max_depth != b.max_depth
            // Indirect light on or off: where view paths gather, the plan's depth.
            || (*indirect_photons == 0) != (b.indirect_photons == 0)
            || *light_tracing != b.light_tracing
            || *wavelengths != b.wavelengths
            || *view_paths != b.view_paths
            || (*seed != b.seed && b.view_paths.per_pass())
            || *exposure != b.exposure
            || *white_point != b.white_point
            || *ambient != b.ambient
            || *background != b.background
        {
            Change::View
        } else if *photons != b.photons
            || *indirect_photons != b.indirect_photons
            || *seed != b.seed
            || *photon_sequence != b.photon_sequence
            || *radius != b.radius
            || *radius_mode != b.radius_mode
            || *estimator != b.estimator
            || *alpha != b.alpha
            || *neighbours != b.neighbours
            || *projection_maps != b.projection_maps
        {
            Change::Photons
        } else {
            Change::None
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::color::ToneMap;
    use crate::model::scene::{Camera, Light, PhotonSequence, RadiusMode};
    use crate::{BandSpec, Vec3};
    use alloc::vec;

    #[test]
    fn changes_are_classified_by_what_they_invalidate() {
        let scene = Scene {
            render: crate::RenderSettings::default(),
            camera: Camera { position: Vec3::new(0.0, 1.0, 5.0), look_at: Vec3::ZERO, up: Vec3::Y, fov_deg: 40.0 },
            lights: vec![Light::Point {
                position: Vec3::new(0.0, 4.0, 0.0),
                power: 10.0,
                spectrum: Default::default(),
                range: None,
            }],
            materials: vec![],
            objects: vec![],
        };
        let edited = |edit: &dyn Fn(&mut Scene)| {
            let mut s = scene.clone();
            edit(&mut s);
            Change::between(&scene, &s)
        };
        assert_eq!(edited(&|_| {}), Change::None);
        assert_eq!(edited(&|s| s.render.tone_map = ToneMap::Reinhard), Change::None);
        assert_eq!(edited(&|s| s.render.auto_exposure = true), Change::None);
        assert_eq!(edited(&|s| s.render.passes = 3), Change::None);
        assert_eq!(edited(&|s| s.render.photons += 1), Change::Photons);
        assert_eq!(edited(&|s| s.render.seed += 1), Change::View, "the default hero view paths take the seed");
        assert_eq!(edited(&|s| s.render.photon_sequence = PhotonSequence::Random), Change::Photons);
        assert_eq!(edited(&|s| s.render.alpha = 0.5), Change::Photons);
        assert_eq!(edited(&|s| s.render.radius_mode = RadiusMode::Fixed), Change::Photons);
        assert_eq!(
            edited(&|s| s.lights[0] =
                Light::Point { position: Vec3::ONE, power: 10.0, spectrum: Default::default(), range: None }),
            Change::View
        );
        assert_eq!(edited(&|s| s.camera.position.x += 0.1), Change::View);
        assert_eq!(edited(&|s| s.render.bands = BandSpec::Paper3), Change::View);
        assert_eq!(edited(&|s| s.render.light_tracing = !s.render.light_tracing), Change::View);
        assert_eq!(edited(&|s| s.render.view_paths = crate::ViewPaths::Sampled), Change::View);
        for (view_paths, change) in
            [(crate::ViewPaths::Centre, Change::Photons), (crate::ViewPaths::Sampled, Change::View)]
        {
            let mut before = scene.clone();
            before.render.view_paths = view_paths;
            let mut after = before.clone();
            after.render.seed += 1;
            assert_eq!(Change::between(&before, &after), change, "a new seed with {view_paths:?} view paths");
        }
        assert_eq!(edited(&|s| s.render.width += 1), Change::Size);
        assert!(Change::None < Change::Photons && Change::Photons < Change::View && Change::View < Change::Size);
    }
}
