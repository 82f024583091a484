//! Area lights as a user writes them: a mesh with an `emission` in a scene
//! file or an emissive glTF material lights the scene with no `[[light]]`,
//! `--area-lights` sets its pieces, and what cannot emit is a clear error.

use prismatic_core::PreparedScene;
use prismatic_core::model::scene::Light;

const SCENE: &str = r#"
[render]
width = 16
height = 16
photons = 2000
passes = 1
ambient = 0

[camera]
position = [0.0, 0.3, 3.0]
look_at = [0.0, 0.0, 0.0]

[material.floor]
kind = "diffuse"

[material.panel]
kind = "diffuse"
emission = [4.0, 3.0, 2.0]

[[object]]
shape = "plane"
material = "floor"
point = [0, 0, 0]
normal = [0, 1, 0]

[[object]]
shape = "mesh"
material = "panel"
positions = [[-0.5, 1, -0.5], [0.5, 1, -0.5], [0.5, 1, 0.5], [-0.5, 1, 0.5]]
triangles = [[0, 1, 2], [0, 2, 3]]
"#;

#[test]
fn an_emissive_mesh_is_the_scenes_light() {
    let doc = prismatic_cli::scene_file::parse(SCENE, "panel.toml", None).unwrap();
    doc.validate().unwrap();
    let scene = PreparedScene::new(doc.scene).unwrap();
    assert_eq!(scene.lights.len(), 14, "2 triangles cut toward the default 16 pieces");
    assert!(scene.lights.iter().all(|l| matches!(l, Light::Area { .. })));
    // π A L with the colour's factor (its largest channel times its spectrum's mean).
    let flux: f32 = scene.lights.iter().map(Light::power).sum();
    assert!(flux > std::f32::consts::PI * 2.0 && flux < std::f32::consts::PI * 4.0, "{flux}");

    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("panel.toml");
    std::fs::write(&path, SCENE).unwrap();
    let render = |extra: &[&str]| crate::render_to_exr(&path, dir.path(), extra);
    let (run, out) = render(&["--area-lights", "2"]);
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let image = prismatic_cli::output::read_exr(&out).unwrap();
    let centre = image.pixels[8 * 16 + 8];
    assert!(centre.x > centre.z && centre.z > 0.0, "the floor under a warm panel: {centre}");
    let (run, out) = render(&["--area-lights", "0"]);
    assert_eq!(run.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(stderr.contains("--area-lights: must be 1 to 4096"), "{stderr}");
    assert!(!out.exists());
}

#[test]
fn what_cannot_emit_is_an_error_that_names_the_key() {
    for (edit, key, reason) in [
        (("emission = [4.0, 3.0, 2.0]", "emission = [4.0, -3.0, 2.0]"), "material.panel.emission", "negative"),
        (("shape = \"mesh\"\nmaterial = \"panel\"", "shape = \"mesh\"\nmaterial = \"floor\""), "light", "no light"),
        (("material = \"floor\"\npoint", "material = \"panel\"\npoint"), "object[0].material", "only a mesh"),
    ] {
        let text = SCENE.replace(edit.0, edit.1);
        assert_ne!(text, SCENE, "{key}: the edit applies");
        let err = prismatic_cli::scene_file::parse(&text, "panel.toml", None)
            .and_then(|doc| doc.validate().map(|_| doc))
            .expect_err(key);
        let message = err.to_string();
        assert!(message.contains(key) && message.contains(reason), "{key}: {message}");
    }
}
