//! The `Backend` trait every implementation provides, its error type, and
//! the scalar reference backend.

use crate::image::Image;
use crate::photon::{PhotonMap, TraceStats};
use crate::prepared::PreparedScene;
use crate::progressive::PassGather;
use crate::visible::{VisiblePoint, VisiblePoints};
use alloc::string::String;

/// Why a backend could not do its work.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum BackendError {
    /// The backend is not available in this build.
    #[error("the {backend} backend is not built yet; use {hint}")]
    NotBuilt {
        /// Its name.
        backend: &'static str,
        /// What to use instead.
        hint: &'static str,
    },
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
}

/// A stage of the pipeline, for progress reports.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// Emitting and tracing photons.
    Trace,
    /// Building the grid, ray tracing and gathering.
    Render,
}

/// Receives progress reports from long work.
pub trait Progress {
    /// `done` of `total` units of `stage` are finished.
    fn advance(&mut self, stage: Stage, done: u64, total: u64);
}

/// Progress that goes nowhere.
#[derive(Clone, Copy, Debug, Default)]
pub struct NoProgress;

impl Progress for NoProgress {
    fn advance(&mut self, _: Stage, _: u64, _: u64) {}
}

/// A photon-mapping backend: traces the caustic photon map and renders with it.
///
/// One frame: [`Backend::trace_photons`] then [`Backend::render`] (or both
/// at once, [`Backend::trace_and_render`]). A progressive render
/// ([`crate::progressive::ProgressiveRender`]) prepares once
/// ([`Backend::visible_points`]), runs passes ([`Backend::gather_pass`]) and
/// reads out the sums, which live in the core.
///
/// Implementations must give the same photon map as the reference (same
/// (emission, band) keys, positions and flux within the tolerances of the
/// parity tests) and return it in canonical order.
pub trait Backend {
    /// Short name (`reference`, `cpu`, `gpu`).
    fn name(&self) -> &'static str;

    /// Traces the scene's white photons into the dispersion caustic map.
    fn trace_photons(&mut self, scene: &PreparedScene, progress: &mut dyn Progress) -> Result<PhotonMap, BackendError>;

    /// Ray traces the image, gathering caustics from `photons`.
    fn render(
        &mut self,
        scene: &PreparedScene,
        photons: &PhotonMap,
        progress: &mut dyn Progress,
    ) -> Result<Image, BackendError>;

    /// Traces and renders in one go, for callers that need the image and
    /// not the photon map: a backend may keep the map where it traced it
    /// (the GPU backend keeps it on the device). Returns what the trace
    /// did and the image.
    fn trace_and_render(
        &mut self,
        scene: &PreparedScene,
        progress: &mut dyn Progress,
    ) -> Result<(TraceStats, Image), BackendError> {
        let map = self.trace_photons(scene, progress)?;
        let image = self.render(scene, &map, progress)?;
        Ok((map.stats, image))
    }

    /// Progressive rendering, step one (once per camera and scene): traces
    /// the view rays into the image without caustics and the visible points
    /// that need them. The default is the scalar reference's.
    fn visible_points(
        &mut self,
        scene: &PreparedScene,
        progress: &mut dyn Progress,
    ) -> Result<VisiblePoints, BackendError> {
        Ok(crate::render::visible_points_with_progress(scene, progress))
    }

    /// Progressive rendering, one pass: traces `scene`'s photons (its seed
    /// and count) and gathers them at `points`, each within its own radius
    /// (`radii`, at most the scene's radius). The default traces with
    /// [`Backend::trace_photons`] and gathers with the scalar reference.
    fn gather_pass(
        &mut self,
        scene: &PreparedScene,
        points: &[VisiblePoint],
        radii: &[f32],
    ) -> Result<PassGather, BackendError> {
        let map = self.trace_photons(scene, &mut NoProgress)?;
        Ok(crate::progressive::gather_pass(scene, &map, points, radii))
    }
}

/// The scalar reference, single-threaded: the definition of right.
#[derive(Clone, Copy, Debug, Default)]
pub struct ReferenceBackend;

impl Backend for ReferenceBackend {
    fn name(&self) -> &'static str {
        "reference"
    }

    fn trace_photons(&mut self, scene: &PreparedScene, progress: &mut dyn Progress) -> Result<PhotonMap, BackendError> {
        Ok(crate::trace::trace_photons_with_progress(scene, progress))
    }

    fn render(
        &mut self,
        scene: &PreparedScene,
        photons: &PhotonMap,
        progress: &mut dyn Progress,
    ) -> Result<Image, BackendError> {
        Ok(crate::render::render_with_progress(scene, photons, progress))
    }
}
