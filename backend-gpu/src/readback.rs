//! Values read back from the device without waiting: the copy and the
//! mapping are submitted now; a later frame, after polling the device,
//! looks whether the bytes have come.

use crate::context::GpuContext;
use prismatic_core::BackendError;
use std::sync::{Arc, Mutex};

/// The first bytes of a device buffer, on their way to the host.
pub struct PendingRead {
    staging: wgpu::Buffer,
    /// Bytes read: the start of `staging`.
    size: u64,
    mapped: Arc<Mutex<Option<Result<(), wgpu::BufferAsyncError>>>>,
}

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
        let mapped = Arc::new(Mutex::new(None));
        let done = Arc::clone(&mapped);
        staging.slice(..size).map_async(wgpu::MapMode::Read, move |r| {
            if let Ok(mut slot) = done.lock() {
                *slot = Some(r);
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
        let Some(result) = self.mapped.lock().ok().and_then(|mut m| m.take()) else { return Ok(None) };
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
