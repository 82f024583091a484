//! The GPU's live render: [`GpuSession`] keeps one scene's buffers, its
//! photon pass, grids, visible points and exact sums on the device from
//! pass to pass and implements the render protocol ([`Render`]) there:
//! the view rays and the pilot pass run on the device, each pass uploads
//! a few uniforms and reads nothing back (no wait on a hardware GPU), and
//! the image, the sums and the statistics are read back only when asked.
//! An engine runs one on its own device and copies the image into its
//! texture on the device ([`GpuSession::copy_to_texture`]).
//!
//! The module's files split the work: `points` (the visible points' device
//! buffers, in chunks of pixels), `view` (the view pass), `layer` (an
//! engine's frame in place of the view: the caustic layer), `history` (a
//! layer's temporal accumulation), `passes` (the
//! pilot, the photon passes and their gathers), `pass_lights` (the lights
//! that change each pass: drawn suns, area lights' aims), `readout` (what is read back).

mod history;
mod layer;
mod pass_lights;
mod passes;
mod points;
mod readout;
mod view;

pub use layer::{DepthEncoding, FrameTextures, NormalEncoding};

use crate::GpuOptions;
use crate::context::GpuContext;
use crate::layout::{RunStats, SessionParams};
use crate::levels::GridLevels;
use crate::photons::window_for;
use crate::pipelines::Pipelines;
use crate::pixels::{self, pixel_buffer};
use crate::readback::PendingRead;
use crate::scene::{EncodedScene, SceneBuffers};
use crate::timing::StageTimer;
use crate::trace::{PhotonPass, map_bound};
use points::PointChunks;
use prismatic_core::plan::schedule::pass_scene;
use prismatic_core::render::accumulation::{contains_pass, insert_passes};
use prismatic_core::{
    Accumulation, BackendError, Change, Image, LayerFrame, PhotonMap, PreparedScene, Progress, Render, RenderStats,
    StageTimes,
};
use std::collections::VecDeque;
use std::sync::Arc;

/// Passes a session lets the device fall behind the host by: the next pass
/// waits for the one this many before it (a hardware GPU behind an engine
/// that presents frames never gets there; a loop of passes is held to the
/// device's pace, so its wall time is the device's).
pub const PASSES_IN_FLIGHT: usize = 2;

/// A scene rendered on the device, pass by pass.
pub struct GpuSession {
    ctx: GpuContext,
    pipelines: Arc<Pipelines>,
    options: GpuOptions,
    /// Photons per bucket one gather dispatch reads (`u32::MAX` on hardware).
    span: u32,
    scene: PreparedScene,
    encoded: EncodedScene,
    buffers: SceneBuffers,
    /// The pass whose lights the buffers hold (0 after an upload).
    lights_pass: u32,
    photons: PhotonPass,
    levels: GridLevels,
    /// The image: row-major `vec4<f32>`, linear RGB, exposure applied.
    pixels: wgpu::Buffer,
    points: PointChunks,
    session_params: wgpu::Buffer,
    /// The render's statistics ([`RunStats`]) and the binding that adds a
    /// pass's tallies to them.
    run_stats: wgpu::Buffer,
    fold_group: wgpu::BindGroup,
    /// The passes summed (known on the host).
    passes: Vec<(u32, u32)>,
    /// What the next pass or read-out must redo.
    stale: Change,
    /// Whether a view pass has told how many visible points the chunks need.
    room_learnt: bool,
    /// The last view pass's point counts on their way back.
    pending_totals: Option<PendingRead>,
    /// GPU stage times, where asked for and the device has timestamps.
    timer: Option<StageTimer>,
    /// The last submission of each pass the device may still be running.
    in_flight: VecDeque<wgpu::SubmissionIndex>,
    /// The engine's frame the caustic is drawn into as a layer (layer.wgsl's
    /// `frame`), if any.
    layer: Option<wgpu::Buffer>,
    /// A layer's temporal accumulation ([`GpuSession::layer_frame`]), once used.
    history: Option<history::LayerHistory>,
}

impl GpuSession {
    /// A session on `ctx` (an engine's device, or one of the backend's) for
    /// `scene`: compiles the pipelines and allocates every buffer. Nothing
    /// is traced yet; the first pass traces the visible points and waits
    /// for the device once, to learn how many points a pixel needs.
    pub fn new(ctx: GpuContext, scene: &PreparedScene, options: GpuOptions) -> Result<Self, BackendError> {
        let pipelines = Arc::new(Pipelines::new(&ctx.device));
        Self::with_pipelines(ctx, pipelines, scene, options)
    }

