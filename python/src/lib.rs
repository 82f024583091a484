//! `prismatic._prismatic`, the Python module over the render protocol: a
//! scene (built-in name, file or TOML text) and keyword settings in, the
//! CLI's job run with the GIL released, numpy arrays, partial renders as
//! bytes and their exact merge out. `prismatic/__init__.py` is its face.

use numpy::{PyArray1, PyArrayMethods};
use prismatic_cli::backends::{self, BackendChoice};
use prismatic_cli::environment_file::EnvironmentArgs;
use prismatic_cli::load_scene;
use prismatic_cli::partial::Partial;
use prismatic_cli::render_job::{JobProgress, RenderJob, finite_image};
use prismatic_cli::scene_file::{self, SceneDocument, SceneFileError};
use prismatic_cli::settings::{SettingValue, Settings, SettingsSource};
use prismatic_core::{Image, NoProgress, PreparedScene, Progress, Stage};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyBytes, PyDict, PyFloat, PyInt};
use std::path::Path;
use std::time::Duration;

pyo3::create_exception!(
    _prismatic,
    SceneError,
    PyValueError,
    "A scene, setting or partial render that cannot be used: `file`, `line`, `key` and `reason` say where and why."
);
pyo3::create_exception!(
    _prismatic,
    RenderError,
    PyRuntimeError,
    "A render that failed (no adapter, a device lost, …)."
);

/// What went wrong, before it becomes a Python exception.
enum Failure {
    Scene(SceneFileError),
    Render(anyhow::Error),
    Python(PyErr),
}

impl From<SceneFileError> for Failure {
    fn from(e: SceneFileError) -> Self {
        Failure::Scene(e)
    }
}

impl From<anyhow::Error> for Failure {
    fn from(e: anyhow::Error) -> Self {
        match e.downcast::<SceneFileError>() {
            Ok(scene) => Failure::Scene(scene),
            Err(e) => match e.downcast::<Interrupted>() {
                Ok(Interrupted(err)) => Failure::Python(err),
                Err(e) => Failure::Render(e),
            },
        }
    }
}

impl From<prismatic_core::BackendError> for Failure {
    fn from(e: prismatic_core::BackendError) -> Self {
        Failure::Render(e.into())
    }
}

impl From<Failure> for PyErr {
    fn from(f: Failure) -> PyErr {
        match f {
            Failure::Scene(e) => Python::attach(|py| {
                let err = SceneError::new_err(e.to_string());
                let value = err.value(py);
                // Attributes on a fresh exception object cannot fail to set.
                let _ = value.setattr("file", &e.file);
                let _ = value.setattr("line", e.line);
                let _ = value.setattr("key", &e.key);
                let _ = value.setattr("reason", &e.reason);
                err
            }),
            Failure::Render(e) => RenderError::new_err(format!("{e:#}")),
            Failure::Python(e) => e,
        }
    }
}

/// A Python exception raised in a progress callback, carried through the job.
#[derive(Debug)]
struct Interrupted(PyErr);

impl std::fmt::Display for Interrupted {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "interrupted: {}", self.0)
    }
}

impl std::error::Error for Interrupted {}

/// A scene as the Python layer passes it: a built-in name or a path, or
/// TOML text (`is_text`) with the file it was read from, if any (named in
/// errors; mesh paths in it are relative to that file's folder).
#[derive(FromPyObject)]
struct Source(String, bool, Option<String>);

impl Source {
    fn document(&self) -> Result<SceneDocument, SceneFileError> {
        let Source(scene, is_text, origin) = self;
        match (is_text, origin) {
            (false, _) => load_scene(scene),
            (true, None) => scene_file::parse(scene, "<text>", None),
            (true, Some(file)) => scene_file::parse(scene, file, Path::new(file).parent()),
        }
    }
}

/// A keyword setting that is not valid.
fn bad_setting(key: &str, reason: impl Into<String>) -> SceneFileError {
    SceneFileError { file: "keyword arguments".into(), line: None, key: key.into(), reason: reason.into() }
}

/// A setting's value parsed by name, or the reason it is not one.
fn named<T>(key: &str, parsed: Result<T, String>) -> Result<T, Failure> {
    parsed.map_err(|reason| bad_setting(key, reason).into())
}

