//! A caustic layer's temporal accumulation for an engine that draws every
//! frame (history.wgsl): each frame is one pass of its own, folded into
//! each pixel's running mean since its surface last changed, at most a cap
//! of frames long. A static caustic in a static frame converges (the mean
//! of every frame, up to the cap: an exponential window past it); a pixel
//! whose surface changes (a moving occluder, a camera move) starts again
//! there alone; and while the light or glass moves, the engine lowers the
//! cap, so that the caustic follows within a few frames and each frame's
//! noise is still averaged.

use super::GpuSession;
use super::layer::FrameTextures;
use crate::pipelines::dispatch;
use crate::shaders::WORKGROUP_SIZE;
use prismatic_core::util::tolerance::LAYER_PLANE_REL;
use prismatic_core::{BackendError, Change, NoProgress, Render};

/// The history's buffers: per pixel the running mean and its frame count,
/// and the frame before this one.
pub(super) struct LayerHistory {
    history: wgpu::Buffer,
    previous: wgpu::Buffer,
    pixels: u64,
}

/// history.wgsl's `HistoryParams`.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct HistoryParams {
    pixels: u32,
    cap: u32,
    plane_rel: f32,
    pad: u32,
}

impl GpuSession {
    /// One frame of a caustic layer with temporal accumulation: the
    /// engine's frame read from `textures`, one pass numbered `frame` (each
    /// frame's photons differ), and each pixel's running mean since its
    /// surface last changed, at most `cap` frames long (at least 1: 1 is
    /// this frame's pass alone), which [`GpuSession::copy_to_texture`] then
    /// shows. The sums hold this frame's pass only.
    pub fn layer_frame(&mut self, textures: &FrameTextures, frame: u32, cap: u32) -> Result<(), BackendError> {
        let pixels = u64::from(self.scene.scene.render.width) * u64::from(self.scene.scene.render.height);
        if self.history.as_ref().is_none_or(|h| h.pixels != pixels) {
            self.history = Some(self.ctx.checked("allocating the layer's history", || {
                let buffer = |label: &str, size: u64| {
                    self.ctx.device.create_buffer(&wgpu::BufferDescriptor {
                        label: Some(label),
                        size,
                        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                        mapped_at_creation: false,
                    })
                };
                LayerHistory {
                    history: buffer("prismatic layer history", pixels * 16),
                    previous: buffer("prismatic layer previous frame", pixels * 8),
                    pixels,
                }
            })?);
        }
        if let (Some(history), Some(current)) = (&self.history, &self.layer)
            && current.size() == history.previous.size()
        {
            let mut encoder = self.ctx.device.create_command_encoder(&Default::default());
            encoder.copy_buffer_to_buffer(current, 0, &history.previous, 0, current.size());
            self.ctx.submit(encoder);
        }
        self.refresh_layer_textures(textures)?;
        self.passes.clear();
        self.stale = self.stale.max(Change::View);
        self.run_pass(frame, &mut NoProgress)?;
        let (Some(history), Some(current)) = (&self.history, &self.layer) else { return Ok(()) };
        let params = HistoryParams { pixels: pixels as u32, cap: cap.max(1), plane_rel: LAYER_PLANE_REL, pad: 0 };
        self.ctx.checked("blending the layer's history", || {
            let params = self.ctx.buffer_with(
                "prismatic history params",
                bytemuck::bytes_of(&params),
                wgpu::BufferUsages::UNIFORM,
            );
            let group = self.ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("prismatic layer history"),
                layout: &self.pipelines.history_layout,
                entries: &[
                    wgpu::BindGroupEntry { binding: 0, resource: params.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 1, resource: self.pixels.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 2, resource: history.history.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 3, resource: history.previous.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 4, resource: current.as_entire_binding() },
                ],
            });
            let mut encoder = self.ctx.device.create_command_encoder(&Default::default());
            dispatch(&mut encoder, &self.pipelines.blend_history, &[&group], pixels, WORKGROUP_SIZE);
            self.ctx.submit(encoder);
        })
    }
}
