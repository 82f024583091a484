//! `prismatic study`: what accuracy costs in time. Sweeps the settings that
//! trade one for the other (band table, wavelength sampling, photon count,
//! gather radius, estimator, light tracing, photon sequence, backend), times
//! every stage of each render and measures its error against a converged
//! reference.

pub mod converged;
pub mod machine;
pub mod metrics;
pub mod plot;
pub mod progress;
pub mod report;

use crate::backends::{BackendChoice, select};
use anyhow::{Context, Result};
use converged::{Reference, ReferenceSpec};
use metrics::{RenderError, StripeSums, mean_delta_e, rmse, stripe_error};
use prismatic_core::model::scene::{RadiusMode, Shape};
use prismatic_core::{
    Backend, BandSpec, Estimator, Light, NoProgress, PhotonSequence, PreparedScene, ViewPaths, WavelengthSampling,
};
use std::path::PathBuf;
use std::time::Instant;

/// Points whose band paths (photons × bands for `split`) exceed this are
/// skipped: their photon maps would not fit in memory (32 bytes a photon,
/// twice over with the CPU grid's copy).
pub const MAX_BAND_PATHS: u64 = 100_000_000;

/// Gather radius: the scene's, or shrinking over passes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RadiusPlan {
    /// The scene's radius, one pass with all photons (the paper's frame).
    Fixed,
    /// The renderer's progressive photon mapping: `passes` passes sharing
    /// the photons, per-point radii shrinking with the scene's α.
    Progressive {
        /// Passes.
        passes: u32,
    },
}

/// One family of settings, swept over photon counts (a curve in the plot).
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    /// Short label (`paper7`, `16 random band`, …).
    pub label: String,
    /// Band table.
    pub bands: BandSpec,
    /// Wavelength sampling.
    pub sampling: WavelengthSampling,
    /// Estimator.
    pub estimator: Estimator,
    /// Light tracing for the caustics the camera sees directly (the gather
    /// only behind mirrors and glass), or the gather everywhere.
    pub light_tracing: bool,
    /// Where the photons' emission and wavelength numbers come from.
    pub sequence: PhotonSequence,
    /// How view rays sample the pixels.
    pub view_paths: ViewPaths,
    /// Radius.
    pub radius: RadiusPlan,
    /// Backend.
    pub backend: BackendChoice,
    /// Largest photon count for this series (the scalar reference is slow).
    pub max_photons: u32,
}

/// What to sweep and how to measure.
#[derive(Clone, Debug)]
pub struct StudyPlan {
    /// Image width and height (the reference's too).
    pub size: (u32, u32),
    /// Photon counts.
    pub photons: Vec<u32>,
    /// The curves.
    pub series: Vec<Series>,
    /// The reference.
    pub reference: ReferenceSpec,
    /// Photons of the paper's Table 5 comparison.
    pub table5_photons: u32,
}

pub(crate) fn series(label: &str, bands: BandSpec, sampling: WavelengthSampling, estimator: Estimator) -> Series {
    Series {
        label: label.into(),
        bands,
        sampling,
        estimator,
        light_tracing: false,
        sequence: PhotonSequence::Sobol,
        view_paths: ViewPaths::Centre,
        radius: RadiusPlan::Fixed,
        backend: BackendChoice::Cpu,
        max_photons: u32::MAX,
    }
}

/// A curve of the progressive renderer over `passes` passes.
fn progressive(mut s: Series, passes: u32) -> Series {
    s.radius = RadiusPlan::Progressive { passes };
    s
}

/// A progressive curve with light tracing: `bands` physically based bands,
/// the density estimator (this wave's estimators).
fn light_traced(
    label: &str,
    bands: u16,
    sampling: WavelengthSampling,
    sequence: PhotonSequence,
    passes: u32,
) -> Series {
    let s = series(label, BandSpec::Physical(bands), sampling, Estimator::Density);
    progressive(Series { light_tracing: true, sequence, ..s }, passes)
}

