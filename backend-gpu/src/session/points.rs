//! The visible points on the device, per chunk of pixels (each chunk's
//! buffers fit one binding): the points the view pass appends (each with
//! its pixel and first radius), the pixels' exact sums and direct light,
//! the points listed by grid level with the gathers' indirect dispatch
//! arguments, and the bind groups of the view pass, the gathers (one per
//! built grid level), the session's entries, the dispatch arguments,
//! light tracing and a caustic layer.
//! A chunk's room for points follows what the view passes found, with an
//! eighth to spare.

use super::GpuSession;
use crate::context::GpuContext;
use crate::layout::VisiblePoint;
use crate::pixels::{PIXEL_BYTES, pixel_chunks, pixels_per_chunk};
use crate::readback::PendingRead;
use prismatic_core::BackendError;
use prismatic_core::plan::schedule::GRID_LEVELS;

/// Bytes of a visible point.
pub const POINT_BYTES: u64 = size_of::<VisiblePoint>() as u64;

/// Bytes of a pixel's sums: three i64 (R, G, B).
pub const SUM_BYTES: u64 = 24;

/// Bytes before the level lists' indices: a count and a cursor per level.
pub const LEVEL_HEADER_BYTES: u64 = 8 * GRID_LEVELS as u64;

/// Bytes of one level's indirect dispatch arguments (x, y, z).
pub const LEVEL_ARGS_BYTES: u64 = 12;

/// Room for visible points per pixel before a view pass has counted them.
const FIRST_POINTS_PER_PIXEL: f64 = 2.0;

/// Every chunk's points and what sizes them.
pub struct PointChunks {
    /// Room for visible points per pixel, on average.
    pub per_pixel: f64,
    /// The chunks, in pixel order.
    pub chunks: Vec<PointChunk>,
    /// Every chunk's appended count, copied together after a view pass to
    /// be read back in one piece.
    totals: wgpu::Buffer,
}

/// A chunk of pixels, its visible points and the pixels' sums.
pub struct PointChunk {
    /// First pixel.
    pub offset: u64,
    /// Pixels.
    pub count: u64,
    /// Room for visible points.
    pub capacity: u64,
    /// The visible points, appended by the view pass.
    pub points: wgpu::Buffer,
    /// Two u32 (view.wgsl's `ViewCounts`): points the view pass appended
    /// (past the capacity: counted only), and pixels whose paths the
    /// device cut short.
    pub total: wgpu::Buffer,
    /// Per pixel: Σ over passes and points of weight × caustic, three i64
    /// in 2^32 per unit (`prismatic_core::Accumulation`'s sums).
    pub sums: wgpu::Buffer,
    /// Per pixel: the direct light (the view pass's pixels).
    pub base: wgpu::Buffer,
    /// Per pixel: its first radius with sampled view paths (the complement
    /// of the bits of its fraction of R; 0 before the pilot marks it).
    pub pixel_ratios: wgpu::Buffer,
    /// This pass's points by grid level: per level a count and a cursor,
    /// then the points' indices (session.wgsl's `LevelLists`).
    pub level_lists: wgpu::Buffer,
    /// Per grid level, its gather's indirect dispatch arguments.
    pub level_args: wgpu::Buffer,
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
    /// The dispatch arguments' group 0.
    pub level_dispatch: wgpu::BindGroup,
    /// Light tracing's group 1.
    pub splat: wgpu::BindGroup,
    /// The caustic layer's group 1 (light tracing's and the engine's
    /// frame), when the session has a layer.
    pub layer: Option<wgpu::BindGroup>,
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
    /// No chunks yet, room for [`FIRST_POINTS_PER_PIXEL`] points a pixel.
    pub fn new(ctx: &GpuContext) -> Result<Self, BackendError> {
        let totals = counts_buffer(ctx, 1)?;
        Ok(PointChunks { per_pixel: FIRST_POINTS_PER_PIXEL, chunks: Vec::new(), totals })
    }

    /// Room for points in all chunks.
    pub fn capacity(&self) -> u64 {
        self.chunks.iter().map(|c| c.capacity).sum()
    }

    /// Copies every chunk's count into one buffer and starts reading it back.
    pub fn read_totals(&self, ctx: &GpuContext) -> Result<PendingRead, BackendError> {
        ctx.checked("reading the visible-point counts", || {
            let mut encoder = ctx.device.create_command_encoder(&Default::default());
            for (i, chunk) in self.chunks.iter().enumerate() {
                encoder.copy_buffer_to_buffer(&chunk.total, 0, &self.totals, 4 * i as u64, 4);
            }
            ctx.submit(encoder);
        })?;
        let staging = crate::readback::staging_buffer(&ctx.device, self.totals.size());
        PendingRead::start_in(ctx, &self.totals, staging, 4 * self.chunks.len() as u64, "the visible-point counts")
    }

    /// Whether every chunk had room for the counts `totals` (one per chunk,
    /// as [`PointChunks::read_totals`] reads them); when not, the room per
    /// pixel grows to what the fullest chunk needed and an eighth more.
    pub fn had_room(&mut self, totals: &[u32]) -> bool {
        let mut fits = true;
        for (chunk, &total) in self.chunks.iter().zip(totals) {
            if u64::from(total) > chunk.capacity {
                fits = false;
                self.per_pixel = self.per_pixel.max(f64::from(total) / chunk.count as f64 * 1.125);
            }
        }
        fits
    }
}

/// A storage buffer of `n` u32 counts, readable back.
fn counts_buffer(ctx: &GpuContext, n: u64) -> Result<wgpu::Buffer, BackendError> {
    ctx.checked("allocating visible-point counts", || {
        ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("prismatic visible-point counts"),
            size: (4 * n).max(16),
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        })
    })
}

