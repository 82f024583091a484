//! `prismatic`: render dispersion caustics, dump photon maps, list built-in scenes.

use anyhow::{Context, Result};
use clap::{Args, Parser, Subcommand};
use prismatic_cli::backends::{self, BackendChoice};
use prismatic_cli::builtin::{BUILTIN_SCENES, GENERATED_SCENES, find, find_generated, names};
use prismatic_cli::output::{PendingFile, write_image, write_photon_csv, write_png};
use prismatic_cli::partial::{Partial, fingerprint};
use prismatic_cli::passes::{parse_passes, parse_seconds};
use prismatic_cli::scene_file::{SceneFileError, parse_bands, parse_estimator, parse_wavelengths};
use prismatic_cli::study::progress::StudyBar;
use prismatic_cli::study::{self, StudyOptions, report};
use prismatic_core::bands::BandSpec;
use prismatic_core::progressive::ProgressiveRender;
use prismatic_core::scene::{Estimator, WavelengthSampling};
use prismatic_core::{PreparedScene, Progress, Stage, TraceStats};
use std::io::{IsTerminal, Write};
use std::ops::Range;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::{Duration, Instant};

#[derive(Parser)]
#[command(name = "prismatic", version, about = "N-band dispersion photon mapping: prisms, caustics and rainbows")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Render a scene progressively: view rays once, then photon passes
    /// whose gather radius shrinks per pixel, averaged into the image.
    Render {
        #[command(flatten)]
        job: JobArgs,
        /// Passes: N (passes 0..N) or A..B (passes A to B-1, e.g. for --partial);
        /// default: the scene's `passes`.
        #[arg(long, value_parser = parse_passes)]
        passes: Option<Range<u32>>,
        /// Stop after the pass that crosses this many seconds.
        #[arg(long, value_parser = parse_seconds)]
        time: Option<f64>,
        /// Write the passes' raw sums to this file (for `prismatic merge`) instead of an image.
        #[arg(long)]
        partial: Option<PathBuf>,
        /// Rewrite the output every this many seconds while rendering.
        #[arg(long, value_parser = parse_seconds)]
        save_every: Option<f64>,
        /// Output image: .png (tone-mapped sRGB) or .exr (linear RGB, 32-bit float).
        #[arg(short, long, default_value = "prismatic.png", conflicts_with = "partial")]
        output: PathBuf,
    },
    /// Combine partial renders (`render --partial`) into the image one run of all their passes gives.
    Merge {
        /// Partial files.
        #[arg(required = true)]
        files: Vec<PathBuf>,
        /// Output image: .png or .exr.
        #[arg(short, long, default_value = "prismatic.png")]
        output: PathBuf,
    },
    /// Trace a scene's caustic photons and write them as CSV.
    Photons {
        #[command(flatten)]
        job: JobArgs,
        /// Output CSV.
        #[arg(short, long, default_value = "photons.csv")]
        output: PathBuf,
    },
    /// Measure what accuracy costs in time: sweep bands, wavelength sampling,
    /// photons, radius, estimator and backend against a converged reference;
    /// writes SCENE.csv, SCENE.md and SCENE.svg.
    Study {
        #[command(flatten)]
        study: StudyArgs,
        /// Output folder.
        #[arg(short, long, default_value = "study")]
        output: PathBuf,
    },
    /// Build (or rebuild) a scene's study reference and write it as a PNG.
    Reference {
        #[command(flatten)]
        study: StudyArgs,
        /// Output PNG.
        #[arg(short, long, default_value = "reference.png")]
        output: PathBuf,
    },
    /// List the built-in scenes.
    Scenes,
    /// Print a built-in scene as TOML (a template for your own).
    Scene {
        /// Built-in scene name.
        name: String,
    },
}

#[derive(Args)]
struct JobArgs {
    /// A built-in scene name or a scene file.
    #[arg(default_value = prismatic_cli::builtin::DEFAULT_SCENE)]
    scene: String,
    /// Which backend does the work.
    #[arg(long, value_enum, default_value_t = BackendChoice::Auto)]
    backend: BackendChoice,
    /// Band table: paper3, paper7 or a number of physically based bands.
    #[arg(long, value_parser = parse_bands)]
    bands: Option<BandSpec>,
    /// White photons to emit.
    #[arg(long)]
    photons: Option<u32>,
    /// Gather radius.
    #[arg(long)]
    radius: Option<f32>,
    /// RNG seed.
    #[arg(long)]
    seed: Option<u32>,
    /// Gather estimator: paper or density.
    #[arg(long, value_parser = parse_estimator)]
    estimator: Option<Estimator>,
    /// Wavelength sampling at dispersive glass: split, random_band or continuous.
    #[arg(long, value_parser = parse_wavelengths)]
    wavelengths: Option<WavelengthSampling>,
    /// Image width.
    #[arg(long)]
    width: Option<u32>,
    /// Image height.
    #[arg(long)]
    height: Option<u32>,
    /// Print every decision of the effect plan with its reason.
    #[arg(long)]
    explain: bool,
}

