//! Indirect light as a user turns it on: `indirect_photons` in a scene file
//! or `--indirect-photons`, which sets the ambient stand-in to 0 unless the
//! file names one; glTF files have it on; too many photons is an error
//! that names the setting.

use prismatic_cli::scene_file::parse;
use prismatic_cli::settings::{Settings, SettingsSource};

const SCENE: &str = r#"
[render]
width = 16
height = 16
photons = 2000
passes = 1

[camera]
position = [0.0, 2.0, 3.0]
look_at = [0.0, 0.0, 0.0]

[material.floor]
kind = "diffuse"

[material.wall]
kind = "diffuse"
albedo = [0.8, 0.2, 0.2]

[[object]]
shape = "plane"
material = "floor"
point = [0, 0, 0]
normal = [0, 1, 0]

[[object]]
shape = "plane"
material = "wall"
point = [-1, 0, 0]
normal = [1, 0, 0]

[[light]]
kind = "point"
position = [0.0, 1.5, 0.0]
power = 50.0
"#;

/// `SCENE`'s `[render]` table with `line` added.
fn with_render_line(line: &str) -> String {
    SCENE.replace("passes = 1\n", &format!("passes = 1\n{line}\n"))
}

#[test]
fn a_scene_file_turns_indirect_light_on_and_the_ambient_off() {
    let render = |text: &str| parse(text, "room.toml", None).unwrap().scene.render;
    let off = render(SCENE);
    assert_eq!((off.indirect_photons, off.ambient), (0, 0.03), "off by default, the ambient stands in");
    let on = render(&with_render_line("indirect_photons = 5000"));
    assert_eq!((on.indirect_photons, on.ambient), (5000, 0.0));
    let both = render(&with_render_line("indirect_photons = 5000\nambient = 0.1"));
    assert_eq!((both.indirect_photons, both.ambient), (5000, 0.1), "a named ambient is kept");
}

#[test]
fn the_setting_sets_the_ambient_only_where_the_file_names_none() {
    let prepared = |text: &str, indirect: u32| {
        let settings = Settings { indirect_photons: Some(indirect), ..Settings::default() };
        let doc = parse(text, "room.toml", None).unwrap();
        settings.prepare(doc, SettingsSource::CommandLine).unwrap()
    };
    let on = prepared(SCENE, 5000);
    assert_eq!(on.scene.render.ambient, 0.0);
    assert!(on.plan.indirect.on, "{}", on.plan.explain());
    assert_eq!(on.traced_photons(), 5000, "caustics are off (no glass): {}", on.plan.explain());
    assert_eq!(prepared(&with_render_line("ambient = 0.1"), 5000).scene.render.ambient, 0.1);
    // Turned off again (a file that had it on): the ambient's default is back.
    let off = prepared(&with_render_line("indirect_photons = 5000"), 0);
    assert_eq!((off.scene.render.ambient, off.plan.indirect.on), (0.03, false));
}

#[test]
fn the_command_line_renders_indirect_light_and_names_a_bad_count() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("room.toml");
    std::fs::write(&path, SCENE).unwrap();
    let render = |extra: &[&str]| crate::render_to_exr(&path, dir.path(), extra);
    let (run, out) = render(&["--indirect-photons", "20000"]);
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let said = String::from_utf8_lossy(&run.stdout) + String::from_utf8_lossy(&run.stderr);
    assert!(said.contains("indirect light (20000 photons bounce off 2 diffuse objects)"), "{said}");
    assert!(prismatic_cli::output::read_exr(&out).unwrap().pixels.iter().all(|p| p.is_finite()));
    let (run, out) = render(&["--indirect-photons", "4294967295"]);
    assert_eq!(run.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(stderr.contains("--indirect-photons") && stderr.contains("would not fit in memory"), "{stderr}");
    assert!(!out.exists());
}
