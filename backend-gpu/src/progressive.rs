//! A progressive pass on the device: twin of `prismatic_core::progressive::
//! gather_pass`. The pass's photons are traced on the device, gridded once
//! per grid level the points need, and gathered at the caller's visible
//! points (uploaded sorted by level, each with its own radius) by
//! gather.wgsl's `gather_points`, in bucket segments on software devices;
//! the points' sums are read back and the estimate finished on the host in
//! f64, where the core accumulates them.

use crate::context::GpuContext;
use crate::grid;
use crate::layout;
use crate::levels;
use crate::pipelines::{Pipelines, dispatch};
use crate::scene::SceneBuffers;
use crate::shaders::WORKGROUP_SIZE;
use crate::trace::DeviceMap;
use prismatic_core::progressive::{GRID_LEVELS, level_of, levels_used};
use prismatic_core::scene::Estimator;
use prismatic_core::visible::VisiblePoint;
use prismatic_core::{BackendError, PreparedScene, Vec3};
use wgpu::util::DeviceExt;

const POINT_BYTES: u64 = std::mem::size_of::<layout::VisiblePoint>() as u64;

/// Gathers the traced `map` at `points` (radii `radii`): per point the
/// caustic irradiance and the photons accepted.
#[expect(clippy::too_many_arguments, reason = "the device's state, the scene's buffers and the pass's inputs")]
pub fn gather_pass(
    ctx: &GpuContext,
    pipelines: &Pipelines,
    buffers: &mut SceneBuffers,
    map: &DeviceMap,
    span: u32,
    scene: &PreparedScene,
    points: &[VisiblePoint],
    radii: &[f32],
) -> Result<(Vec<Vec3>, Vec<u32>), BackendError> {
    let n = points.len();
    let mut irradiance = vec![Vec3::ZERO; n];
    let mut found = vec![0u32; n];
    if n == 0 || map.stored == 0 {
        return Ok((irradiance, found));
    }
    let r_pass = scene.scene.render.radius;
    let used = levels_used(radii, r_pass);
    // Every level's grid first (they share the photons; the gathers bind one at a time).
    let mut grids = Vec::with_capacity(GRID_LEVELS);
    for (level, &needed) in used.iter().enumerate() {
        grids.push(if needed {
            buffers.params.inv_cell = levels::inv_cell(r_pass, level);
            let g = grid::build(ctx, pipelines, buffers, map)?;
            let segments = if span == u32::MAX { 1 } else { g.widest_bucket(ctx, pipelines)?.div_ceil(span).max(1) };
            Some((g, segments))
        } else {
            None
        });
    }
    let small = |label: &str| {
        ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size: 16,
            usage: wgpu::BufferUsages::STORAGE,
            mapped_at_creation: false,
        })
    };
    let (no_counts, no_pixels) =
        ctx.checked("allocating the pass", || (small("unused counts"), small("unused pixels")))?;
    let chunk = (ctx.limits().max_storage_buffer_binding_size.min(1 << 28) / POINT_BYTES) as usize;
    let bands = scene.bands.len() as f64;
    for start in (0..n).step_by(chunk) {
        let end = (start + chunk).min(n);
        // This chunk's points grouped by level (stable), so each level is one range.
        let mut by_level: [Vec<usize>; GRID_LEVELS] = Default::default();
        for i in start..end {
            by_level[level_of(radii[i], r_pass)].push(i);
        }
        let counts = by_level.each_ref().map(Vec::len);
        let order = by_level.concat();
        let uploaded: Vec<layout::VisiblePoint> = order
            .iter()
            .map(|&i| layout::VisiblePoint {
                position: points[i].point.to_array(),
                normal: points[i].normal.to_array(),
                radius: radii[i],
                ..Default::default()
            })
            .collect();
        let device_points = ctx.checked("uploading visible points", || {
            ctx.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("prismatic pass points"),
                contents: bytemuck::cast_slice(&uploaded),
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            })
        })?;
        let mut first = 0;
        for ((level, grid), count) in grids.iter().enumerate().zip(counts) {
            let Some((grid, segments)) = grid.as_ref().filter(|_| count > 0) else {
                first += count;
                continue;
            };
            let group = ctx.checked("binding the pass", || {
                let mut entries = vec![
                    wgpu::BindGroupEntry { binding: 0, resource: buffers.params_buffer.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 1, resource: buffers.bands().as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 2, resource: grid.cells.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 3, resource: no_counts.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 4, resource: device_points.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 5, resource: no_pixels.as_entire_binding() },
                ];
                entries.extend(grid.sorted.entries(6));
                ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("prismatic pass gather"),
                    layout: &pipelines.gather_layout,
                    entries: &entries,
                })
            })?;
            for segment in 0..*segments {
                let p = &mut buffers.params;
                p.inv_cell = levels::inv_cell(r_pass, level);
                (p.pixel_offset, p.pixel_count) = (first as u32, count as u32);
                (p.gather_first, p.gather_span) = (segment.saturating_mul(span), span);
                buffers.write_params(&ctx.queue);
                ctx.checked("gathering the pass", || {
                    let mut encoder = ctx.device.create_command_encoder(&Default::default());
                    dispatch(&mut encoder, &pipelines.gather_points, &[&group], count as u64, WORKGROUP_SIZE);
                    ctx.queue.submit([encoder.finish()]);
                })?;
            }
            first += count;
        }
        let bytes = ctx.read(&device_points, 0, uploaded.len() as u64 * POINT_BYTES)?;
        let gathered: Vec<layout::VisiblePoint> = bytemuck::pod_collect_to_vec(&bytes);
        for (&i, vp) in order.iter().zip(&gathered) {
            irradiance[i] = estimate(vp, scene.scene.render.estimator, bands);
            found[i] = vp.found;
        }
    }
    Ok((irradiance, found))
}

/// The estimate from a point's sums (gather.wgsl's `caustic`, in f64).
fn estimate(vp: &layout::VisiblePoint, estimator: Estimator, bands: f64) -> Vec3 {
    let area = std::f64::consts::PI * f64::from(vp.radius) * f64::from(vp.radius);
    let sums = glam::DVec3::from_array(vp.sums.map(f64::from));
    match estimator {
        Estimator::Density => (sums / area).as_vec3(),
        Estimator::Paper if vp.total == 0 => Vec3::ZERO,
        Estimator::Paper => (sums * (bands / f64::from(vp.total)) * (f64::from(vp.flux) / area)).as_vec3(),
    }
}
