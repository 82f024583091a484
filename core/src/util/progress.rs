//! The stages of a render and how long work reports on them: a leaf module
//! every layer may use (progress bars, GPU timestamps, host timers).

use core::fmt;
use core::time::Duration;

/// A stage of a render pass, in the order a pass runs them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// The view rays: direct light and visible points (after a change only).
    View,
    /// The photon pass: emit, trace and store the caustic photons.
    Photons,
    /// The hash grids over the pass's photons.
    Grid,
    /// The gather at the visible points, and the first radii or the sums.
    Gather,
}

impl Stage {
    /// What the stage is doing, for progress bars ("tracing photons").
    pub fn doing(self) -> &'static str {
        match self {
            Stage::View => "tracing view rays",
            Stage::Photons => "tracing photons",
            Stage::Grid => "building grids",
            Stage::Gather => "gathering",
        }
    }
}

/// Receives progress reports from long work.
pub trait Progress {
    /// `done` of `total` units of `stage` are finished.
    fn advance(&mut self, stage: Stage, done: u64, total: u64);
}

/// Progress that goes nowhere.
#[derive(Clone, Copy, Debug, Default)]
pub struct NoProgress;

impl Progress for NoProgress {
    fn advance(&mut self, _: Stage, _: u64, _: u64) {}
}

/// Time of one pass, per stage. A stage that ran twice (the pilot pass's
/// and the pass's photons after a change) is summed; a stage the pass did
/// not run is zero.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StageTimes {
    /// The view rays.
    pub view: Duration,
    /// The photon passes.
    pub photons: Duration,
    /// The grid builds.
    pub grid: Duration,
    /// The gathers.
    pub gather: Duration,
}

impl StageTimes {
    /// The whole pass: the stages' sum.
    pub fn frame(&self) -> Duration {
        self.view + self.photons + self.grid + self.gather
    }

    /// Adds `time` to `stage`'s.
    pub fn add(&mut self, stage: Stage, time: Duration) {
        match stage {
            Stage::View => self.view += time,
            Stage::Photons => self.photons += time,
            Stage::Grid => self.grid += time,
            Stage::Gather => self.gather += time,
        }
    }
}

/// `view 14.10, photons 0.52, grid 0.31, gather 3.05 ms`, without the view
/// when the pass traced none (the passes that follow no change).
impl fmt::Display for StageTimes {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let ms = |d: Duration| d.as_secs_f64() * 1e3;
        if !self.view.is_zero() {
            write!(f, "view {:.2}, ", ms(self.view))?;
        }
        write!(f, "photons {:.2}, grid {:.2}, gather {:.2} ms", ms(self.photons), ms(self.grid), ms(self.gather))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use alloc::string::ToString;

    #[test]
    fn shown_in_milliseconds_with_the_view_only_when_it_ran() {
        let us = Duration::from_micros;
        let t = StageTimes { view: Duration::ZERO, photons: us(520), grid: us(310), gather: us(3054) };
        assert_eq!(t.to_string(), "photons 0.52, grid 0.31, gather 3.05 ms");
        let t = StageTimes { view: us(14_100), ..t };
        assert_eq!(t.to_string(), "view 14.10, photons 0.52, grid 0.31, gather 3.05 ms");
    }
}
