//! The converged image a study measures error against (the study's
//! "reference", not the scalar reference backend): physically based
//! bands at high N with hero wavelengths (the true spectrum, not N lines),
//! light tracing for the caustics the camera sees directly and the
//! renderer's own progressive photon mapping behind mirrors and glass (a
//! backend's render, per-point radii), Sobol photons, until doubling the
//! passes no longer changes the image; cached on disk by the hash of
//! everything it depends on.

use super::metrics::{StripeSums, caustic_mask, mean_delta_e};
use crate::output::{read_exr, write_exr};
use anyhow::{Context, Result};
use prismatic_core::model::scene::DEFAULT_ALPHA;
use prismatic_core::{
    Backend, BandSpec, Estimator, Image, NoProgress, PhotonSequence, PreparedScene, ViewPaths, WavelengthSampling,
};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Bump when the tracer or renderer changes what a reference looks like, so
/// that cached references are rebuilt.
const REFERENCE_VERSION: &str = "prismatic-reference 4";

/// How a reference is made.
#[derive(Clone, Debug, PartialEq)]
pub struct ReferenceSpec {
    /// Physically based bands.
    pub bands: u16,
    /// How photons sample the spectrum.
    pub wavelengths: WavelengthSampling,
    /// Light tracing for the caustics the camera sees directly: unbiased,
    /// so the reference converges to the caustic, not to a blurred one.
    pub light_tracing: bool,
    /// Where the photons' emission and wavelength numbers come from.
    pub sequence: PhotonSequence,
    /// How view rays sample the pixels: centre rays, exact for what each
    /// pixel's centre sees (every band through glass: at 64 bands their
    /// quantisation lies below the convergence threshold), with no view
    /// noise to wait out.
    pub view_paths: ViewPaths,
    /// White photons per pass.
    pub photons_per_pass: u32,
    /// Photon paths a first radius holds.
    pub neighbours: u32,
    /// Radius shrink per pass (Hachisuka's α).
    pub alpha: f32,
    /// Converged when the passes' mean after 2k passes differs from the mean
    /// after k passes by less than this mean ΔE00 over the caustic pixels.
    pub threshold: f64,
    /// Stop here even if not converged (the report says so).
    pub max_passes: u32,
}

impl ReferenceSpec {
    /// The full study's reference: 250k white photons a pass, each
    /// first radius holding 16 photon paths.
    pub fn full() -> Self {
        ReferenceSpec {
            bands: 64,
            wavelengths: WavelengthSampling::Hero,
            light_tracing: true,
            sequence: PhotonSequence::Sobol,
            view_paths: ViewPaths::Centre,
            photons_per_pass: 250_000,
            neighbours: 16,
            alpha: DEFAULT_ALPHA,
            threshold: 0.15,
            max_passes: 256,
        }
    }

    /// The quick study's (small images, a test in CI: seconds, not minutes).
    pub fn quick() -> Self {
        ReferenceSpec {
            bands: 64,
            wavelengths: WavelengthSampling::Hero,
            light_tracing: true,
            sequence: PhotonSequence::Sobol,
            view_paths: ViewPaths::Centre,
            photons_per_pass: 100_000,
            neighbours: 16,
            alpha: DEFAULT_ALPHA,
            threshold: 0.2,
            max_passes: 128,
        }
    }
}

/// A finished reference.
pub struct Reference {
    /// The converged image.
    pub image: Image,
    /// The same scene without caustic photons (direct light only).
    pub without_caustics: Image,
    /// The pixels the caustic touches.
    pub mask: Vec<bool>,
    /// Flux-weighted stripe positions per band, over all passes.
    pub stripes: StripeSums,
    /// Passes run.
    pub passes: u32,
    /// ΔE00 between the last two checkpoints.
    pub last_change: f64,
    /// Whether `last_change` fell below the threshold.
    pub converged: bool,
    /// Seconds it took to build.
    pub seconds: f64,
    /// Where it is cached.
    pub dir: PathBuf,
}

/// The scene a reference renders: `scene` with the reference's bands,
/// estimator and photons per pass (its radius is pass 1's).
pub fn reference_scene(scene: &PreparedScene, spec: &ReferenceSpec) -> Result<PreparedScene> {
    let mut s = scene.scene.clone();
    s.render.bands = BandSpec::Physical(spec.bands);
    s.render.estimator = Estimator::Density;
    s.render.wavelengths = spec.wavelengths;
    s.render.light_tracing = spec.light_tracing;
    s.render.photon_sequence = spec.sequence;
    s.render.view_paths = spec.view_paths;
    s.render.photons = spec.photons_per_pass;
    s.render.neighbours = spec.neighbours;
    s.render.alpha = spec.alpha;
    Ok(PreparedScene::new(s)?)
}