impl GpuSession {
    /// Allocates the visible points' buffers for the current room per pixel
    /// and binds every chunk.
    pub(super) fn allocate_points(&mut self) -> Result<(), BackendError> {
        let r = &self.scene.scene.render;
        let total = u64::from(r.width) * u64::from(r.height);
        // A layer has no visible points.
        let per_pixel = if self.layer.is_some() { 0.0 } else { self.points.per_pixel };
        let bytes_per_pixel = (POINT_BYTES as f64 * per_pixel).max(SUM_BYTES as f64);
        let chunk = pixels_per_chunk(&self.ctx.limits(), bytes_per_pixel).min(total.max(1).next_multiple_of(16));
        let ctx = &self.ctx;
        let buffer_for = |label: &str, size: u64, usage: wgpu::BufferUsages| {
            ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: size.max(16),
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST | usage,
                mapped_at_creation: false,
            })
        };
        let buffer = |label: &str, size: u64| buffer_for(label, size, wgpu::BufferUsages::COPY_SRC);
        self.points.chunks.clear();
        // Counts of the old chunks on their way back say nothing of the new ones.
        self.pending_totals = None;
        for (offset, count) in pixel_chunks(total, chunk) {
            let capacity = ((count as f64 * per_pixel).ceil() as u64).max(64);
            let chunk = ctx.checked("allocating visible points", || PointChunk {
                offset,
                count,
                capacity,
                points: buffer("prismatic visible points", capacity * POINT_BYTES),
                total: buffer("prismatic visible-point count and cut pixels", 8),
                sums: buffer("prismatic caustic sums", count * SUM_BYTES),
                base: buffer("prismatic direct light", count * PIXEL_BYTES),
                pixel_ratios: buffer("prismatic pixel radii", count * 4),
                level_lists: buffer("prismatic level lists", LEVEL_HEADER_BYTES + 4 * capacity),
                level_args: buffer_for(
                    "prismatic level dispatches",
                    LEVEL_ARGS_BYTES * GRID_LEVELS as u64,
                    wgpu::BufferUsages::INDIRECT,
                ),
                groups: None,
            })?;
            self.points.chunks.push(chunk);
        }
        self.points.totals = counts_buffer(ctx, self.points.chunks.len() as u64)?;
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
                        wgpu::BindGroupEntry { binding: 2, resource: chunk.total.as_entire_binding() },
                        wgpu::BindGroupEntry { binding: 3, resource: chunk.pixel_ratios.as_entire_binding() },
                    ],
                );
                let mut gather: Vec<Option<wgpu::BindGroup>> = vec![None; GRID_LEVELS];
                for (level, grid) in self.levels.iter() {
                    let mut entries = vec![
                        wgpu::BindGroupEntry { binding: 0, resource: self.buffers.params_buffer.as_entire_binding() },
                        wgpu::BindGroupEntry { binding: 1, resource: self.buffers.bands().as_entire_binding() },
                        wgpu::BindGroupEntry { binding: 2, resource: grid.cells.as_entire_binding() },
                        wgpu::BindGroupEntry { binding: 3, resource: chunk.total.as_entire_binding() },
                        wgpu::BindGroupEntry { binding: 4, resource: chunk.points.as_entire_binding() },
                        wgpu::BindGroupEntry { binding: 5, resource: pixel_slice.clone() },
                    ];
                    entries.extend(grid.sorted.entries(6));
                    let scene = self.buffers.surface_buffers();
                    entries.extend(
                        (10..)
                            .zip(scene)
                            .map(|(binding, b)| wgpu::BindGroupEntry { binding, resource: b.as_entire_binding() }),
                    );
                    gather[level] = Some(group("prismatic session gather", &p.gather_layout, &entries));
                }
                let session = group(
                    "prismatic session sums",
                    &p.session_layout,
                    &[
                        wgpu::BindGroupEntry { binding: 0, resource: chunk.sums.as_entire_binding() },
                        wgpu::BindGroupEntry { binding: 1, resource: chunk.base.as_entire_binding() },
                        wgpu::BindGroupEntry { binding: 2, resource: self.session_params.as_entire_binding() },
                        wgpu::BindGroupEntry { binding: 3, resource: self.levels.used.as_entire_binding() },
                        wgpu::BindGroupEntry { binding: 4, resource: self.run_stats.as_entire_binding() },
                        wgpu::BindGroupEntry { binding: 5, resource: chunk.level_lists.as_entire_binding() },
                        wgpu::BindGroupEntry { binding: 6, resource: chunk.pixel_ratios.as_entire_binding() },
                    ],
                );
                let counts = wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                    buffer: &chunk.level_lists,
                    offset: 0,
                    size: wgpu::BufferSize::new(4 * GRID_LEVELS as u64),
                });
                let level_dispatch = group(
                    "prismatic level dispatches",
                    &p.level_dispatch_layout,
                    &[
                        wgpu::BindGroupEntry { binding: 0, resource: counts },
                        wgpu::BindGroupEntry { binding: 1, resource: chunk.level_args.as_entire_binding() },
                    ],
                );
                let mut entries = vec![
                    wgpu::BindGroupEntry { binding: 0, resource: chunk.sums.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 1, resource: self.photons.cursor().as_entire_binding() },
                ];
                entries.extend(self.photons.photons.entries(2));
                let splat = group("prismatic light tracing", &p.splat_layout, &entries);
                let layer = self.layer.as_ref().map(|frame| {
                    entries.push(wgpu::BindGroupEntry { binding: 6, resource: frame.as_entire_binding() });
                    group("prismatic caustic layer", &p.layer_layout, &entries)
                });
                ChunkGroups { view, gather, session, level_dispatch, splat, layer }
            })?;
            chunk.groups = Some(groups);
        }
        Ok(())
    }
}
