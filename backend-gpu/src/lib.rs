//! prismatic-gpu: the wgpu compute backend.
//!
//! Every stage runs on the device in WGSL (`src/shaders/`), each a twin of
//! the core stage of the same name: emit + trace (same counter-based RNG,
//! bit for bit), compaction into canonical (emission, band) order, hash-grid
//! build (count, prefix sum, scatter), ray tracing into visible points, and
//! the gather at them. Buffers stay on the device between stages;
//! [`GpuBackend::frame`] renders reading back only a photon count and two
//! sizes (visible points needed, widest bucket on software devices), and
//! the photon map is read back only when asked for
//! ([`Backend::trace_photons`]).
//!
//! An engine embeds a [`GpuSession`] on its own device ([`GpuContext::from_device`]):
//! it keeps the scene, photon map, grid, visible points and running sums on
//! the device and adds one progressive pass per frame without waiting for
//! it; [`GpuSession::update`] redoes only what a scene change invalidates
//! ([`Change`]). One-off frames go into a caller's buffer or storage
//! texture ([`GpuBackend::render_into_buffer`], [`GpuBackend::render_into_texture`]).

mod context;
mod grid;
pub mod layout;
mod levels;
mod photons;
mod pipelines;
mod progressive;
mod readback;
mod render;
mod scan;
mod scene;
mod session;
pub mod shaders;
mod timing;
mod trace;

pub use context::{AdapterChoice, GpuContext, STORAGE_BUFFERS_NEEDED, describe, is_hardware, required_limits};
pub use render::{PIXEL_BYTES, SOFTWARE_GATHER_SPAN};
pub use session::{Change, GpuSession, SessionFrame};
pub use timing::{StageTimes, timestamp_features};

use photons::PhotonArray;
use pipelines::Pipelines;
use prismatic_core::backend::{Backend, BackendError, Progress, Stage};
use prismatic_core::progressive::PassGather;
use prismatic_core::visible::VisiblePoint;
use prismatic_core::{Image, PhotonMap, PreparedScene, TraceStats};
use scene::{EncodedScene, SceneBuffers};

/// Options that change how the work is cut, not what it computes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct GpuOptions {
    /// Photons per storage binding; `None`: as many as the device allows.
    /// Tests set it small to run the multi-binding paths on small scenes.
    pub window_photons: Option<u32>,
    /// Photons of each grid bucket one gather pass reads; `None`: all of
    /// them in one pass on a hardware GPU, [`SOFTWARE_GATHER_SPAN`] on a
    /// software device (whose invocations may not loop long).
    pub gather_span: Option<u32>,
}

/// The wgpu backend.
pub struct GpuBackend {
    ctx: GpuContext,
    pipelines: Pipelines,
    options: GpuOptions,
    gatherer: render::Gatherer,
    /// The last frame's pixels (reused while the image size stays).
    pixels: Option<wgpu::Buffer>,
}

/// What a device-resident frame did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FrameInfo {
    /// Photons in the caustic map.
    pub stored: u32,
}

impl GpuBackend {
    /// A backend on its own device: the best adapter there is (`choice`).
    pub fn new(choice: AdapterChoice) -> Result<Self, BackendError> {
        Ok(Self::with_context(GpuContext::new(choice)?, GpuOptions::default()))
    }

    /// A backend on a caller's device and queue (a game engine's); the
    /// device needs [`required_limits`].
    pub fn from_device(device: wgpu::Device, queue: wgpu::Queue) -> Result<Self, BackendError> {
        Ok(Self::with_context(GpuContext::from_device(device, queue)?, GpuOptions::default()))
    }

    /// A backend on `ctx` with `options`.
    pub fn with_context(ctx: GpuContext, options: GpuOptions) -> Self {
        let pipelines = Pipelines::new(&ctx.device);
        let software = ctx.device.adapter_info().device_type == wgpu::DeviceType::Cpu;
        let span = options.gather_span.unwrap_or(if software { SOFTWARE_GATHER_SPAN } else { u32::MAX });
        GpuBackend { ctx, pipelines, options, gatherer: render::Gatherer::new(span), pixels: None }
    }