/// A keyword's value as the settings read it: Python's bool, int and
/// float by type (bool first: it is an int in Python), anything else by
/// its text.
fn setting_value(v: &Bound<'_, PyAny>) -> Result<SettingValue, Failure> {
    if v.is_instance_of::<PyBool>() {
        return Ok(SettingValue::Bool(v.extract().map_err(Failure::Python)?));
    }
    if v.is_instance_of::<PyInt>() {
        // An int beyond i64 is no setting's value: its text says why.
        if let Ok(n) = v.extract::<i64>() {
            return Ok(SettingValue::Int(n));
        }
    } else if v.is_instance_of::<PyFloat>() {
        return Ok(SettingValue::Float(v.extract().map_err(Failure::Python)?));
    }
    Ok(SettingValue::Text(v.str().map_err(Failure::Python)?.to_string()))
}

/// The render settings and backend from the keyword dictionary the Python
/// layer passes (names as the CLI's flags, values already checked for type).
fn settings(kw: Option<&Bound<'_, PyDict>>) -> Result<(Settings, EnvironmentArgs, BackendChoice), Failure> {
    let mut s = Settings::default();
    let mut environment = EnvironmentArgs::default();
    let mut backend = BackendChoice::Auto;
    let Some(kw) = kw else { return Ok((s, environment, backend)) };
    for (k, v) in kw.iter() {
        let key: String = k.extract().map_err(Failure::Python)?;
        if EnvironmentArgs::NAMES.contains(&key.as_str()) {
            let text = v.str().map(|s| s.to_string()).map_err(Failure::Python)?;
            named(&key, environment.set(&key, &text))?;
            continue;
        }
        if key == "backend" {
            let name = v.str().map(|s| s.to_string()).map_err(Failure::Python)?;
            let choice = <BackendChoice as clap::ValueEnum>::from_str(&name, true);
            let expected = |_| format!("unknown backend \"{name}\"; expected reference, cpu, gpu or auto");
            backend = named(&key, choice.map_err(expected))?;
            continue;
        }
        s.set(&key, &setting_value(&v)?).map_err(|reason| bad_setting(&key, reason))?;
    }
    Ok((s, environment, backend))
}

/// The scene with the settings applied, validated and prepared.
fn prepare(
    source: &Source,
    kw: Option<&Bound<'_, PyDict>>,
) -> Result<(PreparedScene, SceneDocument, BackendChoice), Failure> {
    let (settings, environment, backend) = settings(kw)?;
    let doc = environment.apply(source.document()?, SettingsSource::Keywords)?;
    let prepared = settings.prepare(doc.clone(), SettingsSource::Keywords)?;
    Ok((prepared, doc, backend))
}

/// Passes progress to a Python callable `(done, total)` (total `None`
/// when only a time budget ends the render); an exception it raises, or
/// a signal (Ctrl-C), stops the render after the pass.
struct PythonProgress {
    callback: Option<Py<PyAny>>,
    raised: Option<PyErr>,
}

impl Progress for PythonProgress {
    fn advance(&mut self, _: Stage, _: u64, _: u64) {}
}

impl JobProgress for PythonProgress {
    fn pass_done(&mut self, done: u32, total: Option<u32>, _: Duration, _: Option<Duration>) {
        if let Some(f) = &self.callback {
            self.raised = Python::attach(|py| f.call1(py, (done, total)).err());
        }
    }

    fn check(&mut self) -> anyhow::Result<()> {
        let raised = self.raised.take().map_or_else(|| Python::attach(|py| py.check_signals()), Err);
        raised.map_err(|e| Interrupted(e).into())
    }
}

