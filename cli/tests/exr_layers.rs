//! An EXR render carries, beside the image, what denoisers and compositors
//! take: the caustic alone, and albedo, normal and depth at the first hit
//! (albedo Fresnel-weighted through glass, as OpenImageDenoise asks).

use exr::prelude::{FlatSamples, ReadChannels, ReadLayers, read};
use std::collections::HashMap;
use std::process::Command;

const SCENE: &str = r#"
[render]
width = 16
height = 16
photons = 20000
passes = 2
ambient = 0

[camera]
position = [0.0, 3.0, 0.0]
look_at = [0.0, 0.0, 0.0]
up = [0.0, 0.0, -1.0]
fov_deg = 30

[[light]]
kind = "point"
position = [0.0, 4.0, 0.5]
power = 100

[material.floor]
kind = "diffuse"
albedo = [0.5, 0.25, 0.125]

[material.sheet]
kind = "dielectric"
ior = 1.5
thin = true

[[object]]
shape = "plane"
material = "floor"
point = [0, 0, 0]
normal = [0, 1, 0]

[[object]]
shape = "disk"
material = "sheet"
center = [0, 1, 0]
normal = [0, 1, 0]
radius = 0.2
"#;

/// Every channel of the EXR at `path`, by name.
fn channels(path: &std::path::Path) -> HashMap<String, Vec<f32>> {
    let image = read().no_deep_data().largest_resolution_level().all_channels().first_valid_layer().all_attributes();
    let image = image.from_file(path).unwrap();
    image
        .layer_data
        .channel_data
        .list
        .into_iter()
        .map(|c| {
            let FlatSamples::F32(v) = c.sample_data else { panic!("{} is not f32", c.name) };
            (c.name.to_string(), v)
        })
        .collect()
}

#[test]
fn an_exr_carries_the_caustic_and_the_features_at_the_first_hit() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("floor.toml");
    std::fs::write(&scene, SCENE).unwrap();
    let out = dir.path().join("out.exr");
    let run = Command::new(env!("CARGO_BIN_EXE_prismatic"))
        .args(["render", scene.to_str().unwrap(), "--backend", "cpu", "-o", out.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let c = channels(&out);
    let mut names: Vec<&str> = c.keys().map(String::as_str).collect();
    names.sort_unstable();
    assert_eq!(
        names,
        [
            "B",
            "G",
            "R",
            "Z",
            "albedo.B",
            "albedo.G",
            "albedo.R",
            "caustic.B",
            "caustic.G",
            "caustic.R",
            "normal.X",
            "normal.Y",
            "normal.Z"
        ]
    );
    // The corner sees the floor: its albedo, the normal up, the depth along the ray.
    let corner = 0;
    assert_eq!([c["albedo.R"][corner], c["albedo.G"][corner], c["albedo.B"][corner]], [0.5, 0.25, 0.125]);
    assert_eq!([c["normal.X"][corner], c["normal.Y"][corner], c["normal.Z"][corner]], [0.0, 1.0, 0.0]);
    assert!(c["Z"][corner] > 3.0 && c["Z"][corner] < 3.3, "{}", c["Z"][corner]);
    // The centre looks through the sheet: the floor's albedo times its
    // transmittance (1 − R)/(1 + R) at normal incidence, plus R_s times the
    // sky above (black); the depth is the sheet's.
    let centre = 8 * 16 + 8;
    let t = (1.0 - 0.04) / (1.0 + 0.04);
    assert!((c["albedo.R"][centre] - 0.5 * t).abs() < 1e-5, "{}", c["albedo.R"][centre]);
    assert!((c["Z"][centre] - 2.0).abs() < 1e-2, "{}", c["Z"][centre]);
    // The caustic is the light that came through the sheet: where the image
    // exceeds its view pass, and nowhere negative.
    assert!(c["caustic.R"].iter().all(|&x| x >= 0.0));
    assert!(c["caustic.R"][centre] > 0.0, "the sheet's light lands under it");
    // Viewers read the image itself.
    let image = prismatic_cli::output::read_exr(&out).unwrap();
    assert_eq!(image.pixels[centre].x, c["R"][centre]);
}
