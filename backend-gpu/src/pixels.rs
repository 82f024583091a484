//! The image on the device: a storage buffer of `vec4<f32>` per pixel
//! (linear RGB, exposure applied, alpha 1), worked on in chunks of pixels
//! that fit one binding each, copied on the device into a caller's storage
//! texture, or read back.

use crate::context::GpuContext;
use crate::pipelines::{Pipelines, dispatch};
use crate::scene::SceneBuffers;
use crate::shaders::WORKGROUP_SIZE;
use prismatic_core::{BackendError, Vec3};

/// Bytes per pixel of the pixel buffer.
pub const PIXEL_BYTES: u64 = 16;

/// Photons per bucket one gather dispatch reads on a software device: eight
/// buckets of this stay well inside lavapipe's 65,535 loop iterations (it
/// stops any invocation's loops after that many in all, which a whole
/// gather in a dense caustic exceeds, and silently drops what was left).
pub const SOFTWARE_GATHER_SPAN: u32 = 4096;

/// Bytes of per-pixel data (visible points, sums) one chunk of pixels may use.
const CHUNK_BUDGET: u64 = 1 << 28;

/// Pixels per chunk whose own data takes `bytes_per_pixel` (besides the
/// pixel itself): within one binding for the pixels and for that data, and
/// within [`CHUNK_BUDGET`]; a multiple of 16 so that each chunk's pixel
/// offset meets the storage-offset alignment (256 bytes).
pub(crate) fn pixels_per_chunk(limits: &wgpu::Limits, bytes_per_pixel: f64) -> u64 {
    let align = u64::from(limits.min_storage_buffer_offset_alignment).max(PIXEL_BYTES) / PIXEL_BYTES;
    let binding = limits.max_storage_buffer_binding_size;
    let by_data = match bytes_per_pixel {
        b if b > 0.0 => (binding.min(CHUNK_BUDGET) as f64 / b) as u64,
        _ => u64::MAX,
    };
    ((binding / PIXEL_BYTES).min(by_data) / align * align).max(align)
}

/// (first pixel, pixels) of each chunk of `chunk` pixels over a `total`-pixel image.
pub(crate) fn pixel_chunks(total: u64, chunk: u64) -> impl Iterator<Item = (u64, u64)> {
    (0..total).step_by(chunk as usize).map(move |offset| (offset, chunk.min(total - offset)))
}

/// A pixel buffer for a `width` × `height` image.
pub fn pixel_buffer(ctx: &GpuContext, width: u32, height: u32) -> Result<wgpu::Buffer, BackendError> {
    ctx.checked("allocating the image", || {
        ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("prismatic pixels"),
            size: (u64::from(width) * u64::from(height) * PIXEL_BYTES).max(PIXEL_BYTES),
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        })
    })
}

/// Copies `pixels` into the storage texture `target` (its size must be the image's).
pub fn copy_to_texture(
    ctx: &GpuContext,
    pipelines: &Pipelines,
    scene_buffers: &mut SceneBuffers,
    pixels: &wgpu::Buffer,
    target: &wgpu::Texture,
) -> Result<(), BackendError> {
    let (w, h) = (scene_buffers.params.width, scene_buffers.params.height);
    if (target.width(), target.height()) != (w, h) || !target.usage().contains(wgpu::TextureUsages::STORAGE_BINDING) {
        return Err(BackendError::Device(format!(
            "the target texture is {}x{} with usage {:?}; the image is {w}x{h} and needs STORAGE_BINDING",
            target.width(),
            target.height(),
            target.usage()
        )));
    }
    let format = target.format();
    let (layout, pipeline) = pipelines.texture_copy(&ctx.device, format).ok_or_else(|| {
        BackendError::Device(format!("cannot write {format:?} textures; use Rgba32Float, Rgba16Float or Rgba8Unorm"))
    })?;
    let view = target.create_view(&Default::default());
    let total = u64::from(w) * u64::from(h);
    let chunk = pixels_per_chunk(&ctx.limits(), 0.0);
    for (offset, count) in pixel_chunks(total, chunk) {
        let p = &mut scene_buffers.params;
        (p.pixel_offset, p.pixel_count) = (offset as u32, count as u32);
        scene_buffers.write_params(ctx);
        ctx.checked("copying to the texture", || {
            let group = ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("prismatic to texture"),
                layout: &layout,
                entries: &[
                    wgpu::BindGroupEntry { binding: 0, resource: scene_buffers.params_buffer.as_entire_binding() },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                            buffer: pixels,
                            offset: offset * PIXEL_BYTES,
                            size: wgpu::BufferSize::new(count * PIXEL_BYTES),
                        }),
                    },
                    wgpu::BindGroupEntry { binding: 2, resource: wgpu::BindingResource::TextureView(&view) },
                ],
            });
            let mut encoder = ctx.device.create_command_encoder(&Default::default());
            dispatch(&mut encoder, &pipeline, &[&group], count, WORKGROUP_SIZE);
            ctx.submit(encoder);
        })?;
    }
    Ok(())
}

/// Reads pixels `first..first + out.len()` of a pixel buffer back into `out`.
pub fn read_pixels(ctx: &GpuContext, pixels: &wgpu::Buffer, first: u64, out: &mut [Vec3]) -> Result<(), BackendError> {
    let bytes = ctx.read(pixels, first * PIXEL_BYTES, out.len() as u64 * PIXEL_BYTES)?;
    let rgba: Vec<[f32; 4]> = bytemuck::pod_collect_to_vec(&bytes);
    for (px, v) in out.iter_mut().zip(rgba) {
        *px = Vec3::new(v[0], v[1], v[2]);
    }
    Ok(())
}