/// A curve with per-pass view paths (`view_paths`): each pass its own
/// spectrally sampled view.
fn with_view(s: Series, view_paths: ViewPaths) -> Series {
    Series { view_paths, ..s }
}

impl StudyPlan {
    /// The full sweep for a scene of `size`.
    pub fn full(size: (u32, u32)) -> Self {
        use WavelengthSampling::{Continuous, Hero, RandomBand, Split};
        let d = Estimator::Density;
        let mut s = vec![
            series("paper3", BandSpec::Paper3, Split, Estimator::Paper),
            series("paper7", BandSpec::Paper7, Split, Estimator::Paper),
            series("paper7 density", BandSpec::Paper7, Split, d),
        ];
        for n in [3, 7, 16, 32, 64] {
            s.push(series(&format!("{n} bands"), BandSpec::Physical(n), Split, d));
        }
        s.push(series("7 bands paper est.", BandSpec::Physical(7), Split, Estimator::Paper));
        s.push(series("16 random band", BandSpec::Physical(16), RandomBand, d));
        s.push(series("64 random band", BandSpec::Physical(64), RandomBand, d));
        s.push(series("16 continuous", BandSpec::Physical(16), Continuous, d));
        for (bands, passes) in [(7, 4), (16, 8)] {
            s.push(progressive(
                series(&format!("{bands} bands progressive"), BandSpec::Physical(bands), Split, d),
                passes,
            ));
        }
        s.push(progressive(series("paper7 progressive", BandSpec::Paper7, Split, Estimator::Paper), 16));
        s.push(light_traced("LT 32 continuous", 32, Continuous, PhotonSequence::Sobol, 8));
        s.push(light_traced("LT 32 hero", 32, Hero, PhotonSequence::Sobol, 8));
        s.push(with_view(light_traced("LT 32 hero (hero view)", 32, Hero, PhotonSequence::Sobol, 8), ViewPaths::Hero));
        s.push(light_traced("LT 32 hero random", 32, Hero, PhotonSequence::Random, 8));
        s.push(light_traced("LT 16 bands", 16, Split, PhotonSequence::Sobol, 8));
        s.push(with_view(
            light_traced("LT 32 hero (sampled view)", 32, Hero, PhotonSequence::Sobol, 32),
            ViewPaths::Sampled,
        ));
        let mut scalar = series("paper7 reference backend", BandSpec::Paper7, Split, Estimator::Paper);
        scalar.backend = BackendChoice::Reference;
        scalar.max_photons = 1_000_000;
        s.push(scalar);
        StudyPlan {
            size,
            photons: vec![10_000, 30_000, 100_000, 300_000, 1_000_000, 3_000_000, 10_000_000],
            series: s,
            reference: ReferenceSpec::full(),
            table5_photons: 20_000,
        }
    }

    /// The quick sweep: small images, three photon counts, fewer curves
    /// (under a minute on two cores, reference included).
    pub fn quick(size: (u32, u32)) -> Self {
        use WavelengthSampling::{Continuous, Hero, RandomBand, Split};
        let d = Estimator::Density;
        let scale = 96.0 / size.0.max(size.1) as f32;
        let small = (((size.0 as f32 * scale) as u32).max(8), ((size.1 as f32 * scale) as u32).max(8));
        let mut scalar = series("paper7 reference backend", BandSpec::Paper7, Split, Estimator::Paper);
        scalar.backend = BackendChoice::Reference;
        scalar.max_photons = 10_000;
        StudyPlan {
            size: small,
            photons: vec![10_000, 40_000, 160_000],
            series: vec![
                series("paper3", BandSpec::Paper3, Split, Estimator::Paper),
                series("paper7", BandSpec::Paper7, Split, Estimator::Paper),
                series("3 bands", BandSpec::Physical(3), Split, d),
                series("7 bands", BandSpec::Physical(7), Split, d),
                series("16 bands", BandSpec::Physical(16), Split, d),
                series("16 random band", BandSpec::Physical(16), RandomBand, d),
                series("16 continuous", BandSpec::Physical(16), Continuous, d),
                progressive(series("16 bands progressive", BandSpec::Physical(16), Split, d), 4),
                light_traced("LT 16 continuous", 16, Continuous, PhotonSequence::Sobol, 4),
                light_traced("LT 16 hero", 16, Hero, PhotonSequence::Sobol, 4),
                with_view(light_traced("LT 16 hero (hero view)", 16, Hero, PhotonSequence::Sobol, 8), ViewPaths::Hero),
                scalar,
            ],
            reference: ReferenceSpec::quick(),
            table5_photons: 20_000,
        }
    }
}

