//! Parity checks between backends: photon maps and images compared under
//! the conformance suite's rules ([`prismatic_conformance::compare`]); on
//! failure both sides are written to `parity-failures/<case>/` (git-ignored)
//! and the message names the folder.

pub use prismatic_conformance::compare::{ParityReport, compare_images, compare_maps, compare_maps_allowing};
use prismatic_core::{Image, PhotonMap, PreparedScene};
use std::path::PathBuf;

/// One backend's output for a scene.
pub struct Output {
    /// Backend name, for file names.
    pub backend: &'static str,
    /// Its photon map.
    pub map: PhotonMap,
    /// Its image.
    pub image: Image,
}

/// Compares `got` with `expected` on `scene`; on failure writes both photon
/// maps (CSV) and images (PNG) to `parity-failures/<case>/` and panics
/// naming the folder.
pub fn assert_parity(case: &str, scene: &PreparedScene, expected: &Output, got: &Output) -> ParityReport {
    let maps = compare_maps(&expected.map, &got.map, scene.bands.len());
    let images = compare_images(&expected.image, &got.image);
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
            let _ = prismatic_cli::output::write_png(&mut w, &o.image, scene.scene.render.tone_map);
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