/// Runs passes `passes` (or the scene's, or until `time` runs out) and
/// returns the render's partial (its base, sums, backend and fingerprint).
fn run(
    py: Python<'_>,
    scene: &PreparedScene,
    backend: BackendChoice,
    passes: Option<(u32, u32)>,
    time: Option<f64>,
    progress: Option<Py<PyAny>>,
) -> Result<Partial, Failure> {
    let passes = match passes {
        Some((a, b)) if a < b => a..b,
        Some((a, b)) => return Err(bad_setting("passes", format!("an empty range {a}..{b}")).into()),
        None if time.is_some() => 0..u32::MAX,
        None => 0..scene.scene.render.passes,
    };
    let time = match time {
        Some(t) if t.is_finite() && t > 0.0 => Some(Duration::from_secs_f64(t)),
        Some(t) => return Err(bad_setting("time", format!("must be a number of seconds > 0, got {t}")).into()),
        None => None,
    };
    let job = RenderJob { passes, time, save_every: None };
    py.detach(|| {
        let mut selected = backends::select(backend)?;
        let mut render = selected.backend.prepare(scene)?;
        let mut progress = PythonProgress { callback: progress, raised: None };
        let rendered = job.run(render.as_mut(), &mut progress, &mut |_, _, _| Ok(()))?;
        Ok(Partial::of(render.as_ref(), rendered.base, rendered.sums))
    })
}

/// An image as a float32 array (height, width, 3), linear RGB.
fn array<'py>(py: Python<'py>, image: &Image) -> PyResult<Bound<'py, PyAny>> {
    let data: Vec<f32> = image.pixels.iter().flat_map(|p| p.to_array()).collect();
    let flat = PyArray1::from_vec(py, data);
    Ok(flat.reshape([image.height as usize, image.width as usize, 3])?.into_any())
}

/// Renders `scene` and returns its image (float32, (height, width, 3), linear RGB).
#[pyfunction]
#[pyo3(signature = (source, settings=None, passes=None, time=None, progress=None))]
fn render<'py>(
    py: Python<'py>,
    source: Source,
    settings: Option<&Bound<'py, PyDict>>,
    passes: Option<(u32, u32)>,
    time: Option<f64>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyAny>> {
    let (scene, _, backend) = prepare(&source, settings)?;
    let partial = run(py, &scene, backend, passes, time, progress)?;
    let image = finite_image(&partial.base, &partial.sums).map_err(Failure::from)?;
    array(py, &image)
}

/// Renders passes `a..b` of `scene` and returns the partial render's bytes
/// (the format of `prismatic render --partial`).
#[pyfunction]
#[pyo3(signature = (source, passes, settings=None, progress=None))]
fn render_partial<'py>(
    py: Python<'py>,
    source: Source,
    passes: (u32, u32),
    settings: Option<&Bound<'py, PyDict>>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyBytes>> {
    let (scene, _, backend) = prepare(&source, settings)?;
    let partial = run(py, &scene, backend, Some(passes), None, progress)?;
    let bytes = py.detach(|| partial.to_bytes());
    Ok(PyBytes::new(py, &bytes))
}

/// Partial renders merged as they come: the sums of all their passes,
/// kept here so that each merge reads only the new partial.
#[pyclass(module = "prismatic._prismatic")]
#[derive(Default)]
struct Merge {
    merged: Option<Partial>,
    added: usize,
}

#[pymethods]
impl Merge {
    #[new]
    fn new() -> Self {
        Merge::default()
    }

    /// Adds a partial render's bytes; partials of another scene, settings,
    /// size or backend, and passes already added, raise `SceneError`.
    fn add(&mut self, py: Python<'_>, partial: &[u8]) -> PyResult<()> {
        let name = format!("partials[{}]", self.added);
        let merged = &mut self.merged;
        py.detach(|| -> Result<(), SceneFileError> {
            let p = read_partial(partial, &name)?;
            match merged {
                None => *merged = Some(p),
                Some(m) => m.merge(&p, &name)?,
            }
            Ok(())
        })
        .map_err(Failure::from)?;
        self.added += 1;
        Ok(())
    }

    /// The pass ranges merged so far.
    fn passes(&self) -> Vec<(u32, u32)> {
        self.merged.as_ref().map_or_else(Vec::new, |m| m.sums.passes.clone())
    }

    /// The image of the passes merged so far (float32, (height, width, 3), linear RGB).
    fn image<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let m = self
            .merged
            .as_ref()
            .ok_or_else(|| Failure::from(bad_setting("partials", "no partial renders to merge")))?;
        let image = finite_image(&m.base, &m.sums).map_err(Failure::from)?;
        array(py, &image)
    }

    /// The merged partial render's bytes (the format of `render --partial`).
    fn to_bytes<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyBytes>> {
        let m = self
            .merged
            .as_ref()
            .ok_or_else(|| Failure::from(bad_setting("partials", "no partial renders to merge")))?;
        let bytes = py.detach(|| m.to_bytes());
        Ok(PyBytes::new(py, &bytes))
    }
}