#[derive(Args)]
struct StudyArgs {
    /// A built-in scene name or a scene file.
    #[arg(default_value = "sphere")]
    scene: String,
    /// Small images, three photon counts, fewer curves: under a minute.
    #[arg(long)]
    quick: bool,
    /// Where references are cached (by content hash).
    #[arg(long, default_value = ".prismatic-cache/references")]
    cache: PathBuf,
    /// Rebuild the reference even when a cached one matches.
    #[arg(long)]
    rebuild_reference: bool,
}

impl StudyArgs {
    fn options(&self, rebuild: bool) -> StudyOptions {
        StudyOptions {
            scene: self.scene.clone(),
            quick: self.quick,
            cache: self.cache.clone(),
            rebuild_reference: self.rebuild_reference || rebuild,
        }
    }
}

/// Exit status for bad input (scene files, arguments), as clap uses for usage errors.
const EXIT_BAD_INPUT: u8 = 2;

fn main() -> ExitCode {
    let cli = Cli::parse();
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            if e.downcast_ref::<SceneFileError>().is_some() {
                ExitCode::from(EXIT_BAD_INPUT)
            } else {
                ExitCode::FAILURE
            }
        }
    }
}

fn run(cli: Cli) -> Result<()> {
    match cli.command {
        Command::Study { study, output } => {
            let mut bar = StudyBar::new();
            let result = study::run(&study.options(false), &mut bar);
            bar.finish();
            let result = result?;
            let written = report::write_all(&result, &output, &machine())?;
            println!(
                "{}: {} points; wrote {}, {} and {}",
                result.scene,
                result.rows.len(),
                written.csv.display(),
                written.markdown.display(),
                written.plot.display()
            );
            Ok(())
        }
        Command::Reference { study, output } => {
            let out = PendingFile::create(&output)?;
            let mut bar = StudyBar::new();
            let built = study::build_reference(&study.options(true), &mut bar);
            bar.finish();
            let (reference, tone_map) = built?;
            out.commit(|w| write_png(w, &reference.image, tone_map))?;
            println!(
                "{}: reference of {} passes (last change ΔE00 {:.3}, {}) in {:.1} s, cached in {}; wrote {}",
                study.scene,
                reference.passes,
                reference.last_change,
                if reference.converged { "converged" } else { "not converged" },
                reference.seconds,
                reference.dir.display(),
                output.display()
            );
            Ok(())
        }
        Command::Scenes => {
            for s in &BUILTIN_SCENES {
                println!("{:<16} {}", s.name, s.description);
            }
            for s in &GENERATED_SCENES {
                println!("{:<16} {}", s.name, s.description);
            }
            Ok(())
        }
        Command::Scene { name } => {
            if let Some(g) = find_generated(&name) {
                println!("{}", (g.document)().to_json());
                return Ok(());
            }
            let s = find(&name).ok_or_else(|| SceneFileError {
                file: name.clone(),
                line: None,
                key: String::new(),
                reason: format!("no such built-in scene; try one of: {}", names().join(", ")),
            })?;
            print!("{}", s.source);
            Ok(())
        }
        Command::Render { job, passes, time, partial, save_every, output } => {
            let target = match &partial {
                Some(file) => Target::Partial(file.clone()),
                None => Target::Image(output),
            };
            let out = PendingFile::create(target.path())?;
            let (name, scene, _) = prepare(&job)?;
            let range = passes.unwrap_or(0..scene.scene.render.passes);
            let mut selected = backends::select(job.backend)?;
            if let Some(note) = &selected.note {
                eprintln!("{note}");
            }
            let backend = selected.backend.as_mut();
            let mut bar = ProgressBar::new();
            let t0 = Instant::now();
            let mut render = ProgressiveRender::prepare(backend, &scene, &mut bar)?;
            let prepared = t0.elapsed();
            let budget = time.map(Duration::from_secs_f64);
            let save_every = save_every.map(Duration::from_secs_f64);
            let mut stats = TraceStats::default();
            let mut last_save = Instant::now();
            for (done, k) in range.clone().enumerate() {
                stats.merge(&render.run_pass(backend, k)?);
                bar.pass(done as u32 + 1, range.len() as u32, stats.emitted, t0.elapsed(), budget);
                if budget.is_some_and(|b| t0.elapsed() >= b) {
                    break;
                }
                if save_every.is_some_and(|e| last_save.elapsed() >= e) && done + 1 < range.len() {
                    let snapshot = PendingFile::create(target.path())?;
                    target.write(snapshot, &render, &scene, backend.name())?;
                    last_save = Instant::now();
                }
            }
            let elapsed = t0.elapsed();
            bar.finish();
            let summed = render.accumulation().pass_count();
            target.write(out, &render, &scene, backend.name())?;
            let radii = render.initial_radii();
            let (lo, hi) = radii.iter().fold((f32::INFINITY, 0.0f32), |(lo, hi), &r| (lo.min(r), hi.max(r)));
            println!(
                "{name}: {} backend, {summed} passes ({}), {}; {} visible points, first radii {}; view rays and \
                 pilot in {}, passes in {} ({:.1} ms a pass); wrote {} ({}x{})",
                backend.name(),
                pass_list(&render.accumulation().passes),
                photon_summary(&scene, &stats),
                render.points().points.len(),
                if radii.is_empty() { "none".to_string() } else { format!("{lo:.4}–{hi:.4}") },
                secs(prepared),
                secs(elapsed - prepared),
                (elapsed - prepared).as_secs_f64() * 1e3 / f64::from(summed.max(1)),
                target.path().display(),
                scene.scene.render.width,
                scene.scene.render.height
            );
            Ok(())
        }
        Command::Merge { files, output } => {
            let out = PendingFile::create(&output)?;
            let mut merged: Option<Partial> = None;
            for file in &files {
                let partial = Partial::read(file)?;
                match &mut merged {
                    None => merged = Some(partial),
                    Some(m) => m.merge(&partial, &file.display().to_string())?,
                }
            }
            let merged = merged.expect("clap requires a file");
            let image = merged.image();
            if !image.is_finite() {
                anyhow::bail!("the merged partials give non-finite pixels; nothing was written");
            }
            out.commit(|w| write_image(w, &output, &image, merged.tone_map))?;
            println!(
                "merged {} partials ({} passes: {}); wrote {} ({}x{})",
                files.len(),
                merged.sums.pass_count(),
                pass_list(&merged.sums.passes),
                output.display(),
                image.width,
                image.height
            );
            Ok(())
        }
        Command::Photons { job, output } => {
            let out = PendingFile::create(&output)?;
            let (name, scene, origin) = prepare(&job)?;
            let mut selected = backends::select(job.backend)?;
            let mut bar = ProgressBar::new();
            let t0 = Instant::now();
            let map = selected.backend.trace_photons(&scene, &mut bar)?;
            let t_trace = t0.elapsed();
            bar.finish();
            out.commit(|w| write_photon_csv(w, &map, &scene.bands, origin))?;
            println!(
                "{name}: {} backend, {}; trace {}; wrote {}",
                selected.backend.name(),
                photon_summary(&scene, &map.stats),
                secs(t_trace),
                output.display()
            );
            Ok(())
        }
    }
}

