//! The hash grid on the device: twin of `prismatic_core::photons::grid`. Count
//! photons per bucket (atomics), prefix-sum the counts into bucket starts,
//! scatter each photon into its bucket's range of a sorted copy that the
//! gather reads in place; on request, find the widest bucket's size.

use crate::context::GpuContext;
use crate::photons::PhotonArray;
use crate::pipelines::{Pipelines, dispatch};
use crate::scan::Scan;
use crate::scene::SceneBuffers;
use crate::shaders::WORKGROUP_SIZE;
use prismatic_core::BackendError;
use prismatic_core::photons::grid::bucket_mask;

/// A grid over a device map.
pub struct DeviceGrid {
    /// `cells[b]..cells[b + 1]` is bucket b's range of `sorted`.
    pub cells: wgpu::Buffer,
    /// The photons in bucket order.
    pub sorted: PhotonArray,
    /// One u32: the most photons in one bucket, once asked for.
    widest: wgpu::Buffer,
    /// Where the scatter puts each bucket's next photon.
    cursor: wgpu::Buffer,
    /// The build's bindings and its scan of the bucket counts (none for an empty map).
    build: Option<(wgpu::BindGroup, Scan)>,
    /// Photons the grid has room for.
    bound: u32,
}

impl DeviceGrid {
    /// The most photons in one bucket (a pass over the buckets, then a
    /// wait for the device); only devices that gather in segments ask.
    pub fn widest_bucket(&self, ctx: &GpuContext, pipelines: &Pipelines) -> Result<u32, BackendError> {
        let Some((group, _)) = &self.build else { return Ok(0) };
        ctx.checked("finding the widest bucket", || {
            let mut encoder = ctx.device.create_command_encoder(&Default::default());
            let buckets = self.cells.size() / 4 - 1;
            dispatch(&mut encoder, &pipelines.grid_widest, &[group], buckets, WORKGROUP_SIZE);
            ctx.submit(encoder);
        })?;
        let bytes = ctx.read(&self.widest, 0, 4)?;
        Ok(u32::from_le_bytes(bytes[..4].try_into().expect("4 bytes")))
    }
}

impl DeviceGrid {
    /// A grid's buffers for at most `bound` photons of `map`, bucketed as
    /// the core grid buckets `bound` photons.
    pub fn new(
        ctx: &GpuContext,
        pipelines: &Pipelines,
        scene_buffers: &SceneBuffers,
        map: &PhotonArray,
        bound: u32,
    ) -> Result<Self, BackendError> {
        let buckets = u64::from(bucket_mask(bound as usize)) + 1;
        let sorted = PhotonArray::new(ctx, "prismatic sorted photons", bound, map.window)?;
        let (cells, cursor, widest) = ctx.checked("allocating the grid", || {
            let buffer = |label: &str, n: u64| {
                ctx.device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some(label),
                    size: n * 4,
                    usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                })
            };
            (
                buffer("prismatic grid cells", buckets + 1),
                buffer("prismatic grid cursor", buckets),
                buffer("prismatic grid widest bucket", 1),
            )
        })?;
        if bound == 0 {
            return Ok(DeviceGrid { cells, sorted, widest, build: None, bound, cursor });
        }
        let build = ctx.checked("binding the grid", || {
            let mut entries = vec![
                wgpu::BindGroupEntry { binding: 0, resource: scene_buffers.params_buffer.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 1, resource: cells.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 2, resource: cursor.as_entire_binding() },
            ];
            entries.extend(map.entries(3));
            entries.extend(sorted.entries(7));
            entries.push(wgpu::BindGroupEntry { binding: 11, resource: widest.as_entire_binding() });
            let group = ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("prismatic grid"),
                layout: &pipelines.grid_layout,
                entries: &entries,
            });
            (group, Scan::new(ctx, pipelines, &cells, (buckets + 1) as u32))
        })?;
        Ok(DeviceGrid { cells, sorted, widest, build: Some(build), bound, cursor })
    }

    /// Submits a rebuild over the map's first `stored` photons (at most the
    /// bound), with cells for the scene's current `inv_cell`; with `count`,
    /// the photon count is the u32 the device holds there (a photon pass's
    /// cursor) and `stored` only bounds the dispatch.
    pub fn rebuild(
        &self,
        ctx: &GpuContext,
        pipelines: &Pipelines,
        scene_buffers: &mut SceneBuffers,
        stored: u32,
        count: Option<&wgpu::Buffer>,
    ) -> Result<(), BackendError> {
        let Some((group, scan)) = &self.build else { return Ok(()) };
        let stored = stored.min(self.bound);
        let buckets = self.cells.size() / 4 - 1;
        let p = &mut scene_buffers.params;
        (p.stored, p.grid_mask, p.window) = (stored, (buckets - 1) as u32, self.sorted.window);
        scene_buffers.write_params(ctx);
        ctx.checked("building the grid", || {
            let mut encoder = ctx.device.create_command_encoder(&Default::default());
            if let Some(count) = count {
                // The count never leaves the device: it goes into the params the grid reads.
                encoder.copy_buffer_to_buffer(count, 0, &scene_buffers.params_buffer, STORED_OFFSET, 4);
            }
            encoder.clear_buffer(&self.cells, 0, None);
            encoder.clear_buffer(&self.widest, 0, None);
            dispatch(&mut encoder, &pipelines.grid_count, &[group], u64::from(stored), WORKGROUP_SIZE);
            scan.record(pipelines, &mut encoder);
            encoder.copy_buffer_to_buffer(&self.cells, 0, &self.cursor, 0, buckets * 4);
            dispatch(&mut encoder, &pipelines.grid_scatter, &[group], u64::from(stored), WORKGROUP_SIZE);
            ctx.submit(encoder);
        })
    }
}

