//! The device the backend works on: its own (adapter chosen here) or a
//! caller's (a game engine's `Device` and `Queue`), the limits and features
//! it needs, the translation of wgpu errors (validation, out of memory,
//! device lost) into `BackendError`s, and the count of the bytes that cross
//! between host and device (every write and read goes through it).

use prismatic_core::{Arithmetic, BackendError};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};

/// Storage buffers a session's gather binds, the most of any stage: the
/// bands, cells, point count, visible points, pixels, four windows of
/// the sorted photons and the scene's objects, surfaces, geometry and
/// tables (group 0), the pixels' sums and direct light, the levels used,
/// the statistics, the level lists and the pixels' first radii (group 1).
pub const STORAGE_BUFFERS_NEEDED: u32 = 19;

/// A device and queue with what the backend knows about them. Clones share
/// the device and the count of bytes moved ([`GpuContext::counting_apart`]
/// makes one with a count of its own).
#[derive(Clone)]
pub struct GpuContext {
    /// The device.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
    /// The adapter, when the backend chose it.
    pub adapter: Option<wgpu::AdapterInfo>,
    lost: Arc<Mutex<Option<String>>>,
    traffic: Arc<Traffic>,
    /// While a caller records ([`GpuContext::record`]): the command buffers
    /// made instead of submitted, in order.
    recorded: Arc<Mutex<Option<Vec<wgpu::CommandBuffer>>>>,
}

/// Bytes written to the device and read back from it.
#[derive(Debug, Default)]
struct Traffic {
    uploaded: AtomicU64,
    read_back: AtomicU64,
}

/// The features stage times need; a device the backend creates requests
/// them when its adapter has them.
pub fn timestamp_features() -> wgpu::Features {
    wgpu::Features::TIMESTAMP_QUERY | wgpu::Features::TIMESTAMP_QUERY_INSIDE_ENCODERS
}

/// Which adapters an own device may run on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AdapterChoice {
    /// The best adapter there is, software (lavapipe) included.
    Any,
    /// Only a hardware GPU (discrete, integrated or virtual).
    HardwareOnly,
}

/// The limits to request from `adapter` for this backend: WebGPU's
/// defaults, plus the storage buffers it binds and the adapter's own buffer
/// and binding sizes (so that large photon maps need fewer chunks).
pub fn required_limits(adapter: &wgpu::Limits) -> wgpu::Limits {
    wgpu::Limits {
        max_storage_buffers_per_shader_stage: STORAGE_BUFFERS_NEEDED
            .max(16)
            .min(adapter.max_storage_buffers_per_shader_stage),
        max_storage_buffer_binding_size: adapter.max_storage_buffer_binding_size,
        max_buffer_size: adapter.max_buffer_size,
        ..wgpu::Limits::default()
    }
}

fn rank(t: wgpu::DeviceType) -> u32 {
    match t {
        wgpu::DeviceType::DiscreteGpu => 4,
        wgpu::DeviceType::IntegratedGpu => 3,
        wgpu::DeviceType::VirtualGpu => 2,
        wgpu::DeviceType::Cpu => 1,
        wgpu::DeviceType::Other => 0,
    }
}

/// True for adapters that are real GPUs (not a software rasterizer).
pub fn is_hardware(info: &wgpu::AdapterInfo) -> bool {
    rank(info.device_type) >= 2
}

/// Names an adapter for messages: "llvmpipe (LLVM 15.0.6, 256 bits), Vulkan, Cpu".
pub fn describe(info: &wgpu::AdapterInfo) -> String {
    format!("{}, {:?}, {:?}", info.name, info.backend, info.device_type)
}

/// A device for a test on the best adapter there is (lavapipe on a machine
/// without a GPU): the one GPU-or-fail rule of every test. Without any
/// adapter a test fails under `CI=true` (CI installs lavapipe, so a missing
/// adapter is a broken machine); elsewhere it prints that `what` is skipped
/// and gets `None`.
pub fn test_context(what: &str) -> Option<GpuContext> {
    match GpuContext::new(AdapterChoice::Any) {
        Ok(ctx) => Some(ctx),
        Err(e) if std::env::var_os("CI").is_some() => panic!("CI=true and no GPU adapter for {what}: {e}"),
        Err(e) => {
            eprintln!("SKIPPING {what} on this machine: {e}");
            None
        }
    }
}

impl GpuContext {
    /// How this device's shaders round: strict on a software rasterizer
    /// (lavapipe), relaxed on a GPU's compiler, and on an engine's device,
    /// whose adapter the context cannot see.
    pub fn arithmetic(&self) -> Arithmetic {
        match &self.adapter {
            Some(info) if !is_hardware(info) => Arithmetic::Strict,
            _ => Arithmetic::Relaxed,
        }
    }