    /// [`GpuSession::new`] with pipelines compiled before (a backend's, for its renders).
    pub fn with_pipelines(
        ctx: GpuContext,
        pipelines: Arc<Pipelines>,
        scene: &PreparedScene,
        options: GpuOptions,
    ) -> Result<Self, BackendError> {
        let ctx = ctx.counting_apart();
        let software = ctx.device.adapter_info().device_type == wgpu::DeviceType::Cpu;
        let span = options.gather_span.unwrap_or(if software { pixels::SOFTWARE_GATHER_SPAN } else { u32::MAX });
        let encoded = EncodedScene::new(scene);
        encoded.fits(&ctx.device)?;
        let buffers =
            ctx.checked("uploading the scene", || SceneBuffers::upload(&ctx, &pipelines.scene_layout, &encoded))?;
        let photons = photon_pass(&ctx, &pipelines, scene, &buffers, window(&ctx, options))?;
        let levels = GridLevels::new(&ctx, &pipelines, &buffers, &photons)?;
        let (session_params, run_stats) = ctx.checked("allocating the session", || {
            let buffer = |label: &str, size: usize, usage: wgpu::BufferUsages| {
                ctx.device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some(label),
                    size: size as u64,
                    usage: usage | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                })
            };
            (
                buffer("prismatic session params", size_of::<SessionParams>(), wgpu::BufferUsages::UNIFORM),
                buffer(
                    "prismatic run statistics",
                    size_of::<RunStats>(),
                    wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                ),
            )
        })?;
        let fold_group = fold_group(&ctx, &pipelines, &photons, &run_stats)?;
        let pixels = pixel_buffer(&ctx, scene.scene.render.width, scene.scene.render.height)?;
        let timer = if options.stage_times { StageTimer::new(&ctx)? } else { None };
        Ok(GpuSession {
            points: PointChunks::new(&ctx)?,
            ctx,
            pipelines,
            options,
            span,
            scene: scene.clone(),
            encoded,
            buffers,
            lights_pass: 0,
            photons,
            levels,
            pixels,
            session_params,
            run_stats,
            fold_group,
            passes: Vec::new(),
            stale: Change::Size,
            room_learnt: false,
            pending_totals: None,
            timer,
            in_flight: VecDeque::new(),
            layer: None,
            history: None,
        })
    }

    /// The device and queue.
    pub fn context(&self) -> &GpuContext {
        &self.ctx
    }

    /// Runs `work` on the session with its submissions recorded instead
    /// ([`GpuContext::record`]): the command buffers come back for an
    /// engine to submit among its own, e.g. a caustic layer's frame and
    /// pass after the engine's depth prepass and before its main pass, in
    /// one frame. A recorded pass neither waits for earlier ones nor writes
    /// stage times.
    pub fn record<T>(&mut self, work: impl FnOnce(&mut Self) -> T) -> (T, Vec<wgpu::CommandBuffer>) {
        let ctx = self.ctx.clone();
        ctx.record(|| work(self))
    }

    /// The image's pixels as the device shows it: width × height row-major
    /// `vec4<f32>` (linear RGB, exposure applied, alpha 1), the base plus
    /// the mean caustic of the passes so far.
    pub fn pixels(&self) -> &wgpu::Buffer {
        &self.pixels
    }

    /// Copies the device's image into `texture` (its size; `Rgba32Float`,
    /// `Rgba16Float` or `Rgba8Unorm`; `STORAGE_BINDING` usage) on the
    /// device; submitted, not waited for.
    pub fn copy_to_texture(&mut self, texture: &wgpu::Texture) -> Result<(), BackendError> {
        pixels::copy_to_texture(&self.ctx, &self.pipelines, &mut self.buffers, &self.pixels, texture)
    }

    /// Room for visible points now (grows to what the scene's view passes
    /// found, with an eighth to spare).
    pub fn point_capacity(&self) -> u64 {
        self.points.capacity()
    }

    /// The grid levels built now: bit l for level l (cells of the pass
    /// radius / 4^l); level 0 always, finer ones once the first radii ask.
    pub fn grid_levels(&self) -> u32 {
        self.levels.built()
    }

    /// Redoes what the last update (or a shortage of room for visible
    /// points) invalidated: buffers, view rays, the pilot pass.
    fn bring_up_to_date(&mut self) -> Result<(), BackendError> {
        self.check_reads()?;
        let redone = std::mem::take(&mut self.stale);
        if redone != Change::None {
            // Pass 0's view and the pilot are lit by pass 0's lights.
            self.use_lights_of(0)?;
        }
        if redone >= Change::Size {
            self.allocate_points()?;
        }
        // Per-pass view paths leave the last pass's points: the pilot's are pass 0's.
        if self.layer.is_some() && redone >= Change::View {
            self.clear_view()?;
        } else if redone >= Change::View || (self.sampled() && redone >= Change::Photons) {
            self.trace_view(0)?;
            self.stamp(prismatic_core::Stage::View)?;
        }
        if redone >= Change::Photons {
            self.empty_sums()?;
            self.pilot()?;
        }
        Ok(())
    }

    /// Whether each pass traces its own view paths (a layer traces none).
    pub(super) fn sampled(&self) -> bool {
        self.layer.is_none() && self.scene.scene.render.view_paths.per_pass()
    }

    /// Waits until fewer than [`PASSES_IN_FLIGHT`] passes are on the device.
    fn throttle(&mut self) -> Result<(), BackendError> {
        while self.in_flight.len() >= PASSES_IN_FLIGHT {
            let oldest = self.in_flight.pop_front().expect("not empty");
            self.ctx
                .device
                .poll(wgpu::PollType::Wait { submission_index: Some(oldest), timeout: None })
                .map_err(|e| BackendError::Device(format!("waiting for the GPU: {e}")))?;
        }
        Ok(())
    }

    /// Stamps the end of `stage` when timing.
    fn stamp(&mut self, stage: prismatic_core::Stage) -> Result<(), BackendError> {
        match &mut self.timer {
            Some(timer) => timer.end(&self.ctx, stage),
            None => Ok(()),
        }
    }
}

