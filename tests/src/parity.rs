//! Parity checks between backends: photon maps and images compared under
//! the conformance suite's rules ([`prismatic_conformance::compare`]); on
//! failure both sides are written to `parity-failures/<case>/` (git-ignored)
//! and the message names the folder.

pub use prismatic_conformance::compare::{ParityReport, compare_images, compare_maps};
use prismatic_conformance::tolerance::Tolerance;
use prismatic_core::{Arithmetic, Backend, Image, PhotonMap, PreparedScene};
use std::path::PathBuf;

/// One backend's output for a scene.
pub struct Output {
    /// Backend name, for file names.
    pub backend: &'static str,
    /// How the backend rounds (which tolerances apply).
    pub arithmetic: Arithmetic,
    /// Its photon map.
    pub map: PhotonMap,
    /// Its image.
    pub image: Image,
}

impl Output {
    /// The paper's frame on `backend` ([`crate::backends::frame`]).
    pub fn frame(backend: &mut dyn Backend, scene: &PreparedScene) -> Output {
        let (map, image) = crate::backends::frame(backend, scene);
        Output { backend: backend.name(), arithmetic: backend.arithmetic(), map, image }
    }
}

/// Compares `got` with `expected` on `scene` (strictly unless either side's
/// arithmetic is relaxed); on failure writes both photon maps (CSV) and
/// images (PNG) to `parity-failures/<case>/` and panics naming the folder.
pub fn assert_parity(case: &str, scene: &PreparedScene, expected: &Output, got: &Output) -> ParityReport {
    let relaxed = [expected, got].iter().any(|o| o.arithmetic == Arithmetic::Relaxed);
    let tol = Tolerance::of(if relaxed { Arithmetic::Relaxed } else { Arithmetic::Strict });
    let maps = compare_maps(&expected.map, &got.map, scene.bands.len(), tol);
    let image_tol = if scene.plan.rough_gathers { tol.with_rough_gathers() } else { tol };
    let images = compare_images(&expected.image, &got.image, image_tol);
    match (maps, images) {
        (Ok(report), Ok(_)) => report,
        (maps, images) => {
            let dir = write_failure(case, scene, &[expected, got]);
            panic!(
                "{case}: {} differs from {}: photon maps: {}; images: {}. Both sides written to {}",
                got.backend,
                expected.backend,
                maps.err().unwrap_or_else(|| "ok".into()),
                images.err().unwrap_or_else(|| "ok".into()),
                dir.display()
            );
        }
    }
}

fn write_failure(case: &str, scene: &PreparedScene, outputs: &[&Output]) -> PathBuf {
    let dir = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../parity-failures")).join(case);
    let _ = std::fs::create_dir_all(&dir);
    let dir = std::fs::canonicalize(&dir).unwrap_or(dir);
    for o in outputs {
        if let Ok(file) = std::fs::File::create(dir.join(format!("{}.csv", o.backend))) {
            let mut w = std::io::BufWriter::new(file);
            let _ = prismatic_cli::output::write_photon_csv(&mut w, &o.map, glam::DVec3::ZERO);
        }
        if let Ok(file) = std::fs::File::create(dir.join(format!("{}.png", o.backend))) {
            let mut w = std::io::BufWriter::new(file);
            let _ = prismatic_cli::output::write_png(&mut w, &o.image, scene.scene.render.display());
        }
    }
    dir
}

/// Photons a pass for a built-in scene in the parity tests: enough for a
/// caustic in every band at 96×96 (the sphere's and the rainbow's are
/// spread over more of the image), few enough for the scalar reference.
pub fn parity_photons(name: &str) -> u32 {
    match name {
        "rainbow" => 60_000,
        "sphere" | "caustic" | "spectrum" => 30_000,
        _ => 4_000,
    }
}

/// Built-in scenes at 96×96 lit by coloured lights, for the parity tests:
/// `sphere` with the default settings under a 2700 K spot and a white
/// point light (coloured and white photons in one pass) with the D65
/// white point (every channel of the view, splats and gathers scaled by
/// the white balance), `prism` with a
/// mercury lamp split into bands and with a fluorescent tube's hero
/// wavelengths, `caustic` (the paper's seven bands) under a sodium lamp,
/// `prism` with a neon lamp's random bands.
pub fn coloured_light_scenes() -> Vec<(String, prismatic_core::PreparedScene)> {
    use prismatic_core::model::spectrum::{Illuminant, Lamp, Spectrum};
    use prismatic_core::{Light, RenderSettings, Vec3, WavelengthSampling};
    let with = |name: &str, spectrum: Spectrum, edit: &dyn Fn(&mut prismatic_core::Scene)| {
        let mut doc = prismatic_cli::load_scene(name).expect("built-in scene");
        let scene = &mut doc.scene;
        (scene.render.width, scene.render.height, scene.render.photons) = (96, 96, parity_photons(name));
        *scene.lights[0].spectrum_mut() = spectrum;
        edit(scene);
        prismatic_core::PreparedScene::new(doc.scene).unwrap_or_else(|e| panic!("{name}: {e}"))
    };
    let defaults = |scene: &mut prismatic_core::Scene| {
        let own = scene.render.clone();
        scene.render = RenderSettings {
            width: own.width,
            height: own.height,
            photons: own.photons,
            radius: own.radius,
            exposure: own.exposure,
            ambient: own.ambient,
            ..RenderSettings::default()
        };
    };
    let sampling = |w: WavelengthSampling| move |scene: &mut prismatic_core::Scene| scene.render.wavelengths = w;
    vec![
        (
            "sphere-2700K-and-white-D65".into(),
            with("sphere", Spectrum::Blackbody { kelvin: 2700.0 }, &|scene| {
                defaults(scene);
                scene.render.white_point = prismatic_core::model::scene::WhitePoint::D65;
                let power = 0.5 * scene.lights[0].power();
                scene.lights.push(Light::Point {
                    position: Vec3::new(1.0, 3.0, 2.0),
                    power,
                    spectrum: Spectrum::default(),
                    range: None,
                });
            }),
        ),
        ("prism-mercury-split".into(), with("prism", Spectrum::Lamp(Lamp::Mercury), &|_| {})),
        ("prism-F11-hero".into(), with("prism", Spectrum::Illuminant(Illuminant::F11), &|scene| defaults(scene))),
        ("caustic-sodium".into(), with("caustic", Spectrum::Lamp(Lamp::Sodium), &|_| {})),
        (
            "prism-neon-random-band".into(),
            with("prism", Spectrum::Lamp(Lamp::Neon), &sampling(WavelengthSampling::RandomBand)),
        ),
    ]
}