/// Byte offset of `Params::stored` in the uniform buffer.
const STORED_OFFSET: u64 = std::mem::offset_of!(crate::layout::Params, stored) as u64;

#[cfg(test)]
mod tests {
    use super::*;
    use prismatic_core::photons::grid::{bucket_of, cell_of};
    use prismatic_core::{Photon, util::rng::random_f32};

    /// The device grid's bucket starts and bucket contents equal the core
    /// grid's (its twin), on a cloud dense enough for two scan levels; the
    /// widest bucket is the core grid's.
    #[test]
    fn device_grid_matches_the_core_grid() {
        let Some(ctx) = crate::test_context("the device grid") else { return };
        let pipelines = Pipelines::new(&ctx.device);
        let photons: Vec<Photon> = (0..300_000u32)
            .map(|i| Photon {
                // Half the photons in a uniform cloud, half in one dense spot
                // (a caustic's focus: tens of thousands in a few buckets).
                position: [0, 1, 2].map(|d| (random_f32(9, i, d) * 2.0 - 1.0) * if i % 2 == 0 { 1.0 } else { 0.004 }),
                emission: i,
                band: (i % 7) as u16,
                ..Photon::default()
            })
            .collect();
        let radius = 0.01;
        let mut encoded = crate::scene::EncodedScene::default();
        encoded.params.inv_cell = 1.0 / (2.0 * radius);
        let mut buffers = SceneBuffers::upload(&ctx, &pipelines.scene_layout, &encoded);
        let window = crate::photons::window_for(&ctx.limits());
        let map = PhotonArray::upload(&ctx, &photons, window).unwrap();
        let grid = DeviceGrid::new(&ctx, &pipelines, &buffers, &map, photons.len() as u32).unwrap();
        grid.rebuild(&ctx, &pipelines, &mut buffers, photons.len() as u32, None).unwrap();
        let core = prismatic_core::photons::grid::PhotonGrid::build(&photons, radius);
        let cells = ctx.read(&grid.cells, 0, grid.cells.size()).unwrap();
        let cells: Vec<u32> = bytemuck::pod_collect_to_vec(&cells);
        assert_eq!(cells, core.cell_start);
        let widest = core.cell_start.windows(2).map(|w| w[1] - w[0]).max().unwrap();
        assert_eq!(grid.widest_bucket(&ctx, &pipelines).unwrap(), widest);
        let sorted = grid.sorted.read(&ctx, photons.len() as u32).unwrap();
        let inv = 1.0 / core.cell_size;
        for (b, w) in core.cell_start.windows(2).enumerate() {
            let mut got: Vec<u32> = sorted[w[0] as usize..w[1] as usize].iter().map(|p| p.emission).collect();
            got.sort_unstable();
            assert_eq!(got, core.photon_index[w[0] as usize..w[1] as usize], "bucket {b}");
            for p in &sorted[w[0] as usize..w[1] as usize] {
                assert_eq!(bucket_of(cell_of(p.pos(), inv), core.mask), b as u32);
            }
        }
    }
}
