//! Ray tracing and gather on the device: twin of `prismatic_core::render`.
//! Three passes per chunk of pixels: the view rays (render.wgsl) write
//! each pixel's direct light and leave every diffuse hit that needs the
//! caustic as a visible point; the gather (gather.wgsl) sums the photons
//! around each point, over one or more passes of bucket segments; the
//! resolve adds the points' caustics to their pixels. Pixels go into a
//! storage buffer of `vec4<f32>` (linear RGB, exposure applied, alpha 1); a
//! last pass can copy them into a caller's storage texture.
//!
//! No invocation runs more than one segment of a gather: lavapipe (the
//! software Vulkan driver CI runs on) stops any invocation's loops after
//! 65,535 iterations in all, which a whole gather in a dense caustic
//! exceeds, and silently drops what was left.

use crate::context::GpuContext;
use crate::grid::DeviceGrid;
use crate::layout::VisiblePoint;
use crate::pipelines::{Pipelines, dispatch};
use crate::scene::SceneBuffers;
use crate::shaders::{WORKGROUP_SIZE, stack_size};
use prismatic_core::{BackendError, Image, Vec3};

/// Bytes per pixel of the pixel buffer.
pub const PIXEL_BYTES: u64 = 16;

/// Photons per bucket one gather pass reads on a software device: eight
/// buckets of this stay well inside lavapipe's 65,535 loop iterations.
pub const SOFTWARE_GATHER_SPAN: u32 = 4096;

/// Visible-point slots per pixel before any frame has asked for more.
pub(crate) const FIRST_POINTS_PER_PIXEL: u32 = 16;

/// Bytes of visible points one chunk of pixels may use.
const POINT_BUDGET: u64 = 1 << 28;

pub(crate) const POINT_BYTES: u64 = std::mem::size_of::<VisiblePoint>() as u64;

/// Pixels per chunk with `points_per_pixel` slots each: within one binding
/// for the pixels and for the points, and within [`POINT_BUDGET`]; a
/// multiple of 16 so that each chunk's pixel offset meets the storage-offset
/// alignment (256 bytes).
pub(crate) fn pixels_per_chunk(limits: &wgpu::Limits, points_per_pixel: u32) -> u64 {
    let align = u64::from(limits.min_storage_buffer_offset_alignment).max(PIXEL_BYTES) / PIXEL_BYTES;
    let binding = limits.max_storage_buffer_binding_size;
    let by_points = binding.min(POINT_BUDGET) / (POINT_BYTES * u64::from(points_per_pixel.max(1)));
    ((binding / PIXEL_BYTES).min(by_points) / align * align).max(align)
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
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        })
    })
}

/// The visible points of one chunk and what the gather learnt across
/// frames: slots per pixel grow to what the scene's pixels need and stay.
pub struct Gatherer {
    /// Photons per bucket one gather pass reads (`u32::MAX`: all, one pass).
    pub span: u32,
    points_per_pixel: u32,
    buffers: Option<PointBuffers>,
}

struct PointBuffers {
    /// `points_per_pixel` slots for each pixel of a chunk, slot-major.
    points: wgpu::Buffer,
    /// Visible points each pixel of the chunk wanted.
    counts: wgpu::Buffer,
    /// The most points a pixel wanted, where more than its slots.
    needed: wgpu::Buffer,
}

impl Gatherer {
    /// A gatherer reading `span` photons per bucket and pass.
    pub fn new(span: u32) -> Self {
        Gatherer { span: span.max(1), points_per_pixel: FIRST_POINTS_PER_PIXEL, buffers: None }
    }

    /// Visible-point slots per pixel (what the scenes so far have needed).
    pub fn points_per_pixel(&self) -> u32 {
        self.points_per_pixel
    }

    fn buffers(&mut self, ctx: &GpuContext, chunk: u64) -> Result<&PointBuffers, BackendError> {
        let bytes = chunk * u64::from(self.points_per_pixel) * POINT_BYTES;
        if self.buffers.as_ref().is_none_or(|b| b.points.size() != bytes || b.counts.size() != chunk * 4) {
            let buffers = ctx.checked("allocating visible points", || {
                let buffer = |label: &str, size: u64, usage: wgpu::BufferUsages| {
                    ctx.device.create_buffer(&wgpu::BufferDescriptor {
                        label: Some(label),
                        size,
                        usage: wgpu::BufferUsages::STORAGE | usage,
                        mapped_at_creation: false,
                    })
                };
                let copy = wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST;
                PointBuffers {
                    points: buffer("prismatic visible points", bytes, wgpu::BufferUsages::empty()),
                    counts: buffer("prismatic points per pixel", chunk * 4, wgpu::BufferUsages::empty()),
                    needed: buffer("prismatic points needed", 4, copy),
                }
            })?;
            self.buffers = Some(buffers);
        }
        Ok(self.buffers.as_ref().expect("just made"))
    }
}

