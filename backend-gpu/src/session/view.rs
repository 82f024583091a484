//! A session's view pass (view.wgsl, the twin of `prismatic_core::render::view`):
//! every chunk's pixels get their direct light (kept as the base) and their
//! visible points, appended to the chunk's array. How many points each
//! chunk appended is read back without waiting, except once: the first
//! view pass waits for the counts and traces again where a chunk lacked room.

use super::GpuSession;
use crate::pipelines::dispatch;
use crate::pixels::PIXEL_BYTES;
use crate::shaders::{WORKGROUP_SIZE, stack_size};
use crate::timing::StageTimer;
use prismatic_core::{BackendError, Change};

impl GpuSession {
    /// Traces the view rays of every chunk into its pixels (the direct
    /// light, kept as the base) and visible points (pass `pass`'s sampled
    /// paths with sampled view paths). The first time, waits
    /// to learn whether every chunk had room for its points and traces
    /// again with more when not; later, the counts are read back a pass or
    /// more afterwards ([`GpuSession::check_reads`]).
    pub(super) fn trace_view(&mut self, pass: u32) -> Result<(), BackendError> {
        self.buffers.params.view_pass = pass;
        loop {
            let view = self.pipelines.view(&self.ctx.device, stack_size(self.buffers.params.max_depth));
            let caustics = u32::from(self.photons.capacity() > 0);
            for chunk in &self.points.chunks {
                let p = &mut self.buffers.params;
                (p.pixel_offset, p.pixel_count, p.point_capacity, p.stored) =
                    (chunk.offset as u32, chunk.count as u32, chunk.capacity as u32, caustics);
                self.buffers.write_params(&self.ctx);
                self.ctx.checked("tracing the view rays", || {
                    let mut encoder = self.ctx.device.create_command_encoder(&Default::default());
                    encoder.clear_buffer(&chunk.total, 0, None);
                    let groups = [&self.buffers.bind_group, &chunk.groups().view];
                    dispatch(&mut encoder, &view, &groups, chunk.count, WORKGROUP_SIZE);
                    let bytes = chunk.count * PIXEL_BYTES;
                    encoder.copy_buffer_to_buffer(&self.pixels, chunk.offset * PIXEL_BYTES, &chunk.base, 0, bytes);
                    self.ctx.submit(encoder);
                })?;
            }
            self.pending_totals = Some(self.points.read_totals(&self.ctx)?);
            if self.room_learnt {
                return Ok(());
            }
            // The first view pass: wait for the counts, and trace again with room.
            if let Some(totals) = &self.pending_totals {
                totals.wait(&self.ctx)?;
            }
            self.room_learnt = true;
            self.check_reads()?;
            if self.stale < Change::Size {
                return Ok(());
            }
            self.stale = Change::None;
            self.allocate_points()?;
        }
    }

    /// With sampled view paths, after a pass's view: its direct light
    /// added to the pixels' sums and the base emptied (every pass's view is
    /// in its sums, none is shared).
    pub(super) fn add_view(&mut self) -> Result<(), BackendError> {
        for chunk in &self.points.chunks {
            let p = &mut self.buffers.params;
            (p.pixel_offset, p.pixel_count) = (chunk.offset as u32, chunk.count as u32);
            self.buffers.write_params(&self.ctx);
            self.ctx.checked("adding the view to the sums", || {
                let mut encoder = self.ctx.device.create_command_encoder(&Default::default());
                let groups = [chunk.groups().gather(0), &chunk.groups().session];
                dispatch(&mut encoder, &self.pipelines.add_view, &groups, chunk.count, WORKGROUP_SIZE);
                encoder.clear_buffer(&chunk.base, 0, None);
                self.ctx.submit(encoder);
            })?;
        }
        Ok(())
    }

    /// Looks (without waiting) whether values read back have come: the
    /// last view pass's point counts (where a chunk lacked room, the next
    /// pass allocates more, traces the view again and starts the sums
    /// afresh), the grid levels the first radii need (built for the next
    /// pass) and the stage stamps.
    pub(super) fn check_reads(&mut self) -> Result<(), BackendError> {
        let timing = self.timer.as_ref().is_some_and(StageTimer::reading);
        if self.pending_totals.is_none() && !self.levels.reading() && !timing {
            return Ok(());
        }
        self.ctx
            .device
            .poll(wgpu::PollType::Poll)
            .map_err(|e| BackendError::Device(format!("polling the GPU: {e}")))?;
        if let Some(bytes) = self.pending_totals.as_ref().map(|p| p.bytes()).transpose()?.flatten() {
            self.pending_totals = None;
            let totals: Vec<u32> = bytemuck::pod_collect_to_vec(&bytes);
            if !self.points.had_room(&totals) {
                self.stale = Change::Size;
                self.passes.clear();
            }
        }
        self.adopt_levels()?;
        if let Some(timer) = &mut self.timer {
            timer.check()?;
        }
        Ok(())
    }

    /// Builds the grid levels the pilot's mark names once it has come back
    /// (binding the points again when the set changed).
    pub(super) fn adopt_levels(&mut self) -> Result<(), BackendError> {
        if self.levels.adopt(&self.ctx, &self.pipelines, &self.buffers, &self.photons)?
            && !self.points.chunks.is_empty()
        {
            self.bind_points()?;
        }
        Ok(())
    }
}
