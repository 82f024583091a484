//! `prismatic render`'s job on any backend's render, apart from the
//! command line (the Python package runs the same job): passes in order
//! within a time budget, the output rewritten every so often while they
//! run, and at the end an image (PNG or EXR) or a partial render's raw sums
//! (for `prismatic merge`).

use crate::output::{ExrLayers, PendingFile, write_image};
use crate::partial::Partial;
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
    pub fn write(&self, out: PendingFile, render: &dyn Render, base: Image, sums: Accumulation) -> Result<()> {
        let display = render.scene().scene.render.display();
        match self {
            Output::Image(path) => {
                let image = finite_image(&base, &sums)?;
                let layers = || ExrLayers::of(render.scene(), &image, &base);
                out.commit(|w| write_image(w, path, &image, display, layers))
            }
            Output::Partial(_) => out.commit(|w| Partial::of(render, base, sums).write(w)),
        }
    }
}

/// The image of `sums` over `base`, refused if any pixel is not finite.
pub fn finite_image(base: &Image, sums: &Accumulation) -> Result<Image> {
    let image = sums.image(base);
    if !image.is_finite() {
        bail!("the render produced non-finite pixels; nothing was written (please report this scene)");
    }
    Ok(image)
}

/// What to run: passes, a time budget, periodic saves.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderJob {
    /// Passes, run in order (an end of `u32::MAX`: until the time budget says stop).
    pub passes: Range<u32>,
    /// Stop after the pass that crosses this much time.
    pub time: Option<Duration>,
    /// Save every this much time while passes remain.
    pub save_every: Option<Duration>,
}

/// What a job rendered: the image without caustics and the passes' sums.
#[derive(Clone, Debug, PartialEq)]
pub struct Rendered {
    /// The image without caustics.
    pub base: Image,
    /// The passes' exact sums.
    pub sums: Accumulation,
    /// What the job did.
    pub report: JobReport,
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

    /// After each pass: an error stops the job with it (an interrupt, a
    /// caller's callback that failed).
    fn check(&mut self) -> Result<()> {
        Ok(())
    }
}

impl JobProgress for NoProgress {
    fn pass_done(&mut self, _: u32, _: Option<u32>, _: Duration, _: Option<Duration>) {}
}

/// Called with the render, its base and its sums so far every
/// `save_every` while passes remain.
pub type Save<'a> = dyn FnMut(&dyn Render, Image, Accumulation) -> Result<()> + 'a;

impl RenderJob {
    /// Runs the job on `render` and returns its base and sums; `save` gets
    /// them every `save_every` while passes remain.
    pub fn run(&self, render: &mut dyn Render, progress: &mut dyn JobProgress, save: &mut Save) -> Result<Rendered> {
        let t0 = Instant::now();
        render.ready(progress)?;
        let prepared = t0.elapsed();
        let total = (self.passes.end != u32::MAX).then(|| self.passes.len() as u32);
        let (mut last_save, mut saves) = (Instant::now(), 0);
        for (done, k) in self.passes.clone().enumerate() {
            render.run_pass(k, progress)?;
            let done = done as u32 + 1;
            progress.pass_done(done, total, t0.elapsed(), self.time);
            progress.check()?;
            if self.time.is_some_and(|budget| t0.elapsed() >= budget) {
                break;
            }
            let more = total.is_none_or(|t| done < t);
            if more && self.save_every.is_some_and(|every| last_save.elapsed() >= every) {
                let (base, sums) = (render.base()?, render.sums()?);
                save(&*render, base, sums)?;
                (last_save, saves) = (Instant::now(), saves + 1);
            }
        }
        let (base, sums) = (render.base()?, render.sums()?);
        let passing = t0.elapsed() - prepared;
        let passes = sums.passes.clone();
        let report = JobReport { stats: render.stats()?, passes, prepared, passing, saves };
        Ok(Rendered { base, sums, report })
    }

    /// Runs the job on `render` into `output`, rewritten every `save_every`;
    /// `out` is the output file, created before the work starts (so that an
    /// unwritable path fails early).
    pub fn run_into(
        &self,
        render: &mut dyn Render,
        output: &Output,
        out: PendingFile,
        progress: &mut dyn JobProgress,
    ) -> Result<JobReport> {
        let mut save =
            |render: &dyn Render, base, sums| output.write(PendingFile::create(output.path())?, render, base, sums);
        let rendered = self.run(render, progress, &mut save)?;
        output.write(out, &*render, rendered.base, rendered.sums)?;
        Ok(rendered.report)
    }
}
