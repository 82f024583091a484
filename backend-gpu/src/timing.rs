//! GPU timestamps between a session pass's stages, where the device has
//! them (`TIMESTAMP_QUERY` and `TIMESTAMP_QUERY_INSIDE_ENCODERS`): each
//! stamp is written in queue order after the stage's submissions, the
//! stamps are resolved on the device and read back without waiting, a
//! frame or more later. A frame whose stamps would overlap a read still
//! on its way is not timed.

use crate::context::{GpuContext, timestamp_features};
use crate::readback::{PendingRead, staging_buffer};
use prismatic_core::{BackendError, Stage, StageTimes};
use std::time::Duration;

/// Stamps a frame writes at most: its start, the view, and photons, grid
/// and gather for the pilot pass and the pass.
const MAX_STAMPS: u32 = 8;

/// A session's timestamp queries and the last frame's times that came back.
pub struct StageTimer {
    queries: wgpu::QuerySet,
    resolved: wgpu::Buffer,
    /// Where the resolved stamps are read back (one read at a time).
    staging: wgpu::Buffer,
    /// Nanoseconds per timestamp tick.
    period: f64,
    /// The stage that ended at each stamp after the first, this frame.
    stages: Vec<Stage>,
    /// Whether this frame writes stamps.
    timing: bool,
    pending: Option<(PendingRead, Vec<Stage>)>,
    last: Option<StageTimes>,
}

impl StageTimer {
    /// A timer on `ctx`'s device; `None` when the device lacks timestamps.
    pub fn new(ctx: &GpuContext) -> Result<Option<Self>, BackendError> {
        if !ctx.device.features().contains(timestamp_features()) {
            return Ok(None);
        }
        let (queries, resolved, staging) = ctx.checked("allocating the stage stamps", || {
            let queries = ctx.device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("prismatic stage stamps"),
                ty: wgpu::QueryType::Timestamp,
                count: MAX_STAMPS,
            });
            let resolved = ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("prismatic stage stamps resolved"),
                size: u64::from(MAX_STAMPS) * 8,
                usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            });
            (queries, resolved, staging_buffer(&ctx.device, u64::from(MAX_STAMPS) * 8))
        })?;
        let period = f64::from(ctx.queue.get_timestamp_period());
        Ok(Some(StageTimer {
            queries,
            resolved,
            staging,
            period,
            stages: Vec::new(),
            timing: false,
            pending: None,
            last: None,
        }))
    }

    /// Starts a frame: its first stamp, unless the last timed frame's
    /// stamps are still on their way back.
    pub fn begin(&mut self, ctx: &GpuContext) -> Result<(), BackendError> {
        self.stages.clear();
        self.timing = self.pending.is_none();
        if self.timing { self.write(ctx, 0) } else { Ok(()) }
    }

    /// Starts a frame that writes no stamps (one recorded for an engine to
    /// submit: its stamps would land out of order).
    pub fn skip(&mut self) {
        self.stages.clear();
        self.timing = false;
    }

    /// Stamps the end of `stage`: the time since the last stamp is its.
    pub fn end(&mut self, ctx: &GpuContext, stage: Stage) -> Result<(), BackendError> {
        let index = self.stages.len() as u32 + 1;
        if !self.timing || index >= MAX_STAMPS {
            return Ok(());
        }
        self.stages.push(stage);
        self.write(ctx, index)
    }

    /// Ends the frame: resolves its stamps and starts reading them back.
    pub fn finish(&mut self, ctx: &GpuContext) -> Result<(), BackendError> {
        if !self.timing || self.stages.is_empty() {
            return Ok(());
        }
        let stamps = self.stages.len() as u32 + 1;
        ctx.checked("resolving the stage stamps", || {
            let mut encoder = ctx.device.create_command_encoder(&Default::default());
            encoder.resolve_query_set(&self.queries, 0..stamps, &self.resolved, 0);
            ctx.queue.submit([encoder.finish()]);
        })?;
        let size = u64::from(stamps) * 8;
        let read = PendingRead::start_in(ctx, &self.resolved, self.staging.clone(), size, "the stage stamps")?;
        self.pending = Some((read, std::mem::take(&mut self.stages)));
        Ok(())
    }

    /// Takes the stamps if they have come (the caller has polled the device).
    pub fn check(&mut self) -> Result<(), BackendError> {
        let Some((read, stages)) = &self.pending else { return Ok(()) };
        let Some(bytes) = read.bytes()? else { return Ok(()) };
        let ticks: Vec<u64> = bytemuck::pod_collect_to_vec(&bytes);
        self.last = Some(stage_times(&ticks, stages, self.period));
        self.pending = None;
        Ok(())
    }

    /// Whether stamps are on their way back.
    pub fn reading(&self) -> bool {
        self.pending.is_some()
    }

    /// The last timed frame's stage times that came back.
    pub fn last(&self) -> Option<StageTimes> {
        self.last
    }
}

impl StageTimer {
    /// Writes stamp `index` after everything submitted so far.
    fn write(&self, ctx: &GpuContext, index: u32) -> Result<(), BackendError> {
        ctx.checked("writing a stage stamp", || {
            let mut encoder = ctx.device.create_command_encoder(&Default::default());
            encoder.write_timestamp(&self.queries, index);
            ctx.queue.submit([encoder.finish()]);
        })
    }
}

/// Stage times from `ticks` (the frame's stamps in order; stamp i + 1
/// ends `stages[i]`) at `period` nanoseconds a tick. A stamp earlier than
/// the one before it (a counter that wrapped or was reset) counts zero.
fn stage_times(ticks: &[u64], stages: &[Stage], period: f64) -> StageTimes {
    let span = |a: u64, b: u64| Duration::from_nanos((b.saturating_sub(a) as f64 * period) as u64);
    let mut times = StageTimes::default();
    for (pair, stage) in ticks.windows(2).zip(stages) {
        times.add(*stage, span(pair[0], pair[1]));
    }
    times
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stages_take_the_time_since_the_stamp_before_them_and_repeated_stages_add_up() {
        let stages = [Stage::Photons, Stage::Grid, Stage::Gather, Stage::Photons, Stage::Grid, Stage::Gather];
        let ticks = [100, 150, 160, 400, 450, 470, 1000];
        let t = stage_times(&ticks, &stages, 2.0);
        let ns = Duration::from_nanos;
        assert_eq!(t.photons, ns(2 * (50 + 50)));
        assert_eq!(t.grid, ns(2 * (10 + 20)));
        assert_eq!(t.gather, ns(2 * (240 + 530)));
        assert_eq!((t.view, t.frame()), (Duration::ZERO, ns(2 * 900)));
    }

    #[test]
    fn a_stamp_before_the_one_before_it_counts_zero() {
        let t = stage_times(&[500, 100, 300], &[Stage::View, Stage::Gather], 1.0);
        assert_eq!((t.view, t.gather), (Duration::ZERO, Duration::from_nanos(200)));
    }
}