/// One measured point.
#[derive(Clone, Debug, PartialEq)]
pub struct StudyRow {
    /// The series' settings (its label names the curve).
    pub setting: Series,
    /// White photons emitted.
    pub photons: u32,
    /// Photons stored (all passes).
    pub stored: u64,
    /// Seconds of the whole render: view rays, pilot, passes, read-out.
    pub seconds: f64,
    /// Seconds of it tracing photons, where the backend times its stages.
    pub trace_s: Option<f64>,
    /// The errors.
    pub error: RenderError,
    /// On the Pareto front of (time, ΔE00) over every row.
    pub pareto: bool,
}

impl StudyRow {
    /// Total seconds.
    pub fn total_s(&self) -> f64 {
        self.seconds
    }
}

/// A row of the paper's Table 5 comparison.
#[derive(Clone, Debug, PartialEq)]
pub struct Table5Row {
    /// What the paper calls it.
    pub method: &'static str,
    /// The paper's frames per second (GTX 260, 400×400).
    pub paper_fps: f64,
    /// Seconds here (trace + render), CPU backend.
    pub seconds: f64,
    /// Mean ΔE00 against the reference.
    pub delta_e: f64,
}

/// Everything a study found.
pub struct StudyResult {
    /// The scene's name.
    pub scene: String,
    /// The plan it ran.
    pub plan: StudyPlan,
    /// Where the reference came from and how converged it is.
    pub reference: ReferenceSummary,
    /// Measured points, in the order run.
    pub rows: Vec<StudyRow>,
    /// The paper's Table 5 measured here.
    pub table5: Vec<Table5Row>,
    /// Points not run, and why.
    pub skipped: Vec<String>,
}

/// How the reference was made.
#[derive(Clone, Debug, PartialEq)]
pub struct ReferenceSummary {
    /// Passes.
    pub passes: u32,
    /// Change at the last doubling (ΔE00).
    pub last_change: f64,
    /// Converged below the threshold.
    pub converged: bool,
    /// Seconds to build (when it was built).
    pub seconds: f64,
    /// Caustic pixels.
    pub caustic_pixels: usize,
    /// Cache directory.
    pub dir: PathBuf,
}

/// Study inputs.
pub struct StudyOptions {
    /// Scene name or file.
    pub scene: String,
    /// Quick mode.
    pub quick: bool,
    /// Cache directory for references.
    pub cache: PathBuf,
    /// Rebuild the reference even if cached.
    pub rebuild_reference: bool,
    /// Run only the curves whose label contains one of these (all when empty).
    pub series: Vec<String>,
}

/// Receives progress: a new total of steps, a finished step, a message.
pub trait StudyProgress {
    /// The number of steps ahead.
    fn start(&mut self, steps: u64);
    /// One step is done; `message` says what runs next or what happened.
    fn step(&mut self, message: &str);
    /// A line for the log.
    fn note(&mut self, message: &str);
}

