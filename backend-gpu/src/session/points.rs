//! The visible points on the device: per chunk of pixels (each chunk's
//! buffers fit one binding), `slots` points per pixel, their first radii,
//! the pixels' exact sums and direct light, and the bind groups of the view
//! pass, the gathers (one per built grid level) and the session's entries.

use super::GpuSession;
use crate::context::GpuContext;
use crate::pixels::{FIRST_POINTS_PER_PIXEL, PIXEL_BYTES, POINT_BYTES, pixel_chunks, pixels_per_chunk};
use prismatic_core::BackendError;
use prismatic_core::schedule::GRID_LEVELS;

/// Bytes of a pixel's sums: three i64 (R, G, B).
pub const SUM_BYTES: u64 = 24;

/// Every chunk's points and what sizes them.
pub struct PointChunks {
    /// Visible-point slots per pixel.
    pub slots: u32,
    /// The most visible points a pixel wanted, where more than its slots.
    pub needed: wgpu::Buffer,
    /// The chunks, in pixel order.
    pub chunks: Vec<PointChunk>,
}

/// A chunk of pixels' visible points, their first radii and the pixels' sums.
pub struct PointChunk {
    /// First pixel.
    pub offset: u64,
    /// Pixels.
    pub count: u64,
    /// `slots` visible points per pixel, slot-major.
    pub points: wgpu::Buffer,
    /// Per pixel: visible points it wanted.
    pub counts: wgpu::Buffer,
    /// Per slot: the first radius as a fraction of the scene's.
    pub ratio: wgpu::Buffer,
    /// Per pixel: Σ over passes and points of weight × caustic, three i64
    /// in 2^32 per unit (`prismatic_core::Accumulation`'s sums).
    pub sums: wgpu::Buffer,
    /// Per pixel: the direct light (the view pass's pixels).
    pub base: wgpu::Buffer,
    groups: Option<ChunkGroups>,
}

/// A chunk's bind groups.
pub struct ChunkGroups {
    /// The view pass's group 1.
    pub view: wgpu::BindGroup,
    /// Per built grid level (by level), the gather's group 0.
    gather: Vec<Option<wgpu::BindGroup>>,
    /// The session entries' group 1.
    pub session: wgpu::BindGroup,
}

impl ChunkGroups {
    /// The gather's bindings with level `level`'s grid.
    pub fn gather(&self, level: usize) -> &wgpu::BindGroup {
        self.gather[level].as_ref().expect("bound for every built level")
    }
}

impl PointChunk {
    /// The chunk's bind groups.
    pub fn groups(&self) -> &ChunkGroups {
        self.groups.as_ref().expect("bound when allocated")
    }
}

impl PointChunks {
    /// No chunks yet, [`FIRST_POINTS_PER_PIXEL`] slots.
    pub fn new(ctx: &GpuContext) -> Result<Self, BackendError> {
        let needed = ctx.checked("allocating the session", || {
            ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("prismatic points needed"),
                size: 16,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        })?;
        Ok(PointChunks { slots: FIRST_POINTS_PER_PIXEL, needed, chunks: Vec::new() })
    }
}

impl GpuSession {
    /// Allocates the visible points' buffers for the current slots and
    /// binds every chunk.
    pub(super) fn allocate_points(&mut self) -> Result<(), BackendError> {
        let r = &self.scene.scene.render;
        let total = u64::from(r.width) * u64::from(r.height);
        let slots = self.points.slots;
        let chunk = pixels_per_chunk(&self.ctx.limits(), slots).min(total.max(1).next_multiple_of(16));
        let ctx = &self.ctx;
        let buffer = |label: &str, size: u64| {
            ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: size.max(16),
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            })
        };
        self.points.chunks.clear();
        for (offset, count) in pixel_chunks(total, chunk) {
            let points = count * u64::from(slots);
            let chunk = ctx.checked("allocating visible points", || PointChunk {
                offset,
                count,
                points: buffer("prismatic visible points", points * POINT_BYTES),
                counts: buffer("prismatic points per pixel", count * 4),
                ratio: buffer("prismatic radius ratios", points * 4),
                sums: buffer("prismatic caustic sums", count * SUM_BYTES),
                base: buffer("prismatic direct light", count * PIXEL_BYTES),
                groups: None,
            })?;
            self.points.chunks.push(chunk);
        }
        self.bind_points()
    }

    /// Binds every chunk to the current pixels, scene, grids and photons
    /// (again after an update moved one of them; the points stay).
    pub(super) fn bind_points(&mut self) -> Result<(), BackendError> {
        let (ctx, p) = (&self.ctx, &self.pipelines);
        for chunk in &mut self.points.chunks {
            let pixel_slice = wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                buffer: &self.pixels,
                offset: chunk.offset * PIXEL_BYTES,
                size: wgpu::BufferSize::new(chunk.count * PIXEL_BYTES),
            });
            let groups = ctx.checked("binding the session", || {
                let group = |label: &str, layout: &wgpu::BindGroupLayout, entries: &[wgpu::BindGroupEntry]| {
                    ctx.device.create_bind_group(&wgpu::BindGroupDescriptor { label: Some(label), layout, entries })
                };
                let view = group(
                    "prismatic session view",
                    &p.view_layout,
                    &[
                        wgpu::BindGroupEntry { binding: 0, resource: pixel_slice.clone() },
                        wgpu::BindGroupEntry { binding: 1, resource: chunk.points.as_entire_binding() },
                        wgpu::BindGroupEntry { binding: 2, resource: chunk.counts.as_entire_binding() },
                        wgpu::BindGroupEntry { binding: 3, resource: self.points.needed.as_entire_binding() },
                        wgpu::BindGroupEntry { binding: 4, resource: self.run_stats.as_entire_binding() },
                    ],
                );
                let mut gather: Vec<Option<wgpu::BindGroup>> = vec![None; GRID_LEVELS];
                for (level, grid) in self.levels.iter() {
                    let mut entries = vec![
                        wgpu::BindGroupEntry { binding: 0, resource: self.buffers.params_buffer.as_entire_binding() },
                        wgpu::BindGroupEntry { binding: 1, resource: self.buffers.bands().as_entire_binding() },
                        wgpu::BindGroupEntry { binding: 2, resource: grid.cells.as_entire_binding() },
                        wgpu::BindGroupEntry { binding: 3, resource: chunk.counts.as_entire_binding() },
                        wgpu::BindGroupEntry { binding: 4, resource: chunk.points.as_entire_binding() },
                        wgpu::BindGroupEntry { binding: 5, resource: pixel_slice.clone() },
                    ];
                    entries.extend(grid.sorted.entries(6));
                    gather[level] = Some(group("prismatic session gather", &p.gather_layout, &entries));
                }
                let session = group(
                    "prismatic session sums",
                    &p.session_layout,
                    &[
                        wgpu::BindGroupEntry { binding: 0, resource: chunk.ratio.as_entire_binding() },
                        wgpu::BindGroupEntry { binding: 1, resource: chunk.sums.as_entire_binding() },
                        wgpu::BindGroupEntry { binding: 2, resource: chunk.base.as_entire_binding() },
                        wgpu::BindGroupEntry { binding: 3, resource: self.session_params.as_entire_binding() },
                        wgpu::BindGroupEntry { binding: 4, resource: self.levels.used.as_entire_binding() },
                        wgpu::BindGroupEntry { binding: 5, resource: self.run_stats.as_entire_binding() },
                    ],
                );
                ChunkGroups { view, gather, session }
            })?;
            chunk.groups = Some(groups);
        }
        Ok(())
    }
}