impl Render for GpuSession {
    fn backend(&self) -> &'static str {
        "gpu"
    }

    fn scene(&self) -> &PreparedScene {
        &self.scene
    }

    /// Uploads only the bytes of the scene's buffers that changed
    /// (reallocating a buffer only when it grows); the photon map and grids
    /// are reallocated only when the photon count, band split or photon
    /// window changes.
    fn update(&mut self, scene: &PreparedScene) -> Result<Change, BackendError> {
        let change = Change::between(&self.scene.scene, &scene.scene);
        if change == Change::None {
            self.scene = scene.clone();
            return Ok(change);
        }
        let encoded = EncodedScene::new(scene);
        encoded.fits(&self.ctx.device)?;
        let regrouped = self.ctx.checked("updating the scene", || {
            self.buffers.update(&self.ctx, &self.pipelines.scene_layout, &self.encoded, &encoded)
        })?;
        self.encoded = encoded;
        self.lights_pass = 0;
        let window = window(&self.ctx, self.options);
        let mut rebind = regrouped;
        if !self.photons.fits(scene, window) {
            self.photons = photon_pass(&self.ctx, &self.pipelines, scene, &self.buffers, window)?;
            self.levels.reallocate(&self.ctx, &self.pipelines, &self.buffers, &self.photons)?;
            self.fold_group = fold_group(&self.ctx, &self.pipelines, &self.photons, &self.run_stats)?;
            rebind = true;
        }
        if change == Change::Size {
            let r = &scene.scene.render;
            self.pixels = pixel_buffer(&self.ctx, r.width, r.height)?;
            self.layer = None;
        } else if rebind {
            // The chunks' bind groups hold the band table, grid and photons that moved.
            self.bind_points()?;
        }
        if change >= Change::Photons {
            self.passes.clear();
        }
        self.scene = scene.clone();
        self.stale = self.stale.max(change);
        Ok(change)
    }

    /// Uploads the frame from the host (an engine with its depth and
    /// normals on the device hands them over there:
    /// [`GpuSession::set_layer_textures`]).
    fn set_layer(&mut self, frame: Option<&LayerFrame>) -> Result<(), BackendError> {
        if let Some(frame) = frame.filter(|f| !f.fits(&self.scene)) {
            return Err(BackendError::frame_size(frame, &self.scene));
        }
        let was_layer = self.layer.is_some();
        let uploaded = frame.map(|f| self.upload_frame(f)).transpose()?;
        self.adopt_frame(uploaded, true)?;
        self.passes.clear();
        // Entering or leaving a layer changes the room visible points need.
        let change = if was_layer == self.layer.is_some() { Change::View } else { Change::Size };
        self.stale = self.stale.max(change);
        Ok(())
    }

    fn ready(&mut self, _progress: &mut dyn Progress) -> Result<(), BackendError> {
        self.bring_up_to_date()
    }

    /// Submits the pass (after redoing what an update invalidated) and
    /// returns without waiting for it, unless [`PASSES_IN_FLIGHT`] passes
    /// are on the device already. On a software device the gather goes in
    /// segments whose number comes from the grid, which it reads back.
    fn run_pass(&mut self, pass: u32, progress: &mut dyn Progress) -> Result<(), BackendError> {
        // A recorded pass is the engine's to submit and pace.
        let recording = self.ctx.recording();
        if !recording {
            self.throttle()?;
        }
        // Stamps of an earlier pass that have come back free the timer for this one.
        self.check_reads()?;
        match &mut self.timer {
            Some(timer) if recording => timer.skip(),
            Some(timer) => timer.begin(&self.ctx)?,
            None => {}
        }
        self.bring_up_to_date()?;
        if contains_pass(&self.passes, pass) {
            return Err(BackendError::PassRepeated(pass));
        }
        let summed = self.passes.iter().map(|(a, b)| b - a).sum::<u32>() + 1;
        self.pass(pass, summed, progress)?;
        insert_passes(&mut self.passes, pass, pass + 1).map_err(|_| BackendError::PassRepeated(pass))?;
        if !recording {
            if let Some(timer) = &mut self.timer {
                timer.finish(&self.ctx)?;
            }
            self.in_flight.push_back(self.ctx.queue.submit([]));
        }
        Ok(())
    }

    fn passes(&self) -> &[(u32, u32)] {
        &self.passes
    }

    fn base(&mut self) -> Result<Image, BackendError> {
        self.bring_up_to_date()?;
        self.read_base()
    }

    fn sums(&mut self) -> Result<Accumulation, BackendError> {
        self.bring_up_to_date()?;
        let r = &self.scene.scene.render;
        let sums = self.read_sums()?;
        Accumulation::from_parts(r.width, r.height, &self.passes, sums)
            .map_err(|e| BackendError::Device(format!("the device's sums: {e}")))
    }

    fn photon_map(&mut self, pass: u32, progress: &mut dyn Progress) -> Result<PhotonMap, BackendError> {
        self.use_lights_of(pass)?;
        self.trace_photons(&pass_scene(&self.scene, pass), progress)?;
        self.photons.read_map(&self.ctx)
    }

    fn stats(&mut self) -> Result<RenderStats, BackendError> {
        self.bring_up_to_date()?;
        self.read_stats()
    }

    fn stage_times(&self) -> Option<StageTimes> {
        self.timer.as_ref().and_then(StageTimer::last)
    }
}