/// Runs the study.
pub fn run(options: &StudyOptions, progress: &mut dyn StudyProgress) -> Result<StudyResult> {
    let (scene, mut plan) = study_scene(options)?;
    if !options.series.is_empty() {
        plan.series.retain(|s| options.series.iter().any(|wanted| s.label.contains(wanted.as_str())));
        anyhow::ensure!(
            !plan.series.is_empty(),
            "--series {}: no curve of the study's plan has that in its label",
            options.series.join(", ")
        );
    }
    let stripes = has_stripes(&scene);

    let points: Vec<(usize, u32)> = plan
        .series
        .iter()
        .enumerate()
        .flat_map(|(i, s)| plan.photons.iter().filter(move |&&p| p <= s.max_photons).map(move |&p| (i, p)))
        .collect();
    progress.start(points.len() as u64 + 5);
    progress.note(&format!("{}: reference ({} bands, density, progressive)", options.scene, plan.reference.bands));
    let mut cpu = select(BackendChoice::Cpu)?.backend;
    let reference = load_reference(options, &scene, &plan, cpu.as_mut(), progress)?;
    progress.step("reference ready");
    let mut rows = Vec::new();
    let mut skipped = Vec::new();
    for (i, photons) in points {
        let setting = &plan.series[i];
        let paths = u64::from(photons) * u64::from(setting.sampling.paths(setting_bands(setting)));
        if paths > MAX_BAND_PATHS {
            skipped.push(format!("{} at {photons} photons ({paths} band paths > {MAX_BAND_PATHS})", setting.label));
            progress.step(&format!("{} {photons}: skipped", setting.label));
            continue;
        }
        let mut backend = select(setting.backend)?.backend;
        let row = measure(&scene, setting, photons, backend.as_mut(), &reference, stripes)
            .with_context(|| format!("{} at {photons} photons", setting.label))?;
        progress.step(&format!("{} {photons}: ΔE00 {:.2} in {:.3} s", setting.label, row.error.delta_e, row.total_s()));
        rows.push(row);
    }
    report::mark_pareto(&mut rows);
    let table5 = table5(&scene, &plan, cpu.as_mut(), &reference, progress)?;
    Ok(StudyResult {
        scene: options.scene.clone(),
        reference: ReferenceSummary {
            passes: reference.passes,
            last_change: reference.last_change,
            converged: reference.converged,
            seconds: reference.seconds,
            caustic_pixels: reference.mask.iter().filter(|&&m| m).count(),
            dir: reference.dir.clone(),
        },
        plan,
        rows,
        table5,
        skipped,
    })
}

/// Builds (or loads) the reference the study of `options` would use; also
/// returns how the scene is shown, for writing it out.
pub fn build_reference(
    options: &StudyOptions,
    progress: &mut dyn StudyProgress,
) -> Result<(Reference, prismatic_core::model::color::Display)> {
    let (scene, plan) = study_scene(options)?;
    let r = load_reference(options, &scene, &plan, select(BackendChoice::Cpu)?.backend.as_mut(), progress)?;
    Ok((r, scene.scene.render.display()))
}

/// The plan's reference for `scene`, from the cache or built on `backend`.
fn load_reference(
    options: &StudyOptions,
    scene: &PreparedScene,
    plan: &StudyPlan,
    backend: &mut dyn Backend,
    progress: &mut dyn StudyProgress,
) -> Result<Reference> {
    converged::load_or_build(
        &options.scene,
        scene,
        &plan.reference,
        has_stripes(scene),
        &options.cache,
        options.rebuild_reference,
        backend,
        &mut |m| progress.note(m),
    )
}

/// The scene at the study's image size, and the plan.
fn study_scene(options: &StudyOptions) -> Result<(PreparedScene, StudyPlan)> {
    let doc = crate::load_scene(&options.scene)?;
    let size = (doc.scene.render.width, doc.scene.render.height);
    let plan = if options.quick { StudyPlan::quick(size) } else { StudyPlan::full(size) };
    let mut scene = doc.scene.clone();
    (scene.render.width, scene.render.height) = plan.size;
    let scene = PreparedScene::new(scene).map_err(|e| doc.error(e))?;
    Ok((scene, plan))
}

fn setting_bands(s: &Series) -> usize {
    prismatic_core::BandTable::new(s.bands).len()
}

/// Band stripes are compared where light arrives as a collimated beam
/// through a prism: every light a beam, some object a prism.
pub fn has_stripes(scene: &PreparedScene) -> bool {
    let s = &scene.scene;
    s.lights.iter().all(|l| matches!(l, Light::Beam { .. }))
        && s.objects.iter().any(|o| matches!(o.shape, Shape::Prism { .. }))
}

