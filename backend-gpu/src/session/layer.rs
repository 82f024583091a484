//! A session's caustic layer (layer.wgsl, the twin of
//! `prismatic_core::render::layer`): the engine's frame on the device (from
//! the host's [`LayerFrame`], or from the engine's depth and normal
//! textures by frame.wgsl), the view that replaces the view rays (black, no
//! visible points), and each pass's photons splatted into the pixels' sums
//! where the frame sees them.

use super::GpuSession;
use crate::pipelines::dispatch;
use crate::shaders::WORKGROUP_SIZE;
use prismatic_core::model::photon::oct_pack;
use prismatic_core::{BackendError, Change, LayerFrame};

/// Bytes of a pixel of the device's frame: the packed normal, the depth's bits.
const FRAME_TEXEL_BYTES: u64 = 8;

/// An engine's frame on the device, as its depth and normal prepass leave
/// it, seen by the scene's camera at the scene's image size.
pub struct FrameTextures<'a> {
    /// The depth buffer: a depth format, multisampled or not (a pixel's
    /// samples are averaged; a pixel with a sample left clear sees nothing).
    pub depth: &'a wgpu::TextureView,
    /// How it holds depth.
    pub depth_encoding: DepthEncoding,
    /// World-space normals in RGB: a float or unorm colour format, as many
    /// samples as the depth.
    pub normal: &'a wgpu::TextureView,
    /// How they are stored.
    pub normal_encoding: NormalEncoding,
}

/// How a depth buffer holds the view-space depth s (the distance along the
/// camera's optical axis).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum DepthEncoding {
    /// Reversed Z with an infinite far plane, d = near / s (Bevy's
    /// perspective, glam's `perspective_infinite_reverse_rh`); 0 is clear.
    ReverseInfinite {
        /// The near plane's distance.
        near: f32,
    },
    /// wgpu's default perspective, d = far (s − near) / (s (far − near))
    /// (glam's `perspective_rh`); 1 is clear.
    Forward {
        /// The near plane's distance.
        near: f32,
        /// The far plane's distance.
        far: f32,
    },
}

/// How a normal texture stores a world-space unit normal n.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NormalEncoding {
    /// n · 0.5 + 0.5 in a unorm format (Bevy's normal prepass, `Rgb10a2Unorm`).
    Unorm,
    /// n itself, in a float format.
    Signed,
}

/// frame.wgsl's `FrameParams`.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct FrameParams {
    width: u32,
    height: u32,
    depth_encoding: u32,
    normal_encoding: u32,
    near: f32,
    far: f32,
    pad: [u32; 2],
}

impl GpuSession {
    /// From now on, draws the caustic as a layer in the engine's frame that
    /// `textures` hold on the device ([`prismatic_core::Render::set_layer`]
    /// with no trip through the host): a kernel reads them into the layer's
    /// frame before the next pass. Starts the passes again; an error when
    /// the textures are not of the scene's image size.
    pub fn set_layer_textures(&mut self, textures: &FrameTextures) -> Result<(), BackendError> {
        self.read_frame(textures)?;
        self.passes.clear();
        self.stale = self.stale.max(Change::View);
        Ok(())
    }

    /// Reads the engine's frame again from `textures` and keeps the passes
    /// (a layer's frame in [`GpuSession::layer_frame`]); a session without a
    /// layer sets one ([`GpuSession::set_layer_textures`]).
    pub(super) fn refresh_layer_textures(&mut self, textures: &FrameTextures) -> Result<(), BackendError> {
        if self.layer.is_none() {
            return self.set_layer_textures(textures);
        }
        self.read_frame(textures)
    }

