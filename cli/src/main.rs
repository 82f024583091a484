//! `prismatic`: render dispersion caustics, dump photon maps, list built-in scenes.

use anyhow::Result;
use clap::{Args, Parser, Subcommand};
use prismatic_cli::backends::{self, BackendChoice};
use prismatic_cli::builtin::{BUILTIN_SCENES, GENERATED_SCENES, find, find_generated, names};
use prismatic_cli::output::{PendingFile, write_image, write_photon_csv, write_png};
use prismatic_cli::partial::Partial;
use prismatic_cli::passes::{parse_passes, parse_seconds};
use prismatic_cli::progress_bar::ProgressBar;
use prismatic_cli::render_job::{Output, RenderJob};
use prismatic_cli::scene_file::{
    SceneFileError, parse_bands, parse_estimator, parse_photon_sequence, parse_radius_mode, parse_view_paths,
    parse_wavelengths,
};
use prismatic_cli::settings::{Settings, SettingsSource};
use prismatic_cli::study::progress::StudyBar;
use prismatic_cli::study::{self, StudyOptions, report};
use prismatic_core::model::bands::BandSpec;
use prismatic_core::model::scene::{Estimator, PhotonSequence, RadiusMode, ViewPaths, WavelengthSampling};
use prismatic_core::{PreparedScene, TraceStats};
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
    /// Band table: paper3, paper7 or a number of physically based bands.
    #[arg(long, value_parser = parse_bands)]
    bands: Option<BandSpec>,
    /// White photons to emit.
    #[arg(long)]
    photons: Option<u32>,
    /// Gather radius (with progressive radii: the largest first radius).
    #[arg(long)]
    radius: Option<f32>,
    /// Gather radii: progressive (per point, shrinking pass by pass) or
    /// fixed (the scene's radius everywhere, the paper's frame).
    #[arg(long, value_parser = parse_radius_mode)]
    radius_mode: Option<RadiusMode>,
    /// RNG seed.
    #[arg(long)]
    seed: Option<u32>,
    /// Gather estimator: paper or density.
    #[arg(long, value_parser = parse_estimator)]
    estimator: Option<Estimator>,
    /// Light tracing (true or false): connect the caustic photons on
    /// surfaces the camera sees directly to the camera; gather only behind
    /// mirrors and glass.
    #[arg(long)]
    light_tracing: Option<bool>,
    /// Wavelength sampling at dispersive glass: split, random_band, continuous or hero.
    #[arg(long, value_parser = parse_wavelengths)]
    wavelengths: Option<WavelengthSampling>,
    /// Where photons' emission directions and wavelengths come from: sobol
    /// (Owen-scrambled, stratified per pass) or random.
    #[arg(long, value_parser = parse_photon_sequence)]
    photon_sequence: Option<PhotonSequence>,
    /// How view rays sample the pixels: centre (once per render, through
    /// pixel centres) or sampled (each pass anew: jittered in the pixel, 4
    /// hero wavelengths at dispersive glass; anti-aliased).
    #[arg(long, value_parser = parse_view_paths)]
    view_paths: Option<ViewPaths>,
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
        Command::Render { job: args, passes, time, partial, save_every, output } => {
            let output = match partial {
                Some(file) => Output::Partial(file),
                None => Output::Image(output),
            };
            let out = PendingFile::create(output.path())?;
            let (name, scene, _) = prepare(&args)?;
            let passes = passes.unwrap_or(if time.is_some() { 0..u32::MAX } else { 0..scene.scene.render.passes });
            let seconds = |s: Option<f64>| s.map(Duration::from_secs_f64);
            let job = RenderJob { passes, time: seconds(time), save_every: seconds(save_every) };
            let mut selected = backends::select(args.backend)?;
            if let Some(note) = &selected.note {
                eprintln!("{note}");
            }
            let mut render = selected.backend.prepare(&scene)?;
            let mut bar = ProgressBar::new();
            let report = job.run_into(render.as_mut(), &output, out, &mut bar);
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
        Command::Photons { job, pass, output } => {
            let out = PendingFile::create(&output)?;
            let (name, scene, origin) = prepare(&job)?;
            let mut selected = backends::select(job.backend)?;
            let mut render = selected.backend.prepare(&scene)?;
            let mut bar = ProgressBar::new();
            let t0 = Instant::now();
            let map = render.photon_map(pass, &mut bar)?;
            let t_trace = t0.elapsed();
            bar.finish();
            out.commit(|w| write_photon_csv(w, &map, &scene.bands, origin))?;
            println!(
                "{name}: {} backend, pass {pass}, {}; trace {}; wrote {}",
                render.backend(),
                photon_summary(&scene, &map.stats),
                secs(t_trace),
                output.display()
            );
            Ok(())
        }
    }
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
    let scene = job.settings().prepare(doc, SettingsSource::CommandLine)?;
    println!("{}", scene.plan.summary());
    if job.explain {
        print!("{}", scene.plan.explain());
    }
    Ok((job.scene.clone(), scene, origin))
}

impl JobArgs {
    fn settings(&self) -> Settings {
        Settings {
            bands: self.bands,
            photons: self.photons,
            radius: self.radius,
            radius_mode: self.radius_mode,
            seed: self.seed,
            estimator: self.estimator,
            light_tracing: self.light_tracing,
            wavelengths: self.wavelengths,
            photon_sequence: self.photon_sequence,
            view_paths: self.view_paths,
            width: self.width,
            height: self.height,
        }
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

/// "12.3 MB", "456 B".
fn bytes(n: u64) -> String {
    match n {
        0..1_000 => format!("{n} B"),
        1_000..1_000_000 => format!("{:.1} kB", n as f64 / 1e3),
        _ => format!("{:.1} MB", n as f64 / 1e6),
    }
}