/// Renders `scene` with `setting` and `photons` through the render
/// protocol, timing it, and measures the error against `reference`.
pub fn measure(
    scene: &PreparedScene,
    setting: &Series,
    photons: u32,
    backend: &mut dyn Backend,
    reference: &Reference,
    stripes: bool,
) -> Result<StudyRow> {
    let mut s = scene.scene.clone();
    s.render.bands = setting.bands;
    s.render.wavelengths = setting.sampling;
    s.render.estimator = setting.estimator;
    s.render.light_tracing = setting.light_tracing;
    s.render.photon_sequence = setting.sequence;
    s.render.view_paths = setting.view_paths;
    let passes = match setting.radius {
        RadiusPlan::Fixed => {
            s.render.radius_mode = RadiusMode::Fixed;
            1
        }
        RadiusPlan::Progressive { passes } => passes,
    };
    s.render.photons = photons.div_ceil(passes);
    let configured = PreparedScene::new(s)?;
    let t0 = Instant::now();
    let mut render = backend.prepare(&configured)?;
    render.ready(&mut NoProgress)?;
    let mut trace_s = render.stage_times().map(|_| 0.0);
    for k in 0..passes {
        render.run_pass(k, &mut NoProgress)?;
        trace_s = trace_s.zip(render.stage_times()).map(|(t, times)| t + times.photons.as_secs_f64());
    }
    let image = render.image()?;
    let seconds = t0.elapsed().as_secs_f64();
    let stored = render.stats()?.trace.stored;
    // The band stripes of the fixed radius's one pass, from its photons
    // traced again (not timed).
    let stripe = match setting.radius {
        RadiusPlan::Fixed if stripes => {
            let map = render.photon_map(0, &mut NoProgress)?;
            let mut own = StripeSums::new(&configured.bands);
            own.add(&map);
            stripe_error(&own, &configured.bands, &reference.stripes)
        }
        _ => None,
    };
    let tone_map = scene.scene.render.tone_map;
    let error = RenderError {
        delta_e: mean_delta_e(&image, &reference.image, &reference.mask, tone_map),
        rmse: rmse(&image, &reference.image),
        stripe,
    };
    Ok(StudyRow { setting: setting.clone(), photons, stored, seconds, trace_s, error, pareto: false })
}

/// The paper's Table 5 at its photon count: ray tracing alone, photon
/// mapping without dispersion (one band), 3 and 7 bands.
fn table5(
    scene: &PreparedScene,
    plan: &StudyPlan,
    backend: &mut dyn Backend,
    reference: &Reference,
    progress: &mut dyn StudyProgress,
) -> Result<Vec<Table5Row>> {
    let methods: [(&str, f64, BandSpec, u32); 4] = [
        ("ray tracing", 5.0, BandSpec::Paper7, 0),
        ("photon mapping without dispersion", 4.6, BandSpec::Physical(1), plan.table5_photons),
        ("3 bands (paper3)", 1.7, BandSpec::Paper3, plan.table5_photons),
        ("7 bands (paper7)", 0.8, BandSpec::Paper7, plan.table5_photons),
    ];
    let mut rows = Vec::new();
    for (method, paper_fps, bands, photons) in methods {
        let setting = series(method, bands, WavelengthSampling::Split, Estimator::Paper);
        // Best of three: these are short runs, easily disturbed.
        let mut best: Option<StudyRow> = None;
        for _ in 0..3 {
            let row = measure(scene, &setting, photons, backend, reference, false)?;
            if best.as_ref().is_none_or(|b| row.total_s() < b.total_s()) {
                best = Some(row);
            }
        }
        let best = best.expect("three runs");
        rows.push(Table5Row { method, paper_fps, seconds: best.total_s(), delta_e: best.error.delta_e });
        progress.step(&format!("Table 5: {method}"));
    }
    Ok(rows)
}
