//! `prismatic render`'s job on any backend's render, apart from the
//! command line: passes in order within a time budget, the output
//! rewritten every so often while they run, and at the end an image (PNG
//! or EXR) or a partial render's raw sums (for `prismatic merge`).

use crate::output::{PendingFile, write_image};
use crate::partial::{Partial, fingerprint};
use anyhow::{Result, bail};
use prismatic_core::{Accumulation, Image, NoProgress, Progress, Render, RenderStats};
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// Where a render goes.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Output {
    /// An image: `.png` (tone-mapped sRGB) or `.exr` (linear RGB).
    Image(PathBuf),
    /// A partial render's raw sums.
    Partial(PathBuf),
}

impl Output {
    /// The file.
    pub fn path(&self) -> &Path {
        match self {
            Output::Image(p) | Output::Partial(p) => p,
        }
    }

    /// Writes what `render`'s passes so far give (its base and `sums`) into
    /// `out`: a complete file or nothing.
    fn write(&self, out: PendingFile, render: &mut dyn Render, base: Image, sums: Accumulation) -> Result<()> {
        let scene = render.scene();
        match self {
            Output::Image(path) => {
                let image = sums.image(&base);
                if !image.is_finite() {
                    bail!("the render produced non-finite pixels; nothing was written (please report this scene)");
                }
                out.commit(|w| write_image(w, path, &image, scene.scene.render.tone_map))
            }
            Output::Partial(_) => {
                let partial = Partial {
                    fingerprint: fingerprint(scene),
                    backend: render.backend().to_string(),
                    tone_map: scene.scene.render.tone_map,
                    base,
                    sums,
                };
                out.commit(|w| partial.write(w))
            }
        }
    }
}

/// What to run: passes, a time budget, periodic saves, the output.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderJob {
    /// Passes, run in order (an end of `u32::MAX`: until the time budget says stop).
    pub passes: Range<u32>,
    /// Stop after the pass that crosses this much time.
    pub time: Option<Duration>,
    /// Rewrite the output every this much time while passes remain.
    pub save_every: Option<Duration>,
    /// Where the result goes.
    pub output: Output,
}

/// What a job did.
#[derive(Clone, Debug, PartialEq)]
pub struct JobReport {
    /// The render's statistics at the end.
    pub stats: RenderStats,
    /// The passes in the output.
    pub passes: Vec<(u32, u32)>,
    /// Time of the view rays and the pilot pass.
    pub prepared: Duration,
    /// Time of the passes, until their sums were read back.
    pub passing: Duration,
    /// Times the output was rewritten before the end.
    pub saves: u32,
}

/// Hears about a job's passes (and, as a [`Progress`], about the work in them).
pub trait JobProgress: Progress {
    /// `done` passes are finished of `total` (`None`: until the time runs out),
    /// after `elapsed`, within `budget`.
    fn pass_done(&mut self, done: u32, total: Option<u32>, elapsed: Duration, budget: Option<Duration>);
}

impl JobProgress for NoProgress {
    fn pass_done(&mut self, _: u32, _: Option<u32>, _: Duration, _: Option<Duration>) {}
}

impl RenderJob {
    /// Runs the job on `render`; `out` is the output file, created before
    /// the work starts (so that an unwritable path fails early).
    pub fn run(&self, render: &mut dyn Render, out: PendingFile, progress: &mut dyn JobProgress) -> Result<JobReport> {
        let t0 = Instant::now();
        render.ready(progress)?;
        let prepared = t0.elapsed();
        let total = (self.passes.end != u32::MAX).then(|| self.passes.len() as u32);
        let (mut last_save, mut saves) = (Instant::now(), 0);
        for (done, k) in self.passes.clone().enumerate() {
            render.run_pass(k, progress)?;
            let done = done as u32 + 1;
            progress.pass_done(done, total, t0.elapsed(), self.time);
            if self.time.is_some_and(|budget| t0.elapsed() >= budget) {
                break;
            }
            let more = total.is_none_or(|t| done < t);
            if more && self.save_every.is_some_and(|every| last_save.elapsed() >= every) {
                let (base, sums) = (render.base()?, render.sums()?);
                self.output.write(PendingFile::create(self.output.path())?, render, base, sums)?;
                (last_save, saves) = (Instant::now(), saves + 1);
            }
        }
        let (base, sums) = (render.base()?, render.sums()?);
        let passing = t0.elapsed() - prepared;
        let passes = sums.passes.clone();
        self.output.write(out, render, base, sums)?;
        Ok(JobReport { stats: render.stats()?, passes, prepared, passing, saves })
    }
}
