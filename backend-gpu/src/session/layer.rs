//! A session's caustic layer (layer.wgsl, the twin of
//! `prismatic_core::render::layer`): the engine's frame on the device, the
//! view that replaces the view rays (black, no visible points), and each
//! pass's photons splatted into the pixels' sums where the frame sees them.

use super::GpuSession;
use crate::pipelines::dispatch;
use crate::shaders::WORKGROUP_SIZE;
use prismatic_core::{BackendError, LayerFrame};

impl GpuSession {
    /// The engine's `frame` as the device's `vec4<f32>` per pixel (normal, depth).
    pub(super) fn upload_frame(&self, frame: &LayerFrame) -> Result<wgpu::Buffer, BackendError> {
        let texels: Vec<[f32; 4]> = frame.normal.iter().zip(&frame.depth).map(|(n, &d)| [n.x, n.y, n.z, d]).collect();
        self.ctx.checked("uploading the layer's frame", || {
            self.ctx.buffer_with(
                "prismatic layer frame",
                bytemuck::cast_slice(&texels),
                wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            )
        })
    }

    /// A layer's view: no view rays; every chunk's direct light black and
    /// no visible points.
    pub(super) fn clear_view(&mut self) -> Result<(), BackendError> {
        self.ctx.checked("clearing the layer's view", || {
            let mut encoder = self.ctx.device.create_command_encoder(&Default::default());
            for chunk in &self.points.chunks {
                encoder.clear_buffer(&chunk.total, 0, None);
                encoder.clear_buffer(&chunk.base, 0, None);
            }
            encoder.clear_buffer(&self.pixels, 0, None);
            self.ctx.queue.submit([encoder.finish()]);
        })
    }

    /// The pass's photons added to the sums of the pixels of the layer's
    /// frame that see them, chunk by chunk. One invocation per slot of the map.
    pub(super) fn splat_into_layer(&mut self) -> Result<(), BackendError> {
        let Some(frame) = &self.layer else { return Ok(()) };
        if self.photons.capacity() == 0 {
            return Ok(());
        }
        for chunk in &self.points.chunks {
            let p = &mut self.buffers.params;
            (p.pixel_offset, p.pixel_count) = (chunk.offset as u32, chunk.count as u32);
            self.buffers.write_params(&self.ctx);
            self.ctx.checked("splatting the pass into the layer", || {
                let mut entries = vec![
                    wgpu::BindGroupEntry { binding: 0, resource: chunk.sums.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 1, resource: self.photons.cursor().as_entire_binding() },
                ];
                entries.extend(self.photons.photons.entries(2));
                entries.push(wgpu::BindGroupEntry { binding: 6, resource: frame.as_entire_binding() });
                let group = self.ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("prismatic caustic layer"),
                    layout: &self.pipelines.layer_layout,
                    entries: &entries,
                });
                let mut encoder = self.ctx.device.create_command_encoder(&Default::default());
                let slots = u64::from(self.photons.capacity());
                dispatch(
                    &mut encoder,
                    &self.pipelines.layer_splat,
                    &[&self.buffers.bind_group, &group],
                    slots,
                    WORKGROUP_SIZE,
                );
                self.ctx.queue.submit([encoder.finish()]);
            })?;
        }
        Ok(())
    }
}
