//! `prismatic`: render dispersion caustics, dump photon maps, list built-in scenes.

use anyhow::Result;
use clap::{Args, Parser, Subcommand};
use prismatic_cli::args::{parse_passes, parse_seconds};
use prismatic_cli::backends::{self, BackendChoice};
use prismatic_cli::builtin::{BUILTIN_SCENES, GENERATED_SCENES, find, find_generated, names};
use prismatic_cli::environment_file::EnvironmentArgs;
use prismatic_cli::output::{ExrLayers, PendingFile, write_image, write_photon_csv, write_png};
use prismatic_cli::partial::Partial;
use prismatic_cli::progress_bar::ProgressBar;
use prismatic_cli::render_job::{Output, RenderJob};
use prismatic_cli::scene_file::SceneFileError;
use prismatic_cli::settings::{Settings, SettingsSource};
use prismatic_cli::study::progress::StudyBar;
use prismatic_cli::study::{self, StudyOptions, machine, report};
use prismatic_core::model::bands::BandSpec;
use prismatic_core::{PreparedScene, TraceStats};
use std::ops::Range;
use std::path::{Path, PathBuf};
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
        /// default: the scene's `passes`, or with --time as many as fit.
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
    /// Trace the caustic photons of one pass of a scene's render and write them as CSV.
    Photons {
        #[command(flatten)]
        job: JobArgs,
        /// The pass whose photons to write (each pass has its own seed).
        #[arg(long, default_value_t = 0)]
        pass: u32,
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
    #[command(flatten)]
    settings: Settings,
    #[command(flatten)]
    environment: EnvironmentArgs,
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
    /// Run only the curves whose label contains this (repeatable, e.g.
    /// `--series LT --series "16 bands"`).
    #[arg(long)]
    series: Vec<String>,
}

impl StudyArgs {
    fn options(&self, rebuild: bool) -> StudyOptions {
        StudyOptions {
            scene: self.scene.clone(),
            quick: self.quick,
            cache: self.cache.clone(),
            rebuild_reference: self.rebuild_reference || rebuild,
            series: self.series.clone(),
        }
    }
}

/// Exit status for bad input (scene files, arguments), as clap uses for usage errors.
const EXIT_BAD_INPUT: u8 = 2;

/// Without `XDG_RUNTIME_DIR` there is no Wayland session, yet Mesa's
/// Vulkan drivers (lavapipe among them) ask libwayland for a display while
/// `auto` lists the adapters, and libwayland prints "error:
/// XDG_RUNTIME_DIR is invalid or not set" twice on renders that work.
/// Naming a display socket that does not exist makes that lookup fail
/// quietly. Called first in `main`, before any thread exists.
#[allow(unsafe_code)] // set_var: sound before any thread starts (see above)
fn quiet_missing_wayland_session() {
    let unset = |name: &str| std::env::var_os(name).is_none_or(|v| v.is_empty());
    if cfg!(target_os = "linux") && unset("XDG_RUNTIME_DIR") && unset("WAYLAND_DISPLAY") && unset("WAYLAND_SOCKET") {
        // SAFETY: no other thread exists yet to read the environment.
        unsafe { std::env::set_var("WAYLAND_DISPLAY", "/nonexistent/prismatic-has-no-wayland-session") };
    }
}

fn main() -> ExitCode {
    quiet_missing_wayland_session();
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
        Command::Render { job, passes, time, partial, save_every, output } => {
            let output = match partial {
                Some(file) => Output::Partial(file),
                None => Output::Image(output),
            };
            render(&job, passes, time, save_every, &output)
        }
        Command::Merge { files, output } => merge(&files, &output),
        Command::Photons { job, pass, output } => photons(&job, pass, &output),
        Command::Study { study, output } => run_study(&study, &output),
        Command::Reference { study, output } => reference(&study, &output),
        Command::Scenes => {
            list_scenes();
            Ok(())
        }
        Command::Scene { name } => print_scene(&name),
    }
}

/// `prismatic render`: the job's passes into an image or a partial.
fn render(
    args: &JobArgs,
    passes: Option<Range<u32>>,
    time: Option<f64>,
    save_every: Option<f64>,
    output: &Output,
) -> Result<()> {
    let out = PendingFile::create(output.path())?;
    let (name, scene, _) = prepare(args)?;
    let passes = passes.unwrap_or(if time.is_some() { 0..u32::MAX } else { 0..scene.scene.render.passes });
    let seconds = |s: Option<f64>| s.map(Duration::from_secs_f64);
    let job = RenderJob { passes, time: seconds(time), save_every: seconds(save_every) };
    let mut selected = backends::select(args.backend)?;
    if let Some(note) = &selected.note {
        eprintln!("{note}");
    }
    let mut render = selected.backend.prepare(&scene)?;
    let mut bar = ProgressBar::new();
    let report = job.run_into(render.as_mut(), output, out, &mut bar);
    bar.finish();
    let report = report?;
    let s = &report.stats;
    let radii = match s.first_radii {
        Some((lo, hi)) => format!("{lo:.4}–{hi:.4}"),
        None => "none".into(),
    };
    let traffic = match (s.uploaded, s.read_back) {
        (0, 0) => String::new(),
        (up, down) => format!("; {} uploaded, {} read back", bytes(up), bytes(down)),
    };
    println!(
        "{name}: {} backend, {} passes ({}), {}; {} visible points, first radii {radii}; view rays and \
         pilot in {}, passes in {} ({:.1} ms a pass){traffic}; wrote {} ({}x{})",
        render.backend(),
        s.passes,
        pass_list(&report.passes),
        photon_summary(&scene, &s.trace),
        s.visible_points,
        secs(report.prepared),
        secs(report.passing),
        report.passing.as_secs_f64() * 1e3 / f64::from(s.passes.max(1)),
        output.path().display(),
        scene.scene.render.width,
        scene.scene.render.height
    );
    if s.view_paths_cut > 0 {
        eprintln!(
            "warning: {name}: the device stopped the view paths of {} pixels short (a software GPU stops an \
             invocation's loops after 65,535 iterations): light is missing there; render with --backend cpu",
            s.view_paths_cut
        );
    }
    Ok(())
}

