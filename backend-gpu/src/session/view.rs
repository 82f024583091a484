//! A session's view pass (view.wgsl, the twin of `prismatic_core::view`):
//! every chunk's pixels get their direct light (kept as the base) and their
//! visible points. How many points a pixel needs is read back without
//! waiting, except once: the first view pass waits for it and traces again
//! with enough slots.

use super::GpuSession;
use crate::layout::RunStats;
use crate::pipelines::dispatch;
use crate::pixels::PIXEL_BYTES;
use crate::readback::PendingRead;
use crate::shaders::{WORKGROUP_SIZE, stack_size};
use crate::timing::StageTimer;
use prismatic_core::{BackendError, Change};

/// Byte offset of `RunStats::points`.
const POINTS_OFFSET: u64 = std::mem::offset_of!(RunStats, points) as u64;

impl GpuSession {
    /// Traces the view rays of every chunk into its pixels (the direct
    /// light, kept as the base) and visible points, and counts the points
    /// into the statistics. The first time, waits to learn whether every
    /// pixel's points had a slot and traces again with more when not;
    /// later, the check is read back a pass or more afterwards
    /// ([`GpuSession::check_reads`]).
    pub(super) fn trace_view(&mut self) -> Result<(), BackendError> {
        loop {
            let view = self.pipelines.view(&self.ctx.device, stack_size(self.buffers.params.max_depth));
            let caustics = u32::from(self.photons.capacity() > 0);
            for (i, chunk) in self.points.chunks.iter().enumerate() {
                let p = &mut self.buffers.params;
                (p.pixel_offset, p.pixel_count, p.points_per_pixel, p.stored) =
                    (chunk.offset as u32, chunk.count as u32, self.points.slots, caustics);
                self.buffers.write_params(&self.ctx);
                self.ctx.checked("tracing the view rays", || {
                    let mut encoder = self.ctx.device.create_command_encoder(&Default::default());
                    if i == 0 {
                        encoder.clear_buffer(&self.points.needed, 0, None);
                        encoder.clear_buffer(&self.run_stats, POINTS_OFFSET, Some(4));
                    }
                    let groups = [&self.buffers.bind_group, &chunk.groups().view];
                    dispatch(&mut encoder, &view, &groups, chunk.count, WORKGROUP_SIZE);
                    let bytes = chunk.count * PIXEL_BYTES;
                    encoder.copy_buffer_to_buffer(&self.pixels, chunk.offset * PIXEL_BYTES, &chunk.base, 0, bytes);
                    self.ctx.queue.submit([encoder.finish()]);
                })?;
            }
            self.pending_slots = Some(PendingRead::start(&self.ctx, &self.points.needed, "the visible-point count")?);
            if self.slots_learnt {
                return Ok(());
            }
            // The first view pass: wait for the answer, and trace again with enough slots.
            self.ctx.wait()?;
            self.slots_learnt = true;
            self.check_reads()?;
            if self.stale < Change::Size {
                return Ok(());
            }
            self.stale = Change::None;
            self.allocate_points()?;
        }
    }

    /// Looks (without waiting) whether values read back have come: the
    /// last view pass's slot count (when some pixel wanted more slots than
    /// it had, the next pass allocates enough, traces the view again and
    /// starts the sums afresh), the grid levels the first radii need
    /// (built for the next pass) and the stage stamps.
    pub(super) fn check_reads(&mut self) -> Result<(), BackendError> {
        let timing = self.timer.as_ref().is_some_and(StageTimer::reading);
        if self.pending_slots.is_none() && !self.levels.reading() && !timing {
            return Ok(());
        }
        self.ctx
            .device
            .poll(wgpu::PollType::Poll)
            .map_err(|e| BackendError::Device(format!("polling the GPU: {e}")))?;
        if let Some(needed) = self.pending_slots.as_ref().map(PendingRead::value).transpose()?.flatten() {
            self.pending_slots = None;
            if needed > self.points.slots {
                self.points.slots = needed.next_power_of_two();
                self.stale = Change::Size;
                self.passes.clear();
            }
        }
        if self.levels.adopt(&self.ctx, &self.pipelines, &self.buffers, &self.photons)?
            && !self.points.chunks.is_empty()
        {
            self.bind_points()?;
        }
        if let Some(timer) = &mut self.timer {
            timer.check()?;
        }
        Ok(())
    }
}
