//! The real binary on a folder of bad scene files (`tests/bad-scenes/`):
//! each gets its message (file, line, key, reason), exit code 2, and no
//! output file, not even a temporary one.

use std::path::Path;
use std::process::Command;

/// What `prismatic render FILE` must say about each file, after "FILE:".
const EXPECTED: &[(&str, &str)] = &[
    ("bad-outside-ior", "16: material.glass.outside_ior: an index of refraction must be between 1 and 5, got 0.5"),
    ("empty", "1: camera: is required but missing"),
    ("inf-power", "8: light[0].power: must be a finite number, got inf"),
    ("missing-material", "17: object[0].material: is required but missing"),
    ("nan-radius", "27: object[1].radius: must be a finite number, got NaN"),
    ("negative-radius", "2: render.radius: must be greater than 0, got -0.1"),
    ("not-toml-at-all", "1: TOML syntax error"),
    ("open-dielectric", "19: object[0].material: dielectric 'glass' needs a closed shape"),
    ("photons-beyond-memory", "2: render.photons: 200000000 white photons would not fit in memory"),
    ("syntax-error", "23: TOML syntax error: unclosed array table"),
    ("too-many-bands", "2: render.bands: must be \"paper3\", \"paper7\" or 1 to 256, got 300"),
    ("too-many-photons", "2: render.photons: must be between 0 and 4294967295, got 5000000000"),
    ("unknown-glass", "15: material.glass.ior: unknown glass \"unobtainium\""),
    ("unknown-key", "28: object[1].colour: unknown key"),
    ("unknown-material", "19: object[0].material: unknown material \"marble\""),
    (
        "unknown-photon-sequence",
        "3: render.photon_sequence: unknown photon sequence \"halton\"; expected sobol or random",
    ),
    ("unknown-view-paths", "3: render.view_paths: unknown view paths \"jittered\"; expected centre, hero or sampled"),
    ("unknown-white-point", "3: render.white_point: unknown white point \"D50\"; expected E or D65"),
    ("wrong-type", "2: render.photons: must be a whole number, got string"),
    ("zero-bands", "2: render.bands: must be \"paper3\", \"paper7\" or 1 to 256, got 0"),
    ("zero-neighbours", "3: render.neighbours: must be at least 1, got 0"),
    ("zero-normal", "21: object[0].normal: must not be a zero-length vector"),
];

#[test]
fn every_bad_scene_file_gets_its_message_exit_code_2_and_no_output() {
    let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/bad-scenes");
    let mut files: Vec<String> = std::fs::read_dir(&folder)
        .unwrap()
        .map(|e| e.unwrap().path().file_stem().unwrap().to_string_lossy().into_owned())
        .collect();
    files.sort();
    let listed: Vec<&str> = EXPECTED.iter().map(|(f, _)| *f).collect();
    assert_eq!(files, listed, "every file in {} needs its expected message here", folder.display());
    for (stem, message) in EXPECTED {
        let file = folder.join(format!("{stem}.toml"));
        for command in ["render", "photons"] {
            let out = tempfile::tempdir().unwrap();
            let o = Command::new(env!("CARGO_BIN_EXE_prismatic"))
                .args([command, file.to_str().unwrap(), "-o", "out"])
                .current_dir(out.path())
                .output()
                .expect("the binary runs");
            let stderr = String::from_utf8_lossy(&o.stderr);
            assert_eq!(o.status.code(), Some(2), "{stem} ({command}): exit code, stderr: {stderr}");
            let expected = format!("{}:{message}", file.display());
            assert!(stderr.contains(&expected), "{stem} ({command}): expected «{expected}», got: {stderr}");
            assert!(!stderr.contains("panicked"), "{stem} ({command}): {stderr}");
            let left: Vec<_> = std::fs::read_dir(out.path()).unwrap().collect();
            assert!(left.is_empty(), "{stem} ({command}): left files behind: {left:?}");
        }
    }
}