    /// The adapter, when the backend chose it.
    pub fn adapter(&self) -> Option<&wgpu::AdapterInfo> {
        self.ctx.adapter.as_ref()
    }

    /// Visible-point slots per pixel of the render: grows, once, to what
    /// the scenes rendered so far needed (a re-render of that frame).
    pub fn points_per_pixel(&self) -> u32 {
        self.gatherer.points_per_pixel()
    }

    /// The device and queue (to share with the caller).
    pub fn context(&self) -> &GpuContext {
        &self.ctx
    }

    fn window(&self) -> u32 {
        let device = photons::window_for(&self.ctx.limits());
        self.options.window_photons.map_or(device, |w| w.clamp(1, device))
    }

    fn upload(&self, scene: &PreparedScene) -> Result<SceneBuffers, BackendError> {
        let encoded = EncodedScene::new(scene);
        self.ctx.checked("uploading the scene", || {
            SceneBuffers::upload(&self.ctx.device, &self.pipelines.scene_layout, &encoded)
        })
    }

    fn trace_on_device(
        &mut self,
        scene: &PreparedScene,
        buffers: &mut SceneBuffers,
        progress: &mut dyn Progress,
    ) -> Result<trace::DeviceMap, BackendError> {
        let window = self.window();
        trace::trace(&self.ctx, &self.pipelines, buffers, scene, window, progress)
    }

    fn pixels_for(&mut self, scene: &PreparedScene) -> Result<wgpu::Buffer, BackendError> {
        let r = &scene.scene.render;
        let bytes = (u64::from(r.width) * u64::from(r.height) * PIXEL_BYTES).max(PIXEL_BYTES);
        match &self.pixels {
            Some(b) if b.size() == bytes => Ok(b.clone()),
            _ => {
                let b = render::pixel_buffer(&self.ctx, r.width, r.height)?;
                self.pixels = Some(b.clone());
                Ok(b)
            }
        }
    }

    /// A whole frame on the device, into `pixels`: trace, compaction, grid,
    /// render. Nothing is read back but the photon count and the render's
    /// visible-point check. Returns the scene's buffers and the photon map
    /// for passes that follow on the same frame.
    fn frame_into(
        &mut self,
        scene: &PreparedScene,
        pixels: &wgpu::Buffer,
        progress: &mut dyn Progress,
    ) -> Result<(FrameInfo, SceneBuffers, trace::DeviceMap), BackendError> {
        let mut buffers = self.upload(scene)?;
        let map = self.trace_on_device(scene, &mut buffers, progress)?;
        let grid = grid::build(&self.ctx, &self.pipelines, &mut buffers, &map)?;
        render::render(&self.ctx, &mut self.pipelines, &mut buffers, &grid, &mut self.gatherer, pixels)?;
        Ok((FrameInfo { stored: map.stored }, buffers, map))
    }

    /// Renders a frame into the backend's own pixel buffer and waits for it.
    pub fn frame(&mut self, scene: &PreparedScene) -> Result<FrameInfo, BackendError> {
        let pixels = self.pixels_for(scene)?;
        let (info, ..) = self.frame_into(scene, &pixels, &mut prismatic_core::NoProgress)?;
        self.ctx.wait()?;
        Ok(info)
    }

    /// [`GpuBackend::frame`], then the image read back.
    pub fn frame_image(&mut self, scene: &PreparedScene) -> Result<(FrameInfo, Image), BackendError> {
        let info = self.frame(scene)?;
        let r = &scene.scene.render;
        let pixels = self.pixels_for(scene)?;
        Ok((info, render::read_image(&self.ctx, &pixels, r.width, r.height)?))
    }

    /// Renders a frame into the caller's `buffer` (`STORAGE` usage, at
    /// least width × height × [`PIXEL_BYTES`]): row-major `vec4<f32>`,
    /// linear RGB with exposure applied, alpha 1. Returns when the frame is
    /// done (the render reads back whether every pixel had its visible points).
    pub fn render_into_buffer(
        &mut self,
        scene: &PreparedScene,
        buffer: &wgpu::Buffer,
    ) -> Result<FrameInfo, BackendError> {
        Ok(self.frame_into(scene, buffer, &mut prismatic_core::NoProgress)?.0)
    }

