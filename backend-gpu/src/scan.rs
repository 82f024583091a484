//! Exclusive prefix sums on the device (the counting sorts' first half):
//! one level per `SCAN_BLOCK`× more elements, recorded into the caller's
//! command encoder so that nothing leaves the device.

use crate::layout::ScanParams;
use crate::pipelines::{Pipelines, dispatch};
use crate::shaders::{SCAN_BLOCK, SCAN_THREADS};
use wgpu::util::DeviceExt;

/// Records an in-place exclusive scan of the first `n` u32s of `data`;
/// returns a buffer whose first u32 will hold their total.
pub fn record(
    device: &wgpu::Device,
    pipelines: &Pipelines,
    encoder: &mut wgpu::CommandEncoder,
    data: &wgpu::Buffer,
    n: u32,
) -> wgpu::Buffer {
    let blocks = n.div_ceil(SCAN_BLOCK).max(1);
    let sums = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("prismatic scan sums"),
        size: u64::from(blocks) * 4,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let params = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("prismatic scan params"),
        contents: bytemuck::bytes_of(&ScanParams { n, ..ScanParams::default() }),
        usage: wgpu::BufferUsages::UNIFORM,
    });
    let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("prismatic scan"),
        layout: &pipelines.scan_layout,
        entries: &[
            wgpu::BindGroupEntry { binding: 0, resource: params.as_entire_binding() },
            wgpu::BindGroupEntry { binding: 1, resource: data.as_entire_binding() },
            wgpu::BindGroupEntry { binding: 2, resource: sums.as_entire_binding() },
        ],
    });
    let threads = u64::from(blocks) * u64::from(SCAN_THREADS);
    dispatch(encoder, &pipelines.scan_blocks, &[&group], threads, SCAN_THREADS);
    if blocks == 1 {
        return sums;
    }
    let total = record(device, pipelines, encoder, &sums, blocks);
    dispatch(encoder, &pipelines.scan_add, &[&group], threads, SCAN_THREADS);
    total
}