/// FNV-1a (64 bit) of everything the reference depends on.
pub fn content_hash(scene: &PreparedScene, spec: &ReferenceSpec) -> u64 {
    let text = format!("{REFERENCE_VERSION}\n{spec:?}\n{:?}", scene.scene);
    text.bytes().fold(0xcbf2_9ce4_8422_2325, |h, b| (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3))
}

/// Loads the cached reference for `scene` (named `name`), or builds and
/// caches it (always builds when `rebuild`); with `stripes`, it also sums
/// the band stripes of its photons. `report` hears about each checkpoint.
#[allow(clippy::too_many_arguments)]
pub fn load_or_build(
    name: &str,
    scene: &PreparedScene,
    spec: &ReferenceSpec,
    stripes: bool,
    cache: &Path,
    rebuild: bool,
    backend: &mut dyn Backend,
    report: &mut dyn FnMut(&str),
) -> Result<Reference> {
    let ref_scene = reference_scene(scene, spec)?;
    let dir = cache.join(format!("{}-{:016x}", sanitize(name), content_hash(&ref_scene, spec)));
    if !rebuild && let Some(r) = load(&dir, &ref_scene)? {
        report(&format!("reference: cached in {}", dir.display()));
        return Ok(r);
    }
    let r = build(&ref_scene, spec, stripes, dir, backend, report)?;
    save(&r, &ref_scene)?;
    Ok(r)
}

fn build(
    scene: &PreparedScene,
    spec: &ReferenceSpec,
    stripes_wanted: bool,
    dir: PathBuf,
    backend: &mut dyn Backend,
    report: &mut dyn FnMut(&str),
) -> Result<Reference> {
    let t0 = Instant::now();
    let tone_map = scene.scene.render.tone_map;
    let mut render = backend.prepare(scene)?;
    let without_caustics = render.base()?;
    let mut stripes = StripeSums::new(&scene.bands);
    let mut checkpoint: Option<Image> = None;
    let (mut last_change, mut converged) = (f64::INFINITY, false);
    for k in 1..=spec.max_passes {
        render.run_pass(k - 1, &mut NoProgress)?;
        if stripes_wanted {
            // The pass's photons again, for their positions (the pass's own
            // map stays inside the backend).
            stripes.add(&render.photon_map(k - 1, &mut NoProgress)?);
        }
        if k.is_power_of_two() {
            let image = render.image()?;
            if let Some(previous) = &checkpoint {
                let mask = caustic_mask(&image, &without_caustics, tone_map);
                last_change = mean_delta_e(&image, previous, &mask, tone_map);
                report(&format!("reference: {k} passes, ΔE00 {last_change:.3} from {} passes", k / 2));
                if last_change < spec.threshold {
                    converged = true;
                    break;
                }
            }
            checkpoint = Some(image);
        }
    }
    let image = render.image()?;
    let mask = caustic_mask(&image, &without_caustics, tone_map);
    Ok(Reference {
        image,
        without_caustics,
        mask,
        stripes,
        passes: render.stats()?.passes,
        last_change,
        converged,
        seconds: t0.elapsed().as_secs_f64(),
        dir,
    })
}

/// A file-name-safe stem of a scene name or path.
pub fn sanitize(name: &str) -> String {
    let stem = Path::new(name).file_stem().map_or(name.into(), |s| s.to_string_lossy().into_owned());
    stem.chars().map(|c| if c.is_ascii_alphanumeric() || c == '-' || c == '_' { c } else { '_' }).collect()
}

/// Writes the reference into its directory: a temporary directory first,
/// renamed into place, so a cache entry is whole or absent.
fn save(r: &Reference, scene: &PreparedScene) -> Result<()> {
    let parent = r.dir.parent().context("reference directory has a parent")?;
    std::fs::create_dir_all(parent).with_context(|| format!("{}: cannot create", parent.display()))?;
    let temp = parent.join(format!(".tmp-{}", std::process::id()));
    std::fs::create_dir_all(&temp).with_context(|| format!("{}: cannot create", temp.display()))?;
    for (name, image) in [("reference.exr", &r.image), ("no-caustics.exr", &r.without_caustics)] {
        let path = temp.join(name);
        let file = std::fs::File::create(&path).with_context(|| format!("{}: cannot create", path.display()))?;
        let mut w = std::io::BufWriter::new(file);
        write_exr(&mut w, image)?;
        std::io::Write::flush(&mut w).with_context(|| format!("{}: cannot write", path.display()))?;
    }
    let mut stripes = String::from("lo_nm,hi_nm,flux,moment_x,moment_y,moment_z\n");
    for ((lo, hi), f, m) in &r.stripes.bands {
        writeln!(stripes, "{lo},{hi},{f:e},{:e},{:e},{:e}", m.x, m.y, m.z)?;
    }
    std::fs::write(temp.join("stripes.csv"), stripes)?;
    let info = format!(
        "passes = {}\nlast_change_delta_e = {}\nconverged = {}\nseconds = {:.1}\nbands = {}\nphotons_per_pass = {}\n",
        r.passes,
        if r.last_change.is_finite() { r.last_change } else { -1.0 },
        r.converged,
        r.seconds,
        scene.bands.len(),
        scene.scene.render.photons
    );
    std::fs::write(temp.join("info.toml"), info)?;
    if r.dir.exists() {
        std::fs::remove_dir_all(&r.dir).with_context(|| format!("{}: cannot replace", r.dir.display()))?;
    }
    std::fs::rename(&temp, &r.dir).with_context(|| format!("{}: cannot move into place", r.dir.display()))?;
    Ok(())
}

