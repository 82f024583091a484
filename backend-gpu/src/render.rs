//! Ray tracing and gather on the device: twin of `prismatic_core::render`.
//! Pixels go into a storage buffer of `vec4<f32>` (linear RGB, exposure
//! applied, alpha 1), in chunks of rows when the image is larger than one
//! binding; a second pass can copy them into a caller's storage texture.

use crate::context::GpuContext;
use crate::grid::DeviceGrid;
use crate::pipelines::{Pipelines, dispatch};
use crate::scene::SceneBuffers;
use crate::shaders::{WORKGROUP_SIZE, stack_size};
use prismatic_core::{BackendError, Image, Vec3};

/// Bytes per pixel of the pixel buffer.
pub const PIXEL_BYTES: u64 = 16;

/// Pixels per render dispatch: one binding's worth, a multiple of 16 so
/// that each chunk's offset meets the storage-offset alignment (256 bytes).
fn pixels_per_chunk(limits: &wgpu::Limits) -> u64 {
    let align = u64::from(limits.min_storage_buffer_offset_alignment).max(PIXEL_BYTES);
    (limits.max_storage_buffer_binding_size / PIXEL_BYTES) / (align / PIXEL_BYTES) * (align / PIXEL_BYTES)
}

/// (first pixel, pixels) of each dispatch over a `total`-pixel image.
fn pixel_chunks(total: u64, limits: &wgpu::Limits) -> impl Iterator<Item = (u64, u64)> {
    let chunk = pixels_per_chunk(limits);
    (0..total).step_by(chunk as usize).map(move |offset| (offset, chunk.min(total - offset)))
}

/// A pixel buffer for a `width` × `height` image.
pub fn pixel_buffer(ctx: &GpuContext, width: u32, height: u32) -> Result<wgpu::Buffer, BackendError> {
    ctx.checked("allocating the image", || {
        ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("prismatic pixels"),
            size: (u64::from(width) * u64::from(height) * PIXEL_BYTES).max(PIXEL_BYTES),
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        })
    })
}

/// Renders every pixel into `pixels` (at least width × height × 16 bytes, `STORAGE` usage).
pub fn render(
    ctx: &GpuContext,
    pipelines: &mut Pipelines,
    scene_buffers: &mut SceneBuffers,
    grid: &DeviceGrid,
    pixels: &wgpu::Buffer,
) -> Result<(), BackendError> {
    let (w, h) = (scene_buffers.params.width, scene_buffers.params.height);
    let total = u64::from(w) * u64::from(h);
    if pixels.size() < total * PIXEL_BYTES {
        return Err(BackendError::Device(format!(
            "the pixel buffer has {} bytes; a {w}x{h} image needs {}",
            pixels.size(),
            total * PIXEL_BYTES
        )));
    }
    let pipeline = pipelines.render(&ctx.device, stack_size(scene_buffers.params.max_depth)).clone();
    for (offset, count) in pixel_chunks(total, &ctx.limits()) {
        let p = &mut scene_buffers.params;
        (p.pixel_offset, p.pixel_count) = (offset as u32, count as u32);
        scene_buffers.write_params(&ctx.queue);
        ctx.checked("rendering", || {
            let mut entries = vec![
                wgpu::BindGroupEntry { binding: 0, resource: grid.cells.as_entire_binding() },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                        buffer: pixels,
                        offset: offset * PIXEL_BYTES,
                        size: wgpu::BufferSize::new(count * PIXEL_BYTES),
                    }),
                },
            ];
            entries.extend(grid.sorted.entries(2));
            let group = ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("prismatic render"),
                layout: &pipelines.render_layout,
                entries: &entries,
            });
            let mut encoder = ctx.device.create_command_encoder(&Default::default());
            dispatch(&mut encoder, &pipeline, &[&scene_buffers.bind_group, &group], count, WORKGROUP_SIZE);
            ctx.queue.submit([encoder.finish()]);
        })?;
    }
    Ok(())
}

/// Copies `pixels` into the storage texture `target` (its size must be the image's).
pub fn copy_to_texture(
    ctx: &GpuContext,
    pipelines: &mut Pipelines,
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
    let (layout, pipeline) = pipelines.texture_copy(&ctx.device, format).cloned().ok_or_else(|| {
        BackendError::Device(format!("cannot write {format:?} textures; use Rgba32Float, Rgba16Float or Rgba8Unorm"))
    })?;
    let view = target.create_view(&Default::default());
    let total = u64::from(w) * u64::from(h);
    for (offset, count) in pixel_chunks(total, &ctx.limits()) {
        let p = &mut scene_buffers.params;
        (p.pixel_offset, p.pixel_count) = (offset as u32, count as u32);
        scene_buffers.write_params(&ctx.queue);
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
            ctx.queue.submit([encoder.finish()]);
        })?;
    }
    Ok(())
}

/// Reads a rendered pixel buffer back as an image.
pub fn read_image(ctx: &GpuContext, pixels: &wgpu::Buffer, width: u32, height: u32) -> Result<Image, BackendError> {
    let n = u64::from(width) * u64::from(height);
    let bytes = ctx.read(pixels, 0, n * PIXEL_BYTES)?;
    let rgba: Vec<[f32; 4]> = bytemuck::pod_collect_to_vec(&bytes);
    let mut image = Image::new(width, height);
    for (px, v) in image.pixels.iter_mut().zip(rgba) {
        *px = Vec3::new(v[0], v[1], v[2]);
    }
    Ok(image)
}