/// Photons per storage binding for `options` on `ctx`'s device.
fn window(ctx: &GpuContext, options: GpuOptions) -> u32 {
    let device = window_for(&ctx.limits());
    options.window_photons.map_or(device, |w| w.clamp(1, device))
}

/// A photon pass's buffers for `scene`; an error when its photons cannot
/// all be stored (a pass must never drop photons silently).
fn photon_pass(
    ctx: &GpuContext,
    pipelines: &Pipelines,
    scene: &PreparedScene,
    buffers: &SceneBuffers,
    window: u32,
) -> Result<PhotonPass, BackendError> {
    let pass = PhotonPass::new(ctx, pipelines, scene, buffers, window)?;
    let bound = map_bound(scene);
    if bound > u64::from(pass.capacity()) {
        return Err(BackendError::OutOfMemory(format!(
            "a pass of {} photons can store {bound} photons; this device's photon map holds {} ({} storage \
             bindings of {} photons): trace fewer (indirect) photons per pass, use --wavelengths random_band, or use \
             --backend cpu",
            pass.emissions(),
            pass.capacity(),
            crate::shaders::WINDOWS,
            pass.photons.window
        )));
    }
    Ok(pass)
}

/// The binding that adds `photons`' tallies to `run_stats`.
fn fold_group(
    ctx: &GpuContext,
    pipelines: &Pipelines,
    photons: &PhotonPass,
    run_stats: &wgpu::Buffer,
) -> Result<wgpu::BindGroup, BackendError> {
    ctx.checked("binding the statistics", || {
        ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("prismatic fold tallies"),
            layout: &pipelines.stats_layout,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: photons.tallies().as_entire_binding() },
                wgpu::BindGroupEntry { binding: 1, resource: run_stats.as_entire_binding() },
            ],
        })
    })
}