    /// The engine's frame read from `textures` into the layer's frame
    /// (allocated when missing or of another size).
    fn read_frame(&mut self, textures: &FrameTextures) -> Result<(), BackendError> {
        let r = &self.scene.scene.render;
        let size = |view: &wgpu::TextureView| {
            let t = view.texture();
            (t.width(), t.height())
        };
        for (what, view) in [("depth", textures.depth), ("normal", textures.normal)] {
            if size(view) != (r.width, r.height) {
                let (w, h) = size(view);
                return Err(BackendError::FrameSize {
                    frame: format!("{w}x{h} ({what} texture)"),
                    image: format!("{}x{}", r.width, r.height),
                });
            }
        }
        let pixels = u64::from(r.width) * u64::from(r.height);
        let (frame, fresh) = match self.layer.take() {
            Some(frame) if frame.size() == pixels * FRAME_TEXEL_BYTES => (frame, false),
            old => {
                self.stale = self.stale.max(if old.is_some() { Change::View } else { Change::Size });
                let buffer = self.ctx.checked("allocating the layer's frame", || {
                    self.ctx.device.create_buffer(&wgpu::BufferDescriptor {
                        label: Some("prismatic layer frame"),
                        size: pixels * FRAME_TEXEL_BYTES,
                        usage: wgpu::BufferUsages::STORAGE
                            | wgpu::BufferUsages::COPY_DST
                            | wgpu::BufferUsages::COPY_SRC,
                        mapped_at_creation: false,
                    })
                })?;
                (buffer, true)
            }
        };
        let (depth_encoding, near, far) = match textures.depth_encoding {
            DepthEncoding::ReverseInfinite { near } => (0, near, f32::INFINITY),
            DepthEncoding::Forward { near, far } => (1, near, far),
        };
        let normal_encoding = u32::from(textures.normal_encoding == NormalEncoding::Signed);
        let params =
            FrameParams { width: r.width, height: r.height, depth_encoding, normal_encoding, near, far, pad: [0; 2] };
        let multisampled = textures.depth.texture().sample_count() > 1;
        if multisampled != (textures.normal.texture().sample_count() > 1) {
            return Err(BackendError::Device("the engine's depth and normal textures differ in samples".into()));
        }
        let (layout, pipeline) = (
            &self.pipelines.frame_layouts[usize::from(multisampled)],
            &self.pipelines.frame_from_textures[usize::from(multisampled)],
        );
        self.ctx.checked("reading the engine's frame", || {
            let params = self.ctx.buffer_with(
                "prismatic frame params",
                bytemuck::bytes_of(&params),
                wgpu::BufferUsages::UNIFORM,
            );
            let group = self.ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("prismatic engine frame"),
                layout,
                entries: &[
                    wgpu::BindGroupEntry { binding: 0, resource: params.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 1, resource: wgpu::BindingResource::TextureView(textures.depth) },
                    wgpu::BindGroupEntry { binding: 2, resource: wgpu::BindingResource::TextureView(textures.normal) },
                    wgpu::BindGroupEntry { binding: 3, resource: frame.as_entire_binding() },
                ],
            });
            let mut encoder = self.ctx.device.create_command_encoder(&Default::default());
            dispatch(&mut encoder, pipeline, &[&group], pixels, WORKGROUP_SIZE);
            self.ctx.submit(encoder);
        })?;
        self.adopt_frame(Some(frame), fresh)
    }

    /// Makes `frame` the layer's frame; a `fresh` one (another buffer) is
    /// bound to every chunk's layer group.
    pub(super) fn adopt_frame(&mut self, frame: Option<wgpu::Buffer>, fresh: bool) -> Result<(), BackendError> {
        self.layer = frame;
        if fresh && !self.points.chunks.is_empty() {
            self.bind_points()?;
        }
        Ok(())
    }

    /// The engine's `frame` as the device's frame: per pixel the packed
    /// normal and the depth's bits.
    pub(super) fn upload_frame(&self, frame: &LayerFrame) -> Result<wgpu::Buffer, BackendError> {
        let texels: Vec<[u32; 2]> =
            frame.normal.iter().zip(&frame.depth).map(|(&n, &d)| [oct_pack(n), d.to_bits()]).collect();
        self.ctx.checked("uploading the layer's frame", || {
            self.ctx.buffer_with(
                "prismatic layer frame",
                bytemuck::cast_slice(&texels),
                wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC,
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
            self.ctx.submit(encoder);
        })
    }
}