/// Where a render goes: an image, or a partial render's raw sums.
enum Target {
    Image(PathBuf),
    Partial(PathBuf),
}

impl Target {
    fn path(&self) -> &std::path::Path {
        match self {
            Target::Image(p) | Target::Partial(p) => p,
        }
    }

    /// Writes what the passes so far give into `out` (a complete file or nothing).
    fn write(&self, out: PendingFile, render: &ProgressiveRender, scene: &PreparedScene, backend: &str) -> Result<()> {
        match self {
            Target::Image(path) => {
                let image = render.image();
                if !image.is_finite() {
                    anyhow::bail!(
                        "the render produced non-finite pixels; nothing was written (please report this scene)"
                    );
                }
                out.commit(|w| write_image(w, path, &image, scene.scene.render.tone_map))
            }
            Target::Partial(_) => {
                let partial = Partial {
                    fingerprint: fingerprint(scene),
                    backend: backend.to_string(),
                    tone_map: scene.scene.render.tone_map,
                    base: render.points().base.clone(),
                    sums: render.accumulation().clone(),
                };
                out.commit(|w| partial.write(w))
            }
        }
    }
}

/// "0..8, 12..16".
fn pass_list(ranges: &[(u32, u32)]) -> String {
    ranges.iter().map(|(a, b)| format!("{a}..{b}")).collect::<Vec<_>>().join(", ")
}

/// Loads the scene, applies the command-line overrides and validates. Also
/// returns the world position of the scene's local frame.
fn prepare(job: &JobArgs) -> Result<(String, PreparedScene, glam::DVec3)> {
    let mut doc = prismatic_cli::load_scene(&job.scene)?;
    for w in &doc.warnings {
        eprintln!("warning: {}: {w}", job.scene);
    }
    let r = &mut doc.scene.render;
    r.bands = job.bands.unwrap_or(r.bands);
    r.photons = job.photons.unwrap_or(r.photons);
    r.radius = job.radius.unwrap_or(r.radius);
    r.seed = job.seed.unwrap_or(r.seed);
    r.estimator = job.estimator.unwrap_or(r.estimator);
    r.wavelengths = job.wavelengths.unwrap_or(r.wavelengths);
    r.width = job.width.unwrap_or(r.width);
    r.height = job.height.unwrap_or(r.height);
    doc.validate().map_err(|e| blame_flag(job, e))?;
    let scene = PreparedScene::new(doc.scene.clone()).map_err(|e| blame_flag(job, doc.error(e)))?;
    println!("{}", scene.plan.summary());
    if job.explain {
        print!("{}", scene.plan.explain());
    }
    Ok((job.scene.clone(), scene, doc.origin))
}

