//! Values read back from the device without waiting: the copy and the
//! mapping are submitted now; a later frame, after polling the device,
//! looks whether the bytes have come, or waits for them.

use crate::context::GpuContext;
use prismatic_core::BackendError;
use std::sync::{Arc, Condvar, Mutex};

/// The first bytes of a device buffer, on their way to the host.
pub struct PendingRead {
    staging: wgpu::Buffer,
    /// Bytes read: the start of `staging`.
    size: u64,
    /// The mapping's outcome once its callback has run, and the signal
    /// that it has.
    mapped: Arc<(Mutex<Option<Mapped>>, Condvar)>,
}

/// The outcome of mapping a staging buffer.
type Mapped = Result<(), wgpu::BufferAsyncError>;

impl PendingRead {
    /// Submits a copy of `source`'s first u32 and starts mapping it;
    /// `what` names it in errors.
    pub fn start(ctx: &GpuContext, source: &wgpu::Buffer, what: &str) -> Result<Self, BackendError> {
        let staging = ctx.checked(&format!("reading {what}"), || staging_buffer(&ctx.device, 4))?;
        Self::start_in(ctx, source, staging, 4, what)
    }

    /// Submits a copy of `source`'s first `size` bytes (a multiple of 4)
    /// into the caller's `staging` buffer (from [`staging_buffer`], at
    /// least `size` bytes, not mapped: a read repeated every frame
    /// allocates nothing) and starts mapping it; `what` names it in errors.
    pub fn start_in(
        ctx: &GpuContext,
        source: &wgpu::Buffer,
        staging: wgpu::Buffer,
        size: u64,
        what: &str,
    ) -> Result<Self, BackendError> {
        ctx.checked(&format!("reading {what}"), || {
            let mut encoder = ctx.device.create_command_encoder(&Default::default());
            encoder.copy_buffer_to_buffer(source, 0, &staging, 0, size);
            ctx.queue.submit([encoder.finish()]);
        })?;
        ctx.count_read(size);
        let mapped = Arc::new((Mutex::new(None), Condvar::new()));
        let done = Arc::clone(&mapped);
        staging.slice(..size).map_async(wgpu::MapMode::Read, move |r| {
            if let Ok(mut slot) = done.0.lock() {
                *slot = Some(r);
                done.1.notify_all();
            }
        });
        Ok(PendingRead { staging, size, mapped })
    }

    /// The first u32 when the mapping has completed (the caller polls the
    /// device first), `None` while it has not; never waits.
    pub fn value(&self) -> Result<Option<u32>, BackendError> {
        Ok(self.bytes()?.map(|bytes| u32::from_le_bytes(bytes[..4].try_into().expect("4 bytes"))))
    }

    /// The bytes when the mapping has completed (the caller polls the
    /// device first), `None` while it has not; never waits.
    pub fn bytes(&self) -> Result<Option<Vec<u8>>, BackendError> {
        let Some(result) = self.mapped.0.lock().ok().and_then(|mut m| m.take()) else { return Ok(None) };
        result.map_err(|e| BackendError::Device(format!("mapping a value read back: {e}")))?;
        let bytes = self
            .staging
            .slice(..self.size)
            .get_mapped_range()
            .map_err(|e| BackendError::Device(format!("reading a mapped buffer: {e}")))?
            .to_vec();
        self.staging.unmap();
        Ok(Some(bytes))
    }

    /// Waits until the bytes have come: for the device, then for the
    /// mapping's callback, which another thread polling the same device
    /// (an engine's, or another test's) may be the one to run after this
    /// thread's wait has returned. [`PendingRead::bytes`] then has them.
    pub fn wait(&self, ctx: &GpuContext) -> Result<(), BackendError> {
        ctx.wait()?;
        let (slot, signal) = &*self.mapped;
        let lost = |_| BackendError::Device("a read-back's callback panicked".into());
        let slot = slot.lock().map_err(lost)?;
        drop(signal.wait_while(slot, |mapped| mapped.is_none()).map_err(lost)?);
        Ok(())
    }
}

/// A host-readable buffer of `size` bytes for [`PendingRead`]s.
pub fn staging_buffer(device: &wgpu::Device, size: u64) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("prismatic readback"),
        size,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}