/// The cached reference in `dir`, or `None` when there is none.
fn load(dir: &Path, scene: &PreparedScene) -> Result<Option<Reference>> {
    if !dir.join("info.toml").exists() {
        return Ok(None);
    }
    let bad = |what: &str| format!("{}: broken cached reference ({what}); rebuild it with --rebuild", dir.display());
    let image = read_exr(&dir.join("reference.exr")).with_context(|| bad("reference.exr"))?;
    let without_caustics = read_exr(&dir.join("no-caustics.exr")).with_context(|| bad("no-caustics.exr"))?;
    let info: toml::Table =
        std::fs::read_to_string(dir.join("info.toml"))?.parse().with_context(|| bad("info.toml"))?;
    let mut stripes = StripeSums::default();
    for line in std::fs::read_to_string(dir.join("stripes.csv"))?.lines().skip(1) {
        let v: Vec<f64> =
            line.split(',').map(str::parse).collect::<Result<_, _>>().with_context(|| bad("stripes.csv"))?;
        anyhow::ensure!(v.len() == 6, bad("stripes.csv"));
        stripes.bands.push(((v[0] as f32, v[1] as f32), v[2], glam::DVec3::new(v[3], v[4], v[5])));
    }
    let r = &scene.scene.render;
    anyhow::ensure!((image.width, image.height) == (r.width, r.height), bad("image size"));
    let mask = caustic_mask(&image, &without_caustics, r.tone_map);
    Ok(Some(Reference {
        image,
        without_caustics,
        mask,
        stripes,
        passes: info.get("passes").and_then(|v| v.as_integer()).unwrap_or(0) as u32,
        last_change: info.get("last_change_delta_e").and_then(|v| v.as_float()).unwrap_or(-1.0),
        converged: info.get("converged").and_then(|v| v.as_bool()).unwrap_or(false),
        seconds: info.get("seconds").and_then(|v| v.as_float()).unwrap_or(0.0),
        dir: dir.to_path_buf(),
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_cache_key_changes_with_anything_the_reference_depends_on() {
        let doc = crate::load_scene("sphere").unwrap();
        let scene = PreparedScene::new(doc.scene.clone()).unwrap();
        let spec = ReferenceSpec::quick();
        let key =
            |scene: &PreparedScene, spec: &ReferenceSpec| content_hash(&reference_scene(scene, spec).unwrap(), spec);
        let base = key(&scene, &spec);
        assert_eq!(base, key(&scene, &spec), "stable");
        // The study's own settings do not matter (the reference sets its own)...
        let mut other = doc.scene.clone();
        other.render.bands = BandSpec::Paper3;
        other.render.estimator = Estimator::Paper;
        other.render.light_tracing = !other.render.light_tracing;
        other.render.photon_sequence = PhotonSequence::Random;
        assert_eq!(base, key(&PreparedScene::new(other).unwrap(), &spec));
        // ...but the scene, the image and the reference's own settings do.
        let mut moved = doc.scene.clone();
        moved.lights[0] = match moved.lights[0].clone() {
            prismatic_core::Light::Spot { position, direction, cone_deg, power, .. } => prismatic_core::Light::Spot {
                position,
                direction,
                cone_deg,
                inner_cone_deg: cone_deg,
                power: power * 1.01,
                spectrum: Default::default(),
                range: None,
            },
            other => other,
        };
        assert_ne!(base, key(&PreparedScene::new(moved).unwrap(), &spec));
        let mut wider = doc.scene.clone();
        wider.render.width += 1;
        assert_ne!(base, key(&PreparedScene::new(wider).unwrap(), &spec));
        assert_ne!(base, key(&scene, &ReferenceSpec { threshold: 0.1, ..spec.clone() }));
        assert_ne!(base, key(&scene, &ReferenceSpec { neighbours: 8, ..spec.clone() }));
        assert_ne!(base, key(&scene, &ReferenceSpec { light_tracing: false, ..spec.clone() }));
    }
}