/// Renders every pixel into `pixels` (at least width × height × 16 bytes,
/// `STORAGE` usage). Waits for the device once to learn whether every
/// pixel's visible points had a slot, and renders again with more slots
/// when not; on a device with a finite gather span, once more before, to
/// learn the widest bucket.
pub fn render(
    ctx: &GpuContext,
    pipelines: &mut Pipelines,
    scene_buffers: &mut SceneBuffers,
    grid: &DeviceGrid,
    gatherer: &mut Gatherer,
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
    let passes = match (scene_buffers.params.stored, gatherer.span) {
        (0, _) => 0,
        (_, u32::MAX) => 1,
        (_, span) => grid.widest_bucket(ctx, pipelines)?.div_ceil(span).max(1),
    };
    let view = pipelines.render(&ctx.device, stack_size(scene_buffers.params.max_depth)).clone();
    loop {
        let slots = gatherer.points_per_pixel;
        // One chunk's worth of slots, no more than the image needs.
        let chunk = pixels_per_chunk(&ctx.limits(), slots).min(total.max(1).next_multiple_of(16));
        let span = gatherer.span;
        let buffers = gatherer.buffers(ctx, chunk)?;
        for (offset, count) in pixel_chunks(total, chunk) {
            let pixel_slice = wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                buffer: pixels,
                offset: offset * PIXEL_BYTES,
                size: wgpu::BufferSize::new(count * PIXEL_BYTES),
            });
            let (view_group, gather_group) = ctx.checked("binding the render", || {
                let view_group = ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("prismatic render"),
                    layout: &pipelines.render_layout,
                    entries: &[
                        wgpu::BindGroupEntry { binding: 0, resource: pixel_slice.clone() },
                        wgpu::BindGroupEntry { binding: 1, resource: buffers.points.as_entire_binding() },
                        wgpu::BindGroupEntry { binding: 2, resource: buffers.counts.as_entire_binding() },
                        wgpu::BindGroupEntry { binding: 3, resource: buffers.needed.as_entire_binding() },
                    ],
                });
                let mut entries = vec![
                    wgpu::BindGroupEntry { binding: 0, resource: scene_buffers.params_buffer.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 1, resource: scene_buffers.bands().as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 2, resource: grid.cells.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 3, resource: buffers.counts.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 4, resource: buffers.points.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 5, resource: pixel_slice.clone() },
                ];
                entries.extend(grid.sorted.entries(6));
                let gather_group = ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("prismatic gather"),
                    layout: &pipelines.gather_layout,
                    entries: &entries,
                });
                (view_group, gather_group)
            })?;
            let slot_count = count * u64::from(slots);
            // Pass 0 traces the view rays; each pass reads the next segment of every bucket.
            for pass in 0..passes.max(1) {
                let p = &mut scene_buffers.params;
                (p.pixel_offset, p.pixel_count, p.points_per_pixel) = (offset as u32, count as u32, slots);
                (p.gather_first, p.gather_span) = (pass.saturating_mul(span), span);
                scene_buffers.write_params(&ctx.queue);
                ctx.checked("rendering", || {
                    let mut encoder = ctx.device.create_command_encoder(&Default::default());
                    if pass == 0 {
                        dispatch(&mut encoder, &view, &[&scene_buffers.bind_group, &view_group], count, WORKGROUP_SIZE);
                    }
                    if passes > 0 {
                        dispatch(&mut encoder, &pipelines.gather, &[&gather_group], slot_count, WORKGROUP_SIZE);
                    }
                    if passes > 0 && pass + 1 == passes {
                        dispatch(&mut encoder, &pipelines.resolve, &[&gather_group], count, WORKGROUP_SIZE);
                    }
                    ctx.queue.submit([encoder.finish()]);
                })?;
            }
        }
        let bytes = ctx.read(&buffers.needed, 0, 4)?;
        let needed = u32::from_le_bytes(bytes[..4].try_into().expect("4 bytes"));
        if needed <= slots {
            return Ok(());
        }
        // Some pixel had more visible points than slots: again, with enough.
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        encoder.clear_buffer(&buffers.needed, 0, None);
        ctx.queue.submit([encoder.finish()]);
        gatherer.points_per_pixel = needed.next_power_of_two();
    }
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
    let chunk = pixels_per_chunk(&ctx.limits(), 0);
    for (offset, count) in pixel_chunks(total, chunk) {
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