fn read_partial(bytes: &[u8], name: &str) -> Result<Partial, SceneFileError> {
    Partial::from_bytes(bytes).map_err(|reason| SceneFileError {
        file: name.into(),
        line: None,
        key: String::new(),
        reason,
    })
}

/// The caustic photons of pass `pass_` as columns: the CSV of `prismatic photons`.
#[pyfunction]
#[pyo3(signature = (source, pass_=0, settings=None))]
fn photons<'py>(
    py: Python<'py>,
    source: Source,
    pass_: u32,
    settings: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let (scene, doc, backend) = prepare(&source, settings)?;
    let map = py.detach(|| -> Result<_, Failure> {
        let mut selected = backends::select(backend)?;
        let mut render = selected.backend.prepare(&scene)?;
        Ok(render.photon_map(pass_, &mut NoProgress)?)
    })?;
    let n = map.photons.len();
    let (mut emission, mut band, mut lambda) = (Vec::with_capacity(n), Vec::with_capacity(n), Vec::with_capacity(n));
    let (mut pos, mut dir, mut power) =
        ([(); 3].map(|_| Vec::with_capacity(n)), [(); 3].map(|_| Vec::with_capacity(n)), Vec::with_capacity(n));
    for p in &map.photons {
        emission.push(p.emission);
        match p.wavelength() {
            Some(lambda_nm) => {
                band.push(i32::from(p.band));
                lambda.push(lambda_nm);
            }
            None => {
                band.push(-1i32);
                lambda.push(f32::NAN);
            }
        }
        let world = (p.pos().as_dvec3() + doc.origin).to_array();
        let d = p.direction().to_array();
        for axis in 0..3 {
            pos[axis].push(world[axis]);
            dir[axis].push(d[axis]);
        }
        power.push(p.flux);
    }
    let columns = PyDict::new(py);
    columns.set_item("emission", PyArray1::from_vec(py, emission))?;
    columns.set_item("band", PyArray1::from_vec(py, band))?;
    columns.set_item("lambda_nm", PyArray1::from_vec(py, lambda))?;
    let [x, y, z] = pos;
    let [dx, dy, dz] = dir;
    for (name, v) in [("x", x), ("y", y), ("z", z)] {
        columns.set_item(name, PyArray1::from_vec(py, v))?;
    }
    for (name, v) in [("dir_x", dx), ("dir_y", dy), ("dir_z", dz)] {
        columns.set_item(name, PyArray1::from_vec(py, v))?;
    }
    columns.set_item("power", PyArray1::from_vec(py, power))?;
    Ok(columns)
}

/// The scene's fingerprint and size after the settings: what partial renders are checked against.
#[pyfunction]
#[pyo3(signature = (source, settings=None))]
fn describe<'py>(
    py: Python<'py>,
    source: Source,
    settings: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let (scene, _, _) = prepare(&source, settings)?;
    let r = &scene.scene.render;
    let d = PyDict::new(py);
    d.set_item("fingerprint", prismatic_cli::partial::fingerprint(&scene))?;
    d.set_item("width", r.width)?;
    d.set_item("height", r.height)?;
    d.set_item("passes", r.passes)?;
    d.set_item("photons", r.photons)?;
    Ok(d)
}

/// The built-in scenes' names.
#[pyfunction]
fn scenes() -> Vec<&'static str> {
    prismatic_cli::builtin::names()
}

/// The module.
#[pymodule]
fn _prismatic(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("SceneError", m.py().get_type::<SceneError>())?;
    m.add("RenderError", m.py().get_type::<RenderError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("SETTINGS", [Settings::NAMES, &EnvironmentArgs::NAMES].concat())?;
    m.add_class::<Merge>()?;
    for f in [
        wrap_pyfunction!(render, m)?,
        wrap_pyfunction!(render_partial, m)?,
        wrap_pyfunction!(photons, m)?,
        wrap_pyfunction!(describe, m)?,
        wrap_pyfunction!(scenes, m)?,
    ] {
        m.add_function(f)?;
    }
    Ok(())
}
