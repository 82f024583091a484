//! prismatic-gpu: the wgpu compute backend.
//!
//! Every stage runs on the device in WGSL (`src/shaders/`), each a twin of
//! the core stage of the same name: emit + trace (same counter-based RNG,
//! bit for bit), compaction into canonical (emission, band, bounces) order, hash-grid
//! build (count, prefix sum, scatter), the view rays into visible points,
//! and the gather at them. A render ([`GpuSession`], the backend's
//! implementation of the render protocol) keeps the scene, photon map,
//! grids, visible points and exact sums on the device: a pass uploads a
//! few uniforms and reads nothing back; the image, the sums and the
//! statistics are read back when asked for.
//!
//! An engine embeds a [`GpuSession`] on its own device
//! ([`GpuContext::from_device`]), runs a pass per frame and copies the
//! image into its texture on the device.

mod context;
mod grid;
pub mod layout;
mod levels;
mod photons;
mod pipelines;
mod pixels;
mod readback;
mod scan;
mod scene;
mod session;
pub mod shaders;
mod timing;
mod trace;

pub use context::{
    AdapterChoice, GpuContext, STORAGE_BUFFERS_NEEDED, describe, is_hardware, required_limits, test_context,
    timestamp_features,
};
pub use pixels::{PIXEL_BYTES, SOFTWARE_GATHER_SPAN};
pub use session::{DepthEncoding, FrameTextures, GpuSession, NormalEncoding, PASSES_IN_FLIGHT};

use pipelines::Pipelines;
use prismatic_core::{Arithmetic, Backend, BackendError, PreparedScene, Render};
use std::sync::Arc;

/// Options that change how the work is cut, not what it computes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct GpuOptions {
    /// Photons per storage binding; `None`: as many as the device allows.
    /// Tests set it small to run the multi-binding paths on small scenes.
    pub window_photons: Option<u32>,
    /// Photons of each grid bucket one gather dispatch reads; `None`: all
    /// of them in one dispatch on a hardware GPU, [`SOFTWARE_GATHER_SPAN`]
    /// on a software device (whose invocations may not loop long).
    pub gather_span: Option<u32>,
    /// Time each pass's stages with GPU timestamps, where the device has
    /// them ([`timestamp_features`]): a pass then also reads its stamps back
    /// (64 bytes, without waiting), so it is off unless asked for.
    pub stage_times: bool,
}

/// The wgpu backend: a device and the pipelines its renders share.
pub struct GpuBackend {
    ctx: GpuContext,
    pipelines: Arc<Pipelines>,
    options: GpuOptions,
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

    /// A backend on `ctx` with `options` (compiles every pipeline).
    pub fn with_context(ctx: GpuContext, options: GpuOptions) -> Self {
        let pipelines = Arc::new(Pipelines::new(&ctx.device));
        GpuBackend { ctx, pipelines, options }
    }

    /// A backend on this one's device with its compiled pipelines and
    /// `options` (nothing compiled again: a software device such as
    /// lavapipe takes about a second to compile them).
    pub fn with_options(&self, options: GpuOptions) -> Self {
        GpuBackend { ctx: self.ctx.clone(), pipelines: Arc::clone(&self.pipelines), options }
    }

    /// A backend for a test with `options`, on the device and compiled
    /// pipelines every test of the process shares ([`test_context`]'s
    /// rule: `None` only outside CI on a machine without an adapter). Each
    /// session keeps its own buffers and its own count of bytes moved.
    pub fn for_test(what: &str, options: GpuOptions) -> Option<Self> {
        static SHARED: std::sync::OnceLock<Option<GpuBackend>> = std::sync::OnceLock::new();
        let shared =
            SHARED.get_or_init(|| test_context(what).map(|ctx| GpuBackend::with_context(ctx, GpuOptions::default())));
        shared.as_ref().map(|gpu| gpu.with_options(options))
    }

    /// The adapter, when the backend chose it.
    pub fn adapter(&self) -> Option<&wgpu::AdapterInfo> {
        self.ctx.adapter.as_ref()
    }

    /// The device and queue (to share with the caller).
    pub fn context(&self) -> &GpuContext {
        &self.ctx
    }

    /// A session of `scene` on the backend's device: [`Backend::prepare`]
    /// with the session's own type (for its texture copy and pixel buffer).
    pub fn session(&self, scene: &PreparedScene) -> Result<GpuSession, BackendError> {
        GpuSession::with_pipelines(self.ctx.clone(), Arc::clone(&self.pipelines), scene, self.options)
    }
}

impl Backend for GpuBackend {
    fn name(&self) -> &'static str {
        "gpu"
    }

    fn arithmetic(&self) -> Arithmetic {
        self.ctx.arithmetic()
    }

    fn prepare(&mut self, scene: &PreparedScene) -> Result<Box<dyn Render>, BackendError> {
        Ok(Box::new(self.session(scene)?))
    }
}