    /// Creates a device on the best adapter (`choice` says which count).
    pub fn new(choice: AdapterChoice) -> Result<Self, BackendError> {
        // Only the backends searched below (no EGL opened for nothing).
        let mut descriptor = wgpu::InstanceDescriptor::new_without_display_handle_from_env();
        descriptor.backends &= wgpu::Backends::PRIMARY;
        let instance = wgpu::Instance::new(descriptor);
        let adapters = pollster::block_on(instance.enumerate_adapters(wgpu::Backends::PRIMARY));
        let seen: Vec<String> = adapters.iter().map(|a| describe(&a.get_info())).collect();
        let best = adapters
            .into_iter()
            .filter(|a| a.limits().max_storage_buffers_per_shader_stage >= STORAGE_BUFFERS_NEEDED)
            .filter(|a| choice == AdapterChoice::Any || is_hardware(&a.get_info()))
            .max_by_key(|a| rank(a.get_info().device_type));
        let Some(adapter) = best else {
            let what = if choice == AdapterChoice::Any { "GPU adapter" } else { "hardware GPU adapter" };
            let detail = if seen.is_empty() {
                "wgpu found no Vulkan, Metal or DX12 adapter on this machine (for a software one install \
                 Mesa's lavapipe, Debian package mesa-vulkan-drivers); use --backend cpu"
                    .to_string()
            } else {
                format!("adapters seen: {} (none suitable); use --backend cpu", seen.join("; "))
            };
            return Err(BackendError::NoDevice { what, detail });
        };
        let info = adapter.get_info();
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("prismatic"),
            required_limits: required_limits(&adapter.limits()),
            // Stage times for sessions where the adapter has timestamps (optional).
            required_features: adapter.features() & timestamp_features(),
            ..Default::default()
        }))
        .map_err(|e| BackendError::NoDevice {
            what: "GPU device",
            detail: format!("{} refused a device: {e}; use --backend cpu", describe(&info)),
        })?;
        // Errors are collected by error scopes around each piece of work;
        // one that escapes them must not abort the process.
        device.on_uncaptured_error(Arc::new(|e| eprintln!("prismatic-gpu: uncaptured wgpu error: {e}")));
        let mut ctx = GpuContext::from_device(device, queue)?;
        ctx.watch_for_loss();
        ctx.adapter = Some(info);
        Ok(ctx)
    }

    /// Wraps a caller's device and queue (a game engine's). The device must
    /// allow [`STORAGE_BUFFERS_NEEDED`] storage buffers per shader stage
    /// (request [`required_limits`] when creating it). Its device-lost
    /// callback stays the caller's.
    pub fn from_device(device: wgpu::Device, queue: wgpu::Queue) -> Result<Self, BackendError> {
        let have = device.limits().max_storage_buffers_per_shader_stage;
        if have < STORAGE_BUFFERS_NEEDED {
            return Err(BackendError::Device(format!(
                "the device allows {have} storage buffers per shader stage and the gpu backend binds \
                 {STORAGE_BUFFERS_NEEDED}; create it with prismatic_gpu::required_limits(&adapter.limits())"
            )));
        }
        Ok(GpuContext {
            device,
            queue,
            adapter: None,
            lost: Arc::new(Mutex::new(None)),
            traffic: Arc::default(),
            recorded: Arc::default(),
        })
    }

    /// The same device and queue with a count of bytes moved of its own,
    /// starting at zero (a render counts its own traffic), and recordings
    /// of its own.
    pub fn counting_apart(&self) -> Self {
        GpuContext { traffic: Arc::default(), recorded: Arc::default(), ..self.clone() }
    }

    /// Runs `work` with every submission through this context (and its
    /// clones) recorded instead of submitted, and returns the command
    /// buffers for the caller to submit in its own order: an engine whose
    /// frame submits its command buffers together at its end puts them
    /// between its own (after its depth prepass, before its main pass).
    /// Writes keep their place among them (each a copy from a buffer of its
    /// own). Reads and waits inside `work` see the device as it was before.
    pub fn record<T>(&self, work: impl FnOnce() -> T) -> (T, Vec<wgpu::CommandBuffer>) {
        *self.recorded.lock().unwrap_or_else(|p| p.into_inner()) = Some(Vec::new());
        let out = work();
        let buffers = self.recorded.lock().unwrap_or_else(|p| p.into_inner()).take().unwrap_or_default();
        (out, buffers)
    }

    /// Whether submissions are being recorded ([`GpuContext::record`]).
    pub(crate) fn recording(&self) -> bool {
        self.recorded.lock().map(|r| r.is_some()).unwrap_or(false)
    }

    /// Submits `encoder`'s commands, or keeps them while recording.
    pub(crate) fn submit(&self, encoder: wgpu::CommandEncoder) {
        let buffer = encoder.finish();
        let mut recorded = self.recorded.lock().unwrap_or_else(|p| p.into_inner());
        match recorded.as_mut() {
            Some(buffers) => buffers.push(buffer),
            None => {
                drop(recorded);
                self.queue.submit([buffer]);
            }
        }
    }

    /// Bytes written to the device and read back from it through this
    /// context (and its clones) so far.
    pub fn traffic(&self) -> (u64, u64) {
        (self.traffic.uploaded.load(Ordering::Relaxed), self.traffic.read_back.load(Ordering::Relaxed))
    }

    /// Writes `data` into `buffer` at `offset` (visible to the next
    /// submit; while recording, to the commands recorded after it), counted.
    pub(crate) fn write(&self, buffer: &wgpu::Buffer, offset: u64, data: &[u8]) {
        if self.recording() {
            let source = self.buffer_with("prismatic recorded write", data, wgpu::BufferUsages::COPY_SRC);
            let mut encoder = self.device.create_command_encoder(&Default::default());
            encoder.copy_buffer_to_buffer(&source, 0, buffer, offset, data.len() as u64);
            self.submit(encoder);
            return;
        }
        self.traffic.uploaded.fetch_add(data.len() as u64, Ordering::Relaxed);
        self.queue.write_buffer(buffer, offset, data);
    }

    /// A buffer made with `contents` (an upload, counted) and `usage`.
    pub(crate) fn buffer_with(&self, label: &str, contents: &[u8], usage: wgpu::BufferUsages) -> wgpu::Buffer {
        use wgpu::util::DeviceExt;
        self.traffic.uploaded.fetch_add(contents.len() as u64, Ordering::Relaxed);
        self.device.create_buffer_init(&wgpu::util::BufferInitDescriptor { label: Some(label), contents, usage })
    }

    /// Counts `bytes` read back (for reads that map their own staging buffers).
    pub(crate) fn count_read(&self, bytes: u64) {
        self.traffic.read_back.fetch_add(bytes, Ordering::Relaxed);
    }

    /// Notes the device's loss, so that the next piece of work says so
    /// (only on the backend's own device: an engine's device-lost callback
    /// is the engine's, and replacing it would break its recovery).
    fn watch_for_loss(&self) {
        let sink = Arc::clone(&self.lost);
        self.device.set_device_lost_callback(move |reason, message| {
            if let Ok(mut slot) = sink.lock() {
                *slot = Some(format!("{reason:?}: {message}"));
            }
        });
    }

    /// The device's limits.
    pub fn limits(&self) -> wgpu::Limits {
        self.device.limits()
    }

    /// An error if the device has been lost.
    pub fn check_lost(&self) -> Result<(), BackendError> {
        match self.lost.lock().ok().and_then(|l| l.clone()) {
            Some(why) => Err(BackendError::Device(format!("the GPU device was lost ({why}); use --backend cpu"))),
            None => Ok(()),
        }
    }

    /// Runs `work` (which creates resources and submits commands) under
    /// error scopes and turns what they catch into a `BackendError` naming `what`.
    pub fn checked<T>(&self, what: &str, work: impl FnOnce() -> T) -> Result<T, BackendError> {
        self.check_lost()?;
        let oom = self.device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
        let validation = self.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let internal = self.device.push_error_scope(wgpu::ErrorFilter::Internal);
        let out = work();
        let internal = pollster::block_on(internal.pop());
        let validation = pollster::block_on(validation.pop());
        let oom = pollster::block_on(oom.pop());
        self.check_lost()?;
        if let Some(e) = oom {
            return Err(BackendError::OutOfMemory(format!("{what}: {e}")));
        }
        if let Some(e) = validation.or(internal) {
            return Err(BackendError::Device(format!("{what}: {e}")));
        }
        Ok(out)
    }

    /// Waits until the device has finished all submitted work.
    pub fn wait(&self) -> Result<(), BackendError> {
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| BackendError::Device(format!("waiting for the GPU: {e}")))?;
        self.check_lost()
    }

    /// Copies `size` bytes at `offset` of `buffer` to the host (waits for the device).
    pub fn read(&self, buffer: &wgpu::Buffer, offset: u64, size: u64) -> Result<Vec<u8>, BackendError> {
        if size == 0 {
            return Ok(Vec::new());
        }
        self.count_read(size);
        let staging = self.checked("readback buffer", || {
            let staging = self.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("prismatic readback"),
                size,
                usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            let mut encoder = self.device.create_command_encoder(&Default::default());
            encoder.copy_buffer_to_buffer(buffer, offset, &staging, 0, size);
            self.queue.submit([encoder.finish()]);
            staging
        })?;
        let (send, recv) = std::sync::mpsc::channel();
        staging.slice(..).map_async(wgpu::MapMode::Read, move |r| {
            let _ = send.send(r);
        });
        self.wait()?;
        recv.recv()
            .map_err(|_| BackendError::Device("readback never completed".into()))?
            .map_err(|e| BackendError::Device(format!("mapping a readback buffer: {e}")))?;
        let bytes = staging
            .slice(..)
            .get_mapped_range()
            .map_err(|e| BackendError::Device(format!("reading a mapped buffer: {e}")))?
            .to_vec();
        staging.unmap();
        Ok(bytes)
    }
}