/// `prismatic merge`: partial renders into the image one run of all their passes gives.
fn merge(files: &[PathBuf], output: &Path) -> Result<()> {
    let out = PendingFile::create(output)?;
    let mut merged: Option<Partial> = None;
    for file in files {
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
    let layers = || ExrLayers {
        caustic: Some(ExrLayers::caustic(&image, &merged.base)),
        features: Some(merged.features.clone()),
    };
    out.commit(|w| write_image(w, output, &image, merged.display, layers))?;
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

/// `prismatic photons`: one pass's caustic photon map as CSV.
fn photons(job: &JobArgs, pass: u32, output: &Path) -> Result<()> {
    let out = PendingFile::create(output)?;
    let (name, scene, origin) = prepare(job)?;
    let mut selected = backends::select(job.backend)?;
    let mut render = selected.backend.prepare(&scene)?;
    let mut bar = ProgressBar::new();
    let t0 = Instant::now();
    let map = render.photon_map(pass, &mut bar)?;
    let t_trace = t0.elapsed();
    bar.finish();
    out.commit(|w| write_photon_csv(w, &map, origin))?;
    println!(
        "{name}: {} backend, pass {pass}, {}; trace {}; wrote {}",
        render.backend(),
        photon_summary(&scene, &map.stats),
        secs(t_trace),
        output.display()
    );
    Ok(())
}

/// `prismatic study`: the accuracy study's CSV, report and plot.
fn run_study(study: &StudyArgs, output: &Path) -> Result<()> {
    let mut bar = StudyBar::new();
    let result = study::run(&study.options(false), &mut bar);
    bar.finish();
    let result = result?;
    let written = report::write_all(&result, output, &machine::describe())?;
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

/// `prismatic reference`: (re)builds a scene's converged study image.
fn reference(study: &StudyArgs, output: &Path) -> Result<()> {
    let out = PendingFile::create(output)?;
    let mut bar = StudyBar::new();
    let built = study::build_reference(&study.options(true), &mut bar);
    bar.finish();
    let (reference, display) = built?;
    out.commit(|w| write_png(w, &reference.image, display))?;
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

/// `prismatic scenes`: the built-in scenes, a line each.
fn list_scenes() {
    for s in &BUILTIN_SCENES {
        println!("{:<16} {}", s.name, s.description);
    }
    for s in &GENERATED_SCENES {
        println!("{:<16} {}", s.name, s.description);
    }
}

/// `prismatic scene NAME`: a built-in scene's source (TOML, or the glTF JSON it is written as).
fn print_scene(name: &str) -> Result<()> {
    if let Some(g) = find_generated(name) {
        println!("{}", (g.document)().to_json());
        return Ok(());
    }
    let s = find(name).ok_or_else(|| SceneFileError {
        file: name.to_string(),
        line: None,
        key: String::new(),
        reason: format!("no such built-in scene; try one of: {}", names().join(", ")),
    })?;
    print!("{}", s.source);
    Ok(())
}

/// "0..8, 12..16".
fn pass_list(ranges: &[(u32, u32)]) -> String {
    ranges.iter().map(|(a, b)| format!("{a}..{b}")).collect::<Vec<_>>().join(", ")
}

/// Loads the scene, applies the command-line settings and validates. Also
/// returns the world position of the scene's local frame.
fn prepare(job: &JobArgs) -> Result<(String, PreparedScene, glam::DVec3)> {
    let doc = prismatic_cli::load_scene(&job.scene)?;
    for w in &doc.warnings {
        eprintln!("warning: {}: {w}", job.scene);
    }
    let origin = doc.origin;
    let doc = job.environment.apply(doc, SettingsSource::CommandLine)?;
    let scene = job.settings.prepare(doc, SettingsSource::CommandLine)?;
    println!("{}", scene.plan.summary());
    if job.explain {
        print!("{}", scene.plan.explain());
    }
    Ok((job.scene.clone(), scene, origin))
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

/// "12.3 MB", "456 B".
fn bytes(n: u64) -> String {
    match n {
        0..1_000 => format!("{n} B"),
        1_000..1_000_000 => format!("{:.1} kB", n as f64 / 1e3),
        _ => format!("{:.1} MB", n as f64 / 1e6),
    }
}
