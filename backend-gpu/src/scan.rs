//! Exclusive prefix sums on the device (the counting sorts' first half):
//! one level per `SCAN_BLOCK`× more elements, recorded into the caller's
//! command encoder so that nothing leaves the device. A [`Scan`] makes its
//! scratch buffers and bindings once; a grid keeps its own and records it
//! every rebuild.

use crate::context::GpuContext;
use crate::layout::ScanParams;
use crate::pipelines::{Pipelines, dispatch};
use crate::shaders::{SCAN_BLOCK, SCAN_THREADS};

/// An in-place exclusive scan of the first `n` u32s of one buffer.
pub struct Scan {
    /// Per level, finest first: its bindings (params, data, block sums)
    /// and the threads it dispatches.
    levels: Vec<(wgpu::BindGroup, u64)>,
    /// The coarsest level's block sums: its first u32 is the total.
    total: wgpu::Buffer,
}

impl Scan {
    /// The scan of the first `n` u32s of `data`, its scratch allocated.
    pub fn new(ctx: &GpuContext, pipelines: &Pipelines, data: &wgpu::Buffer, n: u32) -> Self {
        let device = &ctx.device;
        let mut levels = Vec::new();
        let (mut data, mut n) = (data.clone(), n);
        loop {
            let blocks = n.div_ceil(SCAN_BLOCK).max(1);
            let sums = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("prismatic scan sums"),
                size: u64::from(blocks) * 4,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            });
            let params = ctx.buffer_with(
                "prismatic scan params",
                bytemuck::bytes_of(&ScanParams { n, ..ScanParams::default() }),
                wgpu::BufferUsages::UNIFORM,
            );
            let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("prismatic scan"),
                layout: &pipelines.scan_layout,
                entries: &[
                    wgpu::BindGroupEntry { binding: 0, resource: params.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 1, resource: data.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 2, resource: sums.as_entire_binding() },
                ],
            });
            levels.push((group, u64::from(blocks) * u64::from(SCAN_THREADS)));
            if blocks == 1 {
                return Scan { levels, total: sums };
            }
            (data, n) = (sums, blocks);
        }
    }

    /// Records the scan: each level's blocks scanned, finest first, then
    /// each coarser level's offsets added back into the level below it.
    pub fn record(&self, pipelines: &Pipelines, encoder: &mut wgpu::CommandEncoder) {
        for (group, threads) in &self.levels {
            dispatch(encoder, &pipelines.scan_blocks, &[group], *threads, SCAN_THREADS);
        }
        for (group, threads) in self.levels.iter().rev().skip(1) {
            dispatch(encoder, &pipelines.scan_add, &[group], *threads, SCAN_THREADS);
        }
    }

    /// A buffer whose first u32 holds the total once the scan has run.
    pub fn total(&self) -> &wgpu::Buffer {
        &self.total
    }
}
