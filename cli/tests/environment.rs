//! Environments as a user names them: an HDR file (OpenEXR here) or the
//! studio in a scene file, the `--environment` flags, and clear errors for
//! what cannot be used.

use prismatic_core::model::scene::Light;
use std::path::Path;

/// A 16 × 8 equirectangular map: 2 above the horizon, 0.5 below, linear.
fn write_map(path: &Path) {
    let data: Vec<f32> = (0..16 * 8).flat_map(|i| if i / 16 < 4 { [2.0, 2.0, 2.0] } else { [0.5, 0.5, 0.5] }).collect();
    image::Rgb32FImage::from_raw(16, 8, data).unwrap().save(path).unwrap();
}

const SCENE: &str = r#"
[render]
width = 24
height = 16
photons = 2000
passes = 1

[camera]
position = [0.0, 1.0, 4.0]
look_at = [0.0, 0.5, 0.0]

[material.floor]
kind = "diffuse"

[[object]]
shape = "plane"
material = "floor"
point = [0, 0, 0]
normal = [0, 1, 0]
"#;

#[test]
fn a_scene_names_its_environment_by_file_or_as_the_studio() {
    let dir = tempfile::tempdir().unwrap();
    write_map(&dir.path().join("sky.exr"));
    let text =
        format!("{SCENE}\n[[light]]\nkind = \"environment\"\nmap = \"sky.exr\"\nstrength = 3\nrotation_deg = 45\n");
    let doc = prismatic_cli::scene_file::parse(&text, "scene.toml", Some(dir.path())).unwrap();
    let [Light::Environment { map, strength, rotation_deg, .. }] = doc.scene.lights.as_slice() else { panic!() };
    assert_eq!((map.width, map.height, *strength, *rotation_deg), (16, 8, 3.0, 45.0));
    assert_eq!((map.texels[0].x, map.texels[16 * 7].x), (2.0, 0.5));
    let studio = format!("{SCENE}\n[[light]]\nkind = \"environment\"\nmap = \"studio\"\n");
    let doc = prismatic_cli::scene_file::parse(&studio, "scene.toml", None).unwrap();
    assert!(matches!(&doc.scene.lights[0], Light::Environment { map, .. } if map.name == "studio"));
    doc.validate().unwrap();
}

#[test]
fn environments_that_cannot_be_used_are_errors_that_name_the_key() {
    let dir = tempfile::tempdir().unwrap();
    for (light, key, reason) in [
        ("map = \"missing.hdr\"", "light[0].map", "cannot read environment map"),
        ("map = \"studio\"\ncolor = [1, 1, 1]", "light[0].color", "not both"),
        ("color = [0, 0, 0]", "light[0].map", "black everywhere"),
        ("strength = -1", "light[0].strength", ""),
    ] {
        let text = format!("{SCENE}\n[[light]]\nkind = \"environment\"\n{light}\n");
        let e = match prismatic_cli::scene_file::parse(&text, "scene.toml", Some(dir.path())) {
            Ok(doc) => doc.validate().unwrap_err(),
            Err(e) => e,
        };
        assert_eq!(e.key, key, "{light}: {e}");
        assert!(e.reason.contains(reason), "{light}: {e}");
    }
    let two = format!("{SCENE}\n[[light]]\nkind = \"environment\"\n[[light]]\nkind = \"environment\"\n");
    let e = prismatic_cli::scene_file::parse(&two, "scene.toml", None).unwrap().validate().unwrap_err();
    assert_eq!(e.key, "light[1]", "{e}");
    assert!(e.reason.contains("second environment"), "{e}");
}

#[test]
fn the_environment_flags_light_a_scene_and_name_themselves_in_errors() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("floor.toml");
    std::fs::write(&scene, format!("{SCENE}\n[[light]]\nkind = \"sun\"\ndirection = [0, -1, 0]\nirradiance = 1\n"))
        .unwrap();
    write_map(&dir.path().join("sky.exr"));
    let render = |extra: &[&str]| crate::render_to_exr(&scene, dir.path(), extra);
    let sky = dir.path().join("sky.exr");
    let (run, out) = render(&["--environment", sky.to_str().unwrap(), "--environment-strength", "2"]);
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let image = prismatic_cli::output::read_exr(&out).unwrap();
    // The top rows see the sky: 2 × strength 2.
    assert!((image.pixels[0].x - 4.0).abs() < 1e-3, "{}", image.pixels[0]);
    let (run, out) = render(&["--environment-rotation", "10"]);
    assert_eq!(run.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(stderr.contains("--environment-rotation") && stderr.contains("no environment"), "{stderr}");
    assert!(!out.exists());
    // The median cut's size.
    let (run, out) = render(&["--environment", "studio", "--environment-lights", "4"]);
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    assert!(out.exists());
    let (run, out) = render(&["--environment", "studio", "--environment-lights", "0"]);
    assert_eq!(run.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(stderr.contains("--environment-lights: must be 1 to 4096"), "{stderr}");
    assert!(!out.exists());
}