    /// Renders a frame into the caller's storage texture (the image's size;
    /// `Rgba32Float`, `Rgba16Float` or `Rgba8Unorm`; `STORAGE_BINDING`
    /// usage) with a copy on the device; the copy is submitted, not waited for.
    pub fn render_into_texture(
        &mut self,
        scene: &PreparedScene,
        texture: &wgpu::Texture,
    ) -> Result<FrameInfo, BackendError> {
        let pixels = self.pixels_for(scene)?;
        let (info, mut buffers, _) = self.frame_into(scene, &pixels, &mut prismatic_core::NoProgress)?;
        render::copy_to_texture(&self.ctx, &mut self.pipelines, &mut buffers, &pixels, texture)?;
        Ok(info)
    }
}

impl GpuBackend {
    /// Uploads `photons` and builds their grid, waiting for the device
    /// (the `grid/gpu` bench: the stage alone).
    pub fn build_grid(&mut self, scene: &PreparedScene, photons: &PhotonMap) -> Result<(), BackendError> {
        let mut buffers = self.upload(scene)?;
        let array = PhotonArray::upload(&self.ctx, &photons.photons, self.window())?;
        let map = trace::DeviceMap::uploaded(&self.ctx, array, photons.photons.len() as u32);
        grid::build(&self.ctx, &self.pipelines, &mut buffers, &map)?;
        self.ctx.wait()
    }
}

impl Backend for GpuBackend {
    fn name(&self) -> &'static str {
        "gpu"
    }

    fn trace_photons(&mut self, scene: &PreparedScene, progress: &mut dyn Progress) -> Result<PhotonMap, BackendError> {
        let mut buffers = self.upload(scene)?;
        let map = self.trace_on_device(scene, &mut buffers, progress)?;
        let photons = map.photons.read(&self.ctx, map.stored)?;
        Ok(PhotonMap { photons, stats: map.stats(&self.ctx)? })
    }

    fn render(
        &mut self,
        scene: &PreparedScene,
        photons: &PhotonMap,
        progress: &mut dyn Progress,
    ) -> Result<Image, BackendError> {
        let mut buffers = self.upload(scene)?;
        let window = self.window();
        let stored = photons.photons.len() as u32;
        let map =
            trace::DeviceMap::uploaded(&self.ctx, PhotonArray::upload(&self.ctx, &photons.photons, window)?, stored);
        let grid = grid::build(&self.ctx, &self.pipelines, &mut buffers, &map)?;
        let pixels = self.pixels_for(scene)?;
        render::render(&self.ctx, &mut self.pipelines, &mut buffers, &grid, &mut self.gatherer, &pixels)?;
        let r = &scene.scene.render;
        let image = render::read_image(&self.ctx, &pixels, r.width, r.height)?;
        progress.advance(Stage::Render, u64::from(r.height), u64::from(r.height));
        Ok(image)
    }

    /// The whole frame on the device: the photon map is never read back.
    fn trace_and_render(
        &mut self,
        scene: &PreparedScene,
        progress: &mut dyn Progress,
    ) -> Result<(TraceStats, Image), BackendError> {
        let pixels = self.pixels_for(scene)?;
        let (_, _, map) = self.frame_into(scene, &pixels, progress)?;
        let r = &scene.scene.render;
        let image = render::read_image(&self.ctx, &pixels, r.width, r.height)?;
        progress.advance(Stage::Render, u64::from(r.height), u64::from(r.height));
        Ok((map.stats(&self.ctx)?, image))
    }

    /// A pass on the device: trace, grids, gather at the points; the
    /// points' sums are read back (the photon map is not).
    fn gather_pass(
        &mut self,
        scene: &PreparedScene,
        points: &[VisiblePoint],
        radii: &[f32],
    ) -> Result<PassGather, BackendError> {
        let mut buffers = self.upload(scene)?;
        let map = self.trace_on_device(scene, &mut buffers, &mut prismatic_core::NoProgress)?;
        let span = self.gatherer.span;
        let (irradiance, photons) =
            progressive::gather_pass(&self.ctx, &self.pipelines, &mut buffers, &map, span, scene, points, radii)?;
        Ok(PassGather { irradiance, photons, stats: map.stats(&self.ctx)? })
    }
}
