//! A photon array on the device, split over `WINDOWS` buffers of at most
//! one binding each, so that maps larger than a storage binding still fit;
//! the shaders see one array through `{name}_load` / `{name}_store`.

use crate::context::GpuContext;
use crate::shaders::WINDOWS;
use prismatic_core::{BackendError, Photon};

/// Bytes of one photon.
pub const PHOTON_BYTES: u64 = std::mem::size_of::<Photon>() as u64;

/// Photons per window on `limits`: one binding, one buffer.
pub fn window_for(limits: &wgpu::Limits) -> u32 {
    let bytes = limits.max_storage_buffer_binding_size.min(limits.max_buffer_size);
    (bytes / PHOTON_BYTES).min(u64::from(u32::MAX / WINDOWS)) as u32
}

/// Photons in windows of `window` photons each.
pub struct PhotonArray {
    /// One buffer per window (unused windows get a one-photon buffer).
    pub buffers: Vec<wgpu::Buffer>,
    /// Photons per window.
    pub window: u32,
    /// Photons the array holds at most.
    pub capacity: u32,
}

impl PhotonArray {
    /// Room for `capacity` photons (at most `WINDOWS × window`).
    pub fn new(ctx: &GpuContext, label: &str, capacity: u32, window: u32) -> Result<Self, BackendError> {
        let capacity = capacity.min(window.saturating_mul(WINDOWS));
        let buffers = ctx.checked("allocating a photon array", || {
            (0..WINDOWS)
                .map(|w| {
                    let photons = capacity.saturating_sub(w * window).min(window).max(1);
                    ctx.device.create_buffer(&wgpu::BufferDescriptor {
                        label: Some(label),
                        size: u64::from(photons) * PHOTON_BYTES,
                        usage: wgpu::BufferUsages::STORAGE
                            | wgpu::BufferUsages::COPY_SRC
                            | wgpu::BufferUsages::COPY_DST,
                        mapped_at_creation: false,
                    })
                })
                .collect()
        })?;
        Ok(PhotonArray { buffers, window, capacity })
    }

    /// Uploads `photons` (which must fit): tests build grids over maps they made.
    #[cfg(test)]
    pub fn upload(ctx: &GpuContext, photons: &[Photon], window: u32) -> Result<Self, BackendError> {
        let n =
            u32::try_from(photons.len()).ok().filter(|&n| n <= window.saturating_mul(WINDOWS)).ok_or_else(|| {
                BackendError::OutOfMemory(format!(
                    "{} photons do not fit this device's {WINDOWS} storage bindings of {window} photons; \
                     use --backend cpu",
                    photons.len()
                ))
            })?;
        let array = PhotonArray::new(ctx, "prismatic uploaded photons", n, window)?;
        for (w, chunk) in photons.chunks(window.max(1) as usize).enumerate() {
            ctx.write(&array.buffers[w], 0, bytemuck::cast_slice(chunk));
        }
        Ok(array)
    }

    /// Bind-group entries for its windows at bindings `first..first + WINDOWS`.
    pub fn entries(&self, first: u32) -> Vec<wgpu::BindGroupEntry<'_>> {
        self.buffers
            .iter()
            .enumerate()
            .map(|(w, b)| wgpu::BindGroupEntry { binding: first + w as u32, resource: b.as_entire_binding() })
            .collect()
    }

    /// Reads the first `count` photons back.
    pub fn read(&self, ctx: &GpuContext, count: u32) -> Result<Vec<Photon>, BackendError> {
        let mut out = Vec::with_capacity(count as usize);
        let mut left = count.min(self.capacity);
        for buffer in &self.buffers {
            let n = left.min(self.window);
            if n == 0 {
                break;
            }
            let bytes = ctx.read(buffer, 0, u64::from(n) * PHOTON_BYTES)?;
            out.extend(bytemuck::pod_collect_to_vec::<u8, Photon>(&bytes));
            left -= n;
        }
        Ok(out)
    }
}
