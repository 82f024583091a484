//! A one-line progress bar on stderr, shown only when stderr is a terminal:
//! the stage at work until the first pass is done (the view rays, a long
//! first pass), then the passes done with an estimate of what is left.

use crate::render_job::JobProgress;
use prismatic_core::{Progress, Stage};
use std::io::{IsTerminal, Write};
use std::time::Duration;

/// The bar.
pub struct ProgressBar {
    enabled: bool,
    /// What was shown last: a stage and its percentage, or passes (`None`).
    last: Option<(Option<Stage>, u64)>,
}

impl Default for ProgressBar {
    fn default() -> Self {
        Self::new()
    }
}

impl ProgressBar {
    /// A bar on stderr when it is a terminal (nothing otherwise).
    pub fn new() -> Self {
        ProgressBar { enabled: std::io::stderr().is_terminal(), last: None }
    }

    /// Clears the bar's line.
    pub fn finish(&mut self) {
        if self.enabled && self.last.is_some() {
            eprint!("\r{:78}\r", "");
        }
    }
}

impl JobProgress for ProgressBar {
    fn pass_done(&mut self, done: u32, total: Option<u32>, elapsed: Duration, budget: Option<Duration>) {
        if !self.enabled {
            return;
        }
        self.last = Some((None, u64::from(done)));
        let per_pass = elapsed.as_secs_f64() / f64::from(done);
        let mut left = total.map_or(f64::INFINITY, |t| per_pass * f64::from(t - done));
        if let Some(b) = budget {
            left = left.min((b.as_secs_f64() - elapsed.as_secs_f64()).max(0.0));
        }
        let of = match (total, budget) {
            (Some(t), _) => format!("/{t}"),
            (None, Some(b)) => format!(" of {:.0} s", b.as_secs_f64()),
            (None, None) => String::new(),
        };
        let filled = match (total, budget) {
            (Some(t), _) => (done as usize * 25) / t.max(1) as usize,
            (None, Some(b)) => ((elapsed.as_secs_f64() / b.as_secs_f64()).min(1.0) * 25.0) as usize,
            (None, None) => 0,
        };
        eprint!(
            "\rpass {done}{of} [{}{}] {:.1} s, ~{:.1} s left  ",
            "#".repeat(filled),
            " ".repeat(25 - filled),
            elapsed.as_secs_f64(),
            left
        );
        std::io::stderr().flush().ok();
    }
}

impl Progress for ProgressBar {
    /// Shows the stage at work until the first pass is done (then the passes).
    fn advance(&mut self, stage: Stage, done: u64, total: u64) {
        if !self.enabled || total == 0 || matches!(self.last, Some((None, _))) {
            return;
        }
        let percent = done * 100 / total;
        if self.last == Some((Some(stage), percent)) {
            return;
        }
        self.last = Some((Some(stage), percent));
        let filled = (percent / 4) as usize;
        eprint!("\r{:<18} [{}{}] {percent:3}%", stage.doing(), "#".repeat(filled), " ".repeat(25 - filled));
        std::io::stderr().flush().ok();
    }
}