/// A value that came from a flag is reported against the flag, not the scene file.
fn blame_flag(job: &JobArgs, e: SceneFileError) -> SceneFileError {
    let given = [
        ("render.bands", "--bands", job.bands.is_some()),
        ("render.photons", "--photons", job.photons.is_some()),
        ("render.radius", "--radius", job.radius.is_some()),
        ("render.seed", "--seed", job.seed.is_some()),
        ("render.estimator", "--estimator", job.estimator.is_some()),
        ("render.wavelengths", "--wavelengths", job.wavelengths.is_some()),
        ("render.width", "--width", job.width.is_some()),
        ("render.height", "--height", job.height.is_some()),
    ];
    match given.iter().find(|(key, _, set)| *set && e.key == *key) {
        Some((_, flag, _)) => {
            SceneFileError { file: "command line".into(), line: None, key: (*flag).into(), reason: e.reason }
        }
        None => e,
    }
}

/// The machine a study ran on, for its report: CPU model, cores and the date.
fn machine() -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .map(|l| l.split(':').nth(1).unwrap_or("").trim().to_string())
        })
        .unwrap_or_else(|| "unknown CPU".into());
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let days = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.as_secs() / 86_400);
    format!("{cpu}, {cores} cores, {}", civil_date(days as i64))
}

/// YYYY-MM-DD of a day count since 1970-01-01 (Hinnant's civil-from-days).
fn civil_date(days: i64) -> String {
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!("{y:04}-{m:02}-{d:02}")
}

fn photon_summary(scene: &PreparedScene, s: &TraceStats) -> String {
    let bands = match scene.bands.spec() {
        BandSpec::Physical(1) => "1 physically based band".to_string(),
        BandSpec::Physical(n) => format!("{n} physically based bands"),
        paper => format!("{} bands, {paper}", scene.bands.len()),
    };
    format!("{} photons emitted, {} met a specular surface, {} stored ({bands})", s.emitted, s.specular_paths, s.stored)
}

fn secs(d: Duration) -> String {
    format!("{:.2} s", d.as_secs_f64())
}

/// A one-line progress bar on stderr, shown only when stderr is a terminal.
struct ProgressBar {
    enabled: bool,
    last: Option<(Stage, u64)>,
}

impl ProgressBar {
    fn new() -> Self {
        ProgressBar { enabled: std::io::stderr().is_terminal(), last: None }
    }

    fn finish(&mut self) {
        if self.enabled && self.last.is_some() {
            eprint!("\r{:78}\r", "");
        }
    }

    /// After pass `done` of `total`: photons so far, time, and an estimate of what is left.
    fn pass(&mut self, done: u32, total: u32, photons: u64, elapsed: Duration, budget: Option<Duration>) {
        if !self.enabled {
            return;
        }
        self.last = Some((Stage::Trace, u64::from(done)));
        let per_pass = elapsed.as_secs_f64() / f64::from(done);
        let mut left = per_pass * f64::from(total - done);
        if let Some(b) = budget {
            left = left.min((b.as_secs_f64() - elapsed.as_secs_f64()).max(0.0));
        }
        let filled = (done as usize * 25) / total.max(1) as usize;
        eprint!(
            "\rpass {done}/{total} [{}{}] {:.2} M photons, {:.1} s, ~{:.1} s left  ",
            "#".repeat(filled),
            " ".repeat(25 - filled),
            photons as f64 / 1e6,
            elapsed.as_secs_f64(),
            left
        );
        std::io::stderr().flush().context("stderr").ok();
    }
}

impl Progress for ProgressBar {
    fn advance(&mut self, stage: Stage, done: u64, total: u64) {
        if !self.enabled || total == 0 {
            return;
        }
        let percent = done * 100 / total;
        if self.last == Some((stage, percent)) {
            return;
        }
        self.last = Some((stage, percent));
        let label = match stage {
            Stage::Trace => "tracing photons",
            Stage::Render => "rendering",
        };
        let filled = (percent / 4) as usize;
        eprint!("\r{label:<16} [{}{}] {percent:3}%", "#".repeat(filled), " ".repeat(25 - filled));
        std::io::stderr().flush().context("stderr").ok();
    }
}
