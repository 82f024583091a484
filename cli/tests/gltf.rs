//! glTF scenes: a dispersive prism under a spot light read from glTF traces
//! the same photons as the same scene written in TOML; what prismatic
//! cannot represent is a warning; broken files are errors that name the
//! element, exit 2 and write nothing.

use prismatic_cli::gltf_write::{GltfCamera, GltfDocument, GltfLight, GltfMaterial, GltfMesh, prism};
use prismatic_core::PreparedScene;
use prismatic_core::model::metalness::Metalness;
use prismatic_core::model::scene::{Light, MaterialKind, Shape, ThinFilm};
use prismatic_core::photons::trace;
use std::path::Path;
use std::process::Command;

const FLOOR: [[f32; 3]; 4] = [[-4.0, 0.0, -4.0], [4.0, 0.0, -4.0], [4.0, 0.0, 4.0], [-4.0, 0.0, 4.0]];
const FLOOR_TRIANGLES: [u32; 6] = [0, 2, 1, 0, 3, 2];
const PRISM_END: [[f32; 3]; 3] = [[-0.5, 0.3, -0.5], [0.5, 0.3, -0.5], [0.0, 1.2, -0.5]];
const PRISM_EXTRUDE: [f32; 3] = [0.0, 0.0, 1.0];
const SPOT_CONE: f32 = 0.3;
const SPOT_INTENSITY: f32 = 50.0;

/// A floor, a glass prism (n_d 1.5, dispersion 1: V_d 20) and a spot light
/// above it, with a camera.
fn prism_document() -> GltfDocument {
    let (positions, indices) = prism(PRISM_END, PRISM_EXTRUDE);
    GltfDocument {
        materials: vec![GltfMaterial::diffuse("floor", [0.8; 3]), GltfMaterial::glass("glass", 1.5, 1.0)],
        meshes: vec![
            GltfMesh {
                name: "floor".into(),
                positions: FLOOR.to_vec(),
                indices: FLOOR_TRIANGLES.to_vec(),
                uvs: Vec::new(),
                normals: Vec::new(),
                material: 0,
                translation: [0.0; 3],
                tangents: Vec::new(),
            },
            GltfMesh::new("prism", (positions, indices), 1, [0.0; 3]),
        ],
        lights: vec![GltfLight::Spot {
            position: [0.0, 3.0, 0.0],
            direction: [0.0, -1.0, 0.0],
            intensity: SPOT_INTENSITY,
            outer_cone: SPOT_CONE,
        }],
        camera: Some(GltfCamera { position: [0.0, 2.0, 5.0], look_at: [0.0, 0.5, 0.0], yfov: 0.8 }),
    }
}

/// `doc` written to `dir/name`, read back and validated.
fn load_valid(dir: &Path, name: &str, doc: &GltfDocument) -> prismatic_cli::scene_file::SceneDocument {
    let scene = prismatic_cli::load_scene(write(dir, name, doc).to_str().unwrap()).unwrap();
    scene.validate().unwrap_or_else(|e| panic!("{e}"));
    scene
}

fn write(dir: &Path, name: &str, doc: &GltfDocument) -> std::path::PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, doc.to_json()).unwrap();
    path
}

fn array<const N: usize>(v: [f32; N]) -> String {
    format!("[{}]", v.map(|x| format!("{x:?}")).join(", "))
}

#[test]
fn a_gltf_prism_traces_the_photons_of_the_same_scene_in_toml() {
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "prism.gltf", &prism_document());
    let gltf = prismatic_cli::load_scene(path.to_str().unwrap()).unwrap_or_else(|e| panic!("{e}"));
    assert!(gltf.warnings.is_empty(), "{:?}", gltf.warnings);
    gltf.validate().unwrap_or_else(|e| panic!("{e}"));

    // The spot light: its node's −Z, the cone's half-angle, I · 2π(1 − cos θ).
    let [Light::Spot { position, direction, cone_deg, power, .. }] = gltf.scene.lights[..] else {
        panic!("{:?}", gltf.scene.lights)
    };
    assert!((direction - glam::Vec3::NEG_Y).length() < 1e-6, "{direction}");
    assert!((cone_deg - SPOT_CONE.to_degrees()).abs() < 1e-4);
    let expected_power = SPOT_INTENSITY * 2.0 * std::f32::consts::PI * (1.0 - SPOT_CONE.cos());
    assert!((power - expected_power).abs() < 1e-4 * expected_power);

    // The same scene in TOML: meshes and materials as intended, the light
    // as imported (so any difference in the photons is the meshes' or the
    // glass's).
    let (prism_positions, prism_indices) = prism(PRISM_END, PRISM_EXTRUDE);
    let mesh = |positions: &[[f32; 3]], indices: &[u32]| {
        let p: Vec<String> = positions.iter().map(|&v| array(v)).collect();
        let t: Vec<String> = indices.chunks(3).map(|t| format!("[{}, {}, {}]", t[0], t[1], t[2])).collect();
        format!("positions = [{}]\ntriangles = [{}]\n", p.join(", "), t.join(", "))
    };
    let toml = format!(
        "[camera]\nposition = [0, 2, 5]\nlook_at = [0, 0.5, 0]\n\n\
         [[light]]\nkind = \"spot\"\nposition = {}\ndirection = {}\ncone_deg = {cone_deg:?}\npower = {power:?}\n\n\
         [material.floor]\nkind = \"diffuse\"\nalbedo = [0.8, 0.8, 0.8]\n\n\
         [material.glass]\nkind = \"dielectric\"\nior = {{ abbe = [1.5, 20.0] }}\n\n\
         [[object]]\nshape = \"mesh\"\nmaterial = \"floor\"\n{}\n\
         [[object]]\nshape = \"mesh\"\nmaterial = \"glass\"\n{}",
        array(position.to_array()),
        array(direction.to_array()),
        mesh(&FLOOR, &FLOOR_TRIANGLES),
        mesh(&prism_positions, &prism_indices),
    );
    let mut toml = prismatic_cli::scene_file::parse(&toml, "prism.toml", None).unwrap_or_else(|e| panic!("{e}"));
    toml.scene.render = gltf.scene.render.clone();
    toml.scene.render.photons = 4000;
    let mut from_gltf = gltf.scene.clone();
    from_gltf.render.photons = 4000;
    let a = trace::trace_photons(&PreparedScene::new(from_gltf).unwrap(), &mut prismatic_core::NoProgress);
    let b = trace::trace_photons(&PreparedScene::new(toml.scene).unwrap(), &mut prismatic_core::NoProgress);
    assert!(a.photons.iter().any(|p| p.band != prismatic_core::model::photon::WHITE_BAND), "the prism splits bands");
    assert_eq!(a, b);
}

#[test]
fn what_prismatic_cannot_represent_is_a_warning_not_a_failure() {
    let dir = tempfile::tempdir().unwrap();
    let mut doc = prism_document();
    doc.materials[1].roughness = 0.3;
    doc.lights.clear();
    // A film on the bare diffuse floor (no specular layer), which prismatic
    // draws on glass, metals and specular layers only.
    let mut json: serde_json::Value = serde_json::from_str(&doc.to_json()).unwrap();
    json["materials"][0]["extensions"] = serde_json::json!({
        "KHR_materials_iridescence": { "iridescenceFactor": 1.0 },
        "KHR_materials_specular": { "specularFactor": 0.0 }
    });
    json["extensionsUsed"].as_array_mut().unwrap().push("KHR_materials_iridescence".into());
    let path = dir.path().join("rough.gltf");
    std::fs::write(&path, json.to_string()).unwrap();
    let scene = prismatic_cli::load_scene(path.to_str().unwrap()).unwrap();
    scene.validate().unwrap();
    let warnings = scene.warnings.join("\n");
    assert!(warnings.contains("left out: KHR_materials_iridescence of a bare diffuse material"), "{warnings}");
    // Rough transmission is frosted glass, drawn as such: no warning.
    assert!(!warnings.contains("materials[1]"), "{warnings}");
    let glass = &scene.scene.materials.iter().find(|m| m.name == "glass").unwrap().kind;
    assert!(matches!(glass, MaterialKind::Dielectric { roughness, .. } if *roughness == 0.3), "{glass:?}");
    assert!(warnings.contains("no light: lit by the built-in studio environment"), "{warnings}");
    assert!(matches!(scene.scene.lights.as_slice(), [Light::Environment { .. }]), "{:?}", scene.scene.lights);
    // Lit as viewers light it: with its indirect light, no ambient.
    let r = &scene.scene.render;
    assert!(
        r.indirect_photons == r.photons && r.ambient == 0.0,
        "{} indirect photons, ambient {}",
        r.indirect_photons,
        r.ambient
    );
    // The binary prints them and renders.
    let out = dir.path().join("rough.png");
    let run = Command::new(env!("CARGO_BIN_EXE_prismatic"))
        .args([
            "render",
            path.to_str().unwrap(),
            "--photons",
            "2000",
            "--passes",
            "1",
            "--width",
            "32",
            "--height",
            "32",
            "-o",
        ])
        .arg(&out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{stderr}");
    assert!(stderr.contains("warning: ") && stderr.contains("KHR_materials_iridescence"), "{stderr}");
    assert!(out.is_file());
}

#[test]
fn broken_gltf_files_name_the_element_exit_2_and_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let mut bad_index = prism_document();
    bad_index.meshes[1].indices[4] = 99;
    let mut nan = prism_document();
    nan.meshes[1].positions[2][1] = f32::NAN;
    let mut dark = prism_document();
    let GltfLight::Spot { intensity, .. } = &mut dark.lights[0] else { panic!() };
    *intensity = -1.0;
    let mut no_normal = prism_document();
    no_normal.meshes[1].normals = vec![[0.0, 0.0, 1.0]; 6];
    no_normal.meshes[1].normals[3] = [0.0; 3];
    let missing_buffer = prism_document().to_json().replace("data:application/octet-stream;base64,", "missing.bin#");
    let cases: Vec<(&str, String, &str)> = vec![
        (
            "bad-index.gltf",
            bad_index.to_json(),
            "meshes[1].primitives[0].indices: index 99 is out of range (6 vertices)",
        ),
        ("nan.gltf", nan.to_json(), "meshes[1].primitives[0].attributes.POSITION: vertex 2 is not finite"),
        ("dark.gltf", dark.to_json(), "nodes[2].extensions.KHR_lights_punctual.power: "),
        (
            "no-normal.gltf",
            no_normal.to_json(),
            "meshes[1].primitives[0].attributes.NORMAL: normal 3 is not a unit vector",
        ),
        ("missing-buffer.gltf", missing_buffer, "buffers: "),
        ("not-json.gltf", "{ this is not json".into(), "not-json.gltf: "),
    ];
    for (name, text, expected) in cases {
        assert_render_refused(dir.path(), name, &text, expected);
    }
}

/// A mesh's NORMAL attribute becomes its vertex normals, turned with its
/// node (here a translation: unchanged) and named in no warning.
#[test]
fn vertex_normals_are_read_with_their_mesh() {
    let dir = tempfile::tempdir().unwrap();
    let mut doc = prism_document();
    doc.meshes.push(GltfMesh::ball("ball", (0.5, 8), 1, [2.0, 0.5, 0.0]));
    let loaded = prismatic_cli::load_scene(write(dir.path(), "ball.gltf", &doc).to_str().unwrap()).unwrap();
    assert!(loaded.warnings.is_empty(), "{:?}", loaded.warnings);
    let Shape::Mesh { positions, normals, .. } = &loaded.scene.objects[2].shape else { panic!("a mesh") };
    assert_eq!(normals.len(), positions.len());
    let centre = glam::Vec3::new(2.0, 0.5, 0.0);
    for (p, n) in positions.iter().zip(normals) {
        assert!((*n - (*p - centre).normalize()).length() < 1e-5, "{p}: {n}");
    }
    let Shape::Mesh { normals, .. } = &loaded.scene.objects[1].shape else { panic!("a mesh") };
    assert!(normals.is_empty(), "the prism has flat faces");
    PreparedScene::new(loaded.scene).unwrap();
}

/// `prismatic render` of glTF `text`, written to `dir/name`, exits 2 with
/// `expected` in its message, without a panic or an image.
fn assert_render_refused(dir: &Path, name: &str, text: &str, expected: &str) {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    let out = dir.join("out.png");
    let run = Command::new(env!("CARGO_BIN_EXE_prismatic"))
        .args(["render", path.to_str().unwrap(), "-o"])
        .arg(&out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(2), "{name}: {stderr}");
    assert!(stderr.contains(expected), "{name}: expected «{expected}» in {stderr}");
    assert!(!stderr.contains("panicked"), "{name}: {stderr}");
    assert!(!out.exists(), "{name}: wrote an image");
}

/// The built-in DispersionTest-style grid. Its glass follows the
/// extension: n(400 nm) − n(700 nm) is 0 along the n = 1.0 row whatever the
/// dispersion value, and grows along every other row. Traced one prism at a
/// time: behind the n = 1.0 prisms light goes straight on and the bands of
/// a white photon land together; elsewhere, dispersion 0 keeps them
/// together and any other value fans them out. (How far apart they land
/// does not grow steadily with the value: where the bluest bands meet total
/// internal reflection they take another path altogether.)
#[test]
fn the_dispersion_test_grid_spreads_colour_only_where_the_extension_says() {
    use prismatic_cli::dispersion_test::{DISPERSIONS, IORS};
    use prismatic_core::model::scene::MaterialKind;
    let doc = prismatic_cli::load_scene("dispersion-test").unwrap_or_else(|e| panic!("{e}"));
    assert!(doc.warnings.is_empty(), "{:?}", doc.warnings);
    let Light::Sun { direction: sun, .. } = doc.scene.lights[0] else { panic!("the sun") };
    // The floor and the backdrop are textured, through the importer.
    for object in &doc.scene.objects[..2] {
        let kind = &doc.scene.materials[object.material].kind;
        assert!(matches!(kind, MaterialKind::Diffuse { texture: Some(_), .. }), "{kind:?}");
    }
    for (row, ior) in IORS.iter().enumerate() {
        let mut spans = Vec::new();
        for column in 0..DISPERSIONS.len() {
            // Objects: the floor, the backdrop, then the prisms row by row.
            let object = &doc.scene.objects[2 + row * DISPERSIONS.len() + column];
            let MaterialKind::Dielectric { dispersion, .. } = &doc.scene.materials[object.material].kind else {
                panic!("row {row} column {column} is not glass")
            };
            let n = |nm: f32| dispersion.ior_at(nm).unwrap();
            assert!((n(587.56) - ior).abs() < 1e-4, "row {row} column {column}: n_d {}", n(587.56));
            spans.push(n(400.0) - n(700.0));

            let mut scene = doc.scene.clone();
            scene.objects = vec![scene.objects[0].clone(), object.clone()];
            scene.render.photons = 3000;
            let map = trace::trace_photons(&PreparedScene::new(scene).unwrap(), &mut prismatic_core::NoProgress);
            assert!(map.photons.len() > 100, "row {row} column {column}: {} photons", map.photons.len());
            if row == 0 {
                for p in &map.photons {
                    assert!((p.direction() - sun.normalize()).length() < 1e-3, "n = 1 bent a photon: {p:?}");
                }
            }
            // The widest distance between bands of one white photon.
            let mut landing: std::collections::BTreeMap<u32, Vec<glam::Vec3>> = Default::default();
            for p in &map.photons {
                landing.entry(p.emission).or_default().push(p.pos());
            }
            let fanned = landing.values().any(|v| v.iter().any(|p| (*p - v[0]).length() > 1e-4));
            let expected = row > 0 && column > 0;
            assert_eq!(fanned, expected, "row {row} (n {ior}) column {column}: bands fanned out: {fanned}");
        }
        if row == 0 {
            assert!(spans.iter().all(|&s| s == 0.0), "n = 1 disperses: {spans:?}");
        } else {
            assert!(spans[0] == 0.0 && spans.windows(2).all(|w| w[1] > w[0]), "row {row}: {spans:?}");
        }
    }
}

/// `[[object]] shape = "gltf"` places a glTF file's meshes and materials in
/// a TOML scene (its lights and camera left out, with a warning): with the
/// same light, the photons are the glTF scene's; moved and scaled, the
/// file's geometry moves with it; a broken file is the object's error.
#[test]
fn a_gltf_placed_in_a_scene_file_brings_its_meshes_and_materials() {
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "prism.gltf", &prism_document());
    let alone = prismatic_cli::load_scene(path.to_str().unwrap()).unwrap();
    let [Light::Spot { position, direction, cone_deg, power, .. }] = alone.scene.lights[..] else { panic!() };
    let scene = |placement: &str| {
        format!(
            "[camera]\nposition = [0, 2, 5]\nlook_at = [0, 0.5, 0]\n\n\
             [[light]]\nkind = \"spot\"\nposition = {}\ndirection = {}\ncone_deg = {cone_deg:?}\npower = {power:?}\n\n\
             [[object]]\nshape = \"gltf\"\npath = \"prism.gltf\"\n{placement}",
            array(position.to_array()),
            array(direction.to_array()),
        )
    };
    let placed = prismatic_cli::scene_file::parse(&scene(""), "scene.toml", Some(dir.path())).unwrap();
    placed.validate().unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        placed.scene.materials.iter().map(|m| m.name.as_str()).collect::<Vec<_>>(),
        ["prism/floor", "prism/glass"]
    );
    assert!(
        placed.warnings.iter().any(|w| w.contains("object[0]: its lights and camera are left out")),
        "{:?}",
        placed.warnings
    );
    let trace = |mut s: prismatic_core::Scene| {
        // The meshes' caustics (a scene file's render settings have no indirect light).
        (s.render.photons, s.render.indirect_photons, s.render.radius) = (3000, 0, 0.05);
        trace::trace_photons(&PreparedScene::new(s).unwrap(), &mut prismatic_core::NoProgress)
    };
    assert_eq!(trace(placed.scene.clone()), trace(alone.scene.clone()));

    let moved =
        prismatic_cli::scene_file::parse(&scene("translate = [1, 0, 2]\nscale = 2\n"), "scene.toml", Some(dir.path()))
            .unwrap();
    let (Shape::Mesh { positions: a, .. }, Shape::Mesh { positions: b, .. }) =
        (&placed.scene.objects[1].shape, &moved.scene.objects[1].shape)
    else {
        panic!("meshes")
    };
    for (a, b) in a.iter().zip(b) {
        assert!((*a * 2.0 + glam::Vec3::new(1.0, 0.0, 2.0) - *b).length() < 1e-5, "{a} -> {b}");
    }

    std::fs::write(dir.path().join("prism.gltf"), "{ broken").unwrap();
    let e = prismatic_cli::scene_file::parse(&scene(""), "scene.toml", Some(dir.path())).map(|_| ()).unwrap_err();
    assert_eq!(e.key, "object[0].path", "{e}");
    assert!(e.reason.contains("prism.gltf"), "{e}");
}

#[test]
fn volume_attenuation_makes_coloured_glass_and_thin_walls_stay_clear() {
    let dir = tempfile::tempdir().unwrap();
    let mut doc = prism_document();
    doc.materials[1].attenuation = Some(([0.9, 0.4, 0.1], 0.5));
    let scene = prismatic_cli::load_scene(write(dir.path(), "amber.gltf", &doc).to_str().unwrap()).unwrap();
    scene.validate().unwrap();
    let MaterialKind::Dielectric { attenuation: Some(a), .. } = &scene.scene.materials[1].kind else {
        panic!("coloured glass expected, got {:?}", scene.scene.materials[1].kind)
    };
    assert_eq!((a.color.to_array(), a.distance), ([0.9, 0.4, 0.1], 0.5));
    assert!(!scene.warnings.join("\n").contains("attenuation"), "{:?}", scene.warnings);
    // A thin-walled material (thicknessFactor 0) has no volume: clear glass and a warning.
    let json = doc.to_json().replace("\"thicknessFactor\": 1.0", "\"thicknessFactor\": 0.0");
    let path = dir.path().join("thin.gltf");
    std::fs::write(&path, json).unwrap();
    let scene = prismatic_cli::load_scene(path.to_str().unwrap()).unwrap();
    assert!(matches!(&scene.scene.materials[1].kind, MaterialKind::Dielectric { attenuation: None, thin: true, .. }));
    assert!(scene.warnings.join("\n").contains("thin-walled"), "{:?}", scene.warnings);
}

/// glTF's transmission is thin-walled without `KHR_materials_volume`, and
/// a volume needs no closed mesh: such files render (as sheets), with a
/// warning only where a volume is left out.
#[test]
fn glass_without_a_volume_or_on_an_open_mesh_is_a_thin_sheet() {
    let dir = tempfile::tempdir().unwrap();
    let mut json: serde_json::Value = serde_json::from_str(&prism_document().to_json()).unwrap();
    json["materials"][1]["extensions"].as_object_mut().unwrap().remove("KHR_materials_volume");
    let path = dir.path().join("sheet.gltf");
    std::fs::write(&path, json.to_string()).unwrap();
    let scene = prismatic_cli::load_scene(path.to_str().unwrap()).unwrap();
    scene.validate().unwrap();
    assert!(matches!(&scene.scene.materials[1].kind, MaterialKind::Dielectric { thin: true, attenuation: None, .. }));
    assert!(!scene.warnings.join("\n").contains("glass"), "nothing is left out: {:?}", scene.warnings);
    // Its base colour tints what crosses it.
    json["materials"][1]["pbrMetallicRoughness"]["baseColorFactor"] = serde_json::json!([0.2, 0.5, 0.9, 1.0]);
    std::fs::write(&path, json.to_string()).unwrap();
    let scene = prismatic_cli::load_scene(path.to_str().unwrap()).unwrap();
    scene.validate().unwrap();
    let MaterialKind::Dielectric { thin: true, attenuation: Some(a), .. } = &scene.scene.materials[1].kind else {
        panic!("{:?}", scene.scene.materials[1].kind)
    };
    assert_eq!(a.color.to_array(), [0.2, 0.5, 0.9]);

    // Solid glass on an open mesh (the floor's square): drawn as a sheet, said so.
    let mut doc = prism_document();
    doc.meshes[0].material = 1;
    let scene = prismatic_cli::load_scene(write(dir.path(), "open.gltf", &doc).to_str().unwrap()).unwrap();
    scene.validate().unwrap();
    let floor = &scene.scene.materials[scene.scene.objects[0].material];
    assert!(matches!(floor.kind, MaterialKind::Dielectric { thin: true, .. }), "{floor:?}");
    assert_eq!(floor.name, "glass (thin-walled)");
    let prism = &scene.scene.materials[scene.scene.objects[1].material];
    assert!(matches!(prism.kind, MaterialKind::Dielectric { thin: false, .. }), "the closed prism stays solid");
    assert!(
        scene.warnings.iter().any(|w| w.contains("meshes[0]") && w.contains("thin-walled")),
        "{:?}",
        scene.warnings
    );
}

/// `KHR_materials_iridescence`'s textures vary a film over the mesh (its
/// film map: the thickness texture's green from `iridescenceThicknessMinimum`
/// to the maximum, the iridescence texture's red scaling the factor); one on
/// another coordinate set is named as left out, and a texture index the
/// file does not have is refused with its path.
#[test]
fn iridescence_textures_vary_the_film_over_the_mesh() {
    use prismatic_cli::gltf_write::GltfTexture;
    let dir = tempfile::tempdir().unwrap();
    let mut doc = prism_document();
    let oily = GltfTexture { width: 1, height: 1, pixels: vec![[200, 150, 60]], nearest: true, wrap: [10497; 2] };
    doc.materials[0] = GltfMaterial {
        metallic: 1.0,
        roughness: 0.2,
        base_color_texture: Some(oily),
        ..GltfMaterial::diffuse("oily", [1.0; 3])
    };
    doc.meshes[0].uvs = vec![[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]];
    let mut json: serde_json::Value = serde_json::from_str(&doc.to_json()).unwrap();
    json["materials"][0]["extensions"] = serde_json::json!({ "KHR_materials_iridescence": {
        "iridescenceFactor": 0.9,
        "iridescenceThicknessMinimum": 120,
        "iridescenceThicknessMaximum": 480,
        "iridescenceThicknessTexture": { "index": 0 },
        "iridescenceTexture": { "index": 0 }
    } });
    json["extensionsUsed"].as_array_mut().unwrap().push("KHR_materials_iridescence".into());
    let load = |json: &serde_json::Value| {
        let path = dir.path().join("oily.gltf");
        std::fs::write(&path, json.to_string()).unwrap();
        prismatic_cli::load_scene(path.to_str().unwrap())
    };
    let scene = load(&json).unwrap();
    scene.validate().unwrap();
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    let oily = &scene.scene.materials[0];
    let MaterialKind::Metal { film, .. } = &oily.kind else { panic!("a metal: {:?}", oily.kind) };
    assert_eq!(*film, Some(ThinFilm { factor: 0.9, ..ThinFilm::new(1.3, 480.0) }));
    let map = oily.film_map.as_ref().expect("the film's map");
    let texel = |t: &Option<prismatic_core::model::scene::Texture>| t.as_ref().expect("a map").texels[0];
    assert_eq!(
        (map.min_nm, texel(&map.thickness), texel(&map.factor)),
        (120.0, 200 | 150 << 8 | 60 << 16, 200 | 150 << 8 | 60 << 16)
    );
    // Another coordinate set: left out, named; the thickness map stays.
    json["materials"][0]["extensions"]["KHR_materials_iridescence"]["iridescenceTexture"]["texCoord"] = 1.into();
    let scene = load(&json).unwrap();
    let map = scene.scene.materials[0].film_map.as_ref().expect("the film's map");
    assert!(map.thickness.is_some() && map.factor.is_none());
    let warnings = scene.warnings.join("\n");
    assert!(warnings.contains("iridescenceTexture on a texture coordinate set other than 0"), "{warnings}");
    // A texture the file does not have.
    json["materials"][0]["extensions"]["KHR_materials_iridescence"]["iridescenceThicknessTexture"]["index"] = 7.into();
    let err = load(&json).map(|_| ()).unwrap_err().to_string();
    let key = "materials[0].extensions.KHR_materials_iridescence.iridescenceThicknessTexture.index";
    assert!(err.contains(key), "{err}");
}

/// `KHR_materials_iridescence` on glass or a metal is a film of its index
/// and maximum thickness, mixed by its factor; on a diffuse material the
/// whole extension is named as left out, and a factor above 1 is refused
/// with its path.
#[test]
fn iridescence_on_glass_is_a_thin_film() {
    let dir = tempfile::tempdir().unwrap();
    let mut json: serde_json::Value = serde_json::from_str(&prism_document().to_json()).unwrap();
    let load = |json: &serde_json::Value| {
        let path = dir.path().join("film.gltf");
        std::fs::write(&path, json.to_string()).unwrap();
        let scene = prismatic_cli::load_scene(path.to_str().unwrap()).unwrap();
        scene.validate().unwrap();
        scene
    };
    let film = |scene: &prismatic_cli::scene_file::SceneDocument| match &scene.scene.materials[1].kind {
        MaterialKind::Dielectric { film, .. } => *film,
        other => panic!("glass expected, got {other:?}"),
    };
    let mut glass = json["materials"][1]["extensions"].as_object().cloned().unwrap();
    glass.insert("KHR_materials_iridescence".into(), serde_json::json!({ "iridescenceFactor": 1.0 }));
    json["materials"][1]["extensions"] = serde_json::Value::Object(glass.clone());
    let scene = load(&json);
    assert_eq!(film(&scene), Some(ThinFilm::new(1.3, 400.0)), "the extension's defaults");
    assert!(!scene.warnings.join("\n").contains("iridescence"), "{:?}", scene.warnings);
    glass.insert(
        "KHR_materials_iridescence".into(),
        serde_json::json!({
            "iridescenceFactor": 0.5,
            "iridescenceIor": 1.8,
            "iridescenceThicknessMinimum": 200,
            "iridescenceThicknessMaximum": 650
        }),
    );
    json["materials"][1]["extensions"] = serde_json::Value::Object(glass.clone());
    let scene = load(&json);
    // A factor below 1 is the extension's mix of the film's and the bare Fresnel.
    assert_eq!(film(&scene), Some(ThinFilm { factor: 0.5, ..ThinFilm::new(1.8, 650.0) }));
    let warnings = scene.warnings.join("\n");
    assert!(!warnings.contains("iridescence"), "{warnings}");
    // A factor above 1 is invalid (the extension's schema says at most 1).
    glass.insert("KHR_materials_iridescence".into(), serde_json::json!({ "iridescenceFactor": 1.5 }));
    json["materials"][1]["extensions"] = serde_json::Value::Object(glass.clone());
    let path = dir.path().join("too_much.gltf");
    std::fs::write(&path, json.to_string()).unwrap();
    let err = prismatic_cli::load_scene(path.to_str().unwrap()).map(|_| ()).unwrap_err().to_string();
    let key = "materials[1].extensions.KHR_materials_iridescence.iridescenceFactor";
    assert!(err.contains("too_much.gltf") && err.contains(key) && err.contains("0 to 1"), "{err}");
    // A factor of 0 is no film.
    glass.insert("KHR_materials_iridescence".into(), serde_json::json!({ "iridescenceFactor": 0.0 }));
    json["materials"][1]["extensions"] = serde_json::Value::Object(glass);
    assert_eq!(film(&load(&json)), None);
    // On the diffuse floor: named as left out.
    let mut floor = json["materials"][0]["extensions"].as_object().cloned().unwrap_or_default();
    floor.insert("KHR_materials_iridescence".into(), serde_json::json!({ "iridescenceFactor": 1.0 }));
    json["materials"][0]["extensions"] = serde_json::Value::Object(floor);
    json["materials"][0]["pbrMetallicRoughness"]["metallicFactor"] = 0.0.into();
    let warnings = load(&json).warnings.join("\n");
    assert!(warnings.contains("KHR_materials_iridescence of a bare diffuse material"), "{warnings}");
    // Under glTF's default specular layer: a film on the layer, nothing left out.
    json["materials"][0]["extensions"].as_object_mut().unwrap().remove("KHR_materials_specular");
    let scene = load(&json);
    let MaterialKind::Metal { film, metalness, .. } = &scene.scene.materials[0].kind else { panic!("a layered floor") };
    assert_eq!((*film, metalness.factor), (Some(ThinFilm::new(1.3, 400.0)), 0.0));
    assert!(metalness.layer.is_some() && !scene.warnings.join("\n").contains("iridescence"), "{:?}", scene.warnings);
    // A metal floor: a film on the metal, nothing left out.
    json["materials"][0]["pbrMetallicRoughness"]["metallicFactor"] = 1.0.into();
    let scene = load(&json);
    let MaterialKind::Metal { film, .. } = &scene.scene.materials[0].kind else { panic!("a metal floor") };
    assert_eq!(*film, Some(ThinFilm::new(1.3, 400.0)));
    assert!(!scene.warnings.join("\n").contains("iridescence"), "{:?}", scene.warnings);
}

#[test]
fn a_directional_light_becomes_the_sun() {
    let dir = tempfile::tempdir().unwrap();
    let mut doc = prism_document();
    doc.lights = vec![GltfLight::Directional { direction: [1.0, -2.0, 0.5], intensity: 4.0 }];
    let scene = prismatic_cli::load_scene(write(dir.path(), "sun.gltf", &doc).to_str().unwrap()).unwrap();
    scene.validate().unwrap();
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    let [Light::Sun { direction, irradiance, .. }] = scene.scene.lights.as_slice() else {
        panic!("one sun expected, got {:?}", scene.scene.lights)
    };
    assert!((*direction - glam::Vec3::new(1.0, -2.0, 0.5).normalize()).length() < 1e-5, "{direction}");
    assert_eq!(*irradiance, 4.0);
    // Its caustic photons leave toward the prism (the only glass), across
    // its bounding sphere: at least half of them meet it (without indirect
    // light, whose photons the beam spreads over every object).
    let mut caustic_only = scene.scene;
    caustic_only.render.indirect_photons = 0;
    let prepared = PreparedScene::new(caustic_only).unwrap();
    let s = trace::trace_photons(&prepared, &mut prismatic_core::NoProgress).stats;
    assert!(s.specular_paths * 2 > s.emitted, "{s:?}");
}

#[test]
fn a_base_colour_texture_is_read_with_its_sampler_and_texture_coordinates() {
    use prismatic_cli::gltf_write::GltfTexture;
    use prismatic_core::model::scene::{Filter, Wrap};
    let dir = tempfile::tempdir().unwrap();
    let mut doc = prism_document();
    doc.materials[0].base_color_texture = Some(GltfTexture {
        width: 2,
        height: 2,
        pixels: vec![[255, 0, 0], [0, 255, 0], [0, 0, 255], [10, 20, 30]],
        nearest: true,
        wrap: [33071, 33648],
    });
    doc.meshes[0].uvs = vec![[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]];
    let scene = prismatic_cli::load_scene(write(dir.path(), "tiles.gltf", &doc).to_str().unwrap()).unwrap();
    scene.validate().unwrap();
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    let MaterialKind::Diffuse { texture: Some(t), albedo, .. } = &scene.scene.materials[0].kind else {
        panic!("a textured floor expected, got {:?}", scene.scene.materials[0].kind)
    };
    assert_eq!(albedo.to_array(), [0.8; 3], "baseColorFactor multiplies the texture");
    assert_eq!((t.width, t.height), (2, 2));
    assert_eq!(t.texels[..], [255, 255 << 8, 255 << 16, 10 | 20 << 8 | 30 << 16]);
    assert_eq!(
        (t.sampler.filter, t.sampler.wrap_u, t.sampler.wrap_v),
        (Filter::Nearest, Wrap::ClampToEdge, Wrap::MirroredRepeat)
    );
    assert!(t.name.starts_with("images[0]"), "{}", t.name);
    let Shape::Mesh { uvs, .. } = &scene.scene.objects[0].shape else { panic!("a mesh") };
    assert_eq!(uvs[2].to_array(), [2.0, 2.0]);
    // An image that cannot be read, or has no usable source: an error naming it, exit 2, no image written.
    let json = doc.to_json();
    let in_buffer = "\"bufferView\": 5,\n      \"mimeType\": \"image/png\"";
    assert!(json.contains(in_buffer), "{json}");
    for (name, image, reason) in [
        ("missing.gltf", "\"uri\": \"missing.png\"", "images[0]: cannot read the image"),
        ("untyped.gltf", "\"bufferView\": 5", "images[0]: an image in a buffer view needs a mimeType"),
    ] {
        assert_render_refused(dir.path(), name, &json.replace(in_buffer, image), reason);
    }
}

/// `KHR_texture_transform` on a base-colour texture moves the mesh's
/// coordinates by the spec's T · R · S (rows (cos, sin) and (−sin, cos));
/// a transform that names another coordinate set leaves the texture out,
/// with a warning.
#[test]
fn a_texture_transform_moves_the_texture_coordinates() {
    use prismatic_cli::gltf_write::GltfTexture;
    let dir = tempfile::tempdir().unwrap();
    let mut doc = prism_document();
    doc.materials[0].base_color_texture =
        Some(GltfTexture { width: 1, height: 1, pixels: vec![[200, 100, 50]], nearest: false, wrap: [10497; 2] });
    let uvs = [[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 1.0]];
    doc.meshes[0].uvs = uvs.to_vec();
    let ([ox, oy], r, [sx, sy]) = ([0.5f32, 0.25], 0.5f32, [2.0f32, 3.0]);
    let with_transform = |transform: serde_json::Value| {
        let mut json: serde_json::Value = serde_json::from_str(&doc.to_json()).unwrap();
        json["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"] =
            serde_json::json!({ "KHR_texture_transform": transform });
        json["extensionsUsed"].as_array_mut().unwrap().push("KHR_texture_transform".into());
        json.to_string()
    };
    let path = dir.path().join("transformed.gltf");
    std::fs::write(&path, with_transform(serde_json::json!({ "offset": [ox, oy], "rotation": r, "scale": [sx, sy] })))
        .unwrap();
    let scene = prismatic_cli::load_scene(path.to_str().unwrap()).unwrap_or_else(|e| panic!("{e}"));
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    let Shape::Mesh { uvs: got, .. } = &scene.scene.objects[0].shape else { panic!("a mesh") };
    for (&[u, v], got) in uvs.iter().zip(got) {
        let want = [r.cos() * sx * u + r.sin() * sy * v + ox, -r.sin() * sx * u + r.cos() * sy * v + oy];
        assert!((got.x - want[0]).abs() < 1e-5 && (got.y - want[1]).abs() < 1e-5, "({u}, {v}) → {got}, want {want:?}");
    }
    // A transform that names coordinate set 1 (the floor has set 0 only).
    let path = dir.path().join("other_set.gltf");
    std::fs::write(&path, with_transform(serde_json::json!({ "texCoord": 1 }))).unwrap();
    let scene = prismatic_cli::load_scene(path.to_str().unwrap()).unwrap_or_else(|e| panic!("{e}"));
    assert!(
        matches!(scene.scene.materials[0].kind, MaterialKind::Diffuse { texture: None, .. }),
        "{:?}",
        scene.scene.materials[0].kind
    );
    assert!(
        scene.warnings.iter().any(|w| w.contains("baseColorTexture on a texture coordinate set other than 0")),
        "{:?}",
        scene.warnings
    );
}

#[test]
fn the_sunlit_glass_scene_brings_coloured_glass_textures_and_the_sun_through_the_importer() {
    let doc = prismatic_cli::load_scene("sunlit-glass").unwrap_or_else(|e| panic!("{e}"));
    doc.validate().unwrap_or_else(|e| panic!("{e}"));
    assert!(doc.warnings.is_empty(), "{:?}", doc.warnings);
    assert!(matches!(doc.scene.lights[..], [Light::Sun { .. }]), "{:?}", doc.scene.lights);
    let kinds: Vec<&MaterialKind> = doc.scene.objects.iter().map(|o| &doc.scene.materials[o.material].kind).collect();
    let textured = kinds.iter().filter(|k| matches!(k, MaterialKind::Diffuse { texture: Some(_), .. })).count();
    let coloured = kinds.iter().filter(|k| matches!(k, MaterialKind::Dielectric { attenuation: Some(_), .. })).count();
    let dispersive = kinds
        .iter()
        .filter(|k| matches!(k, MaterialKind::Dielectric { dispersion, .. } if !dispersion.is_constant()))
        .count();
    assert_eq!((textured, coloured, dispersive), (2, 2, 2));
}

/// The prism document lit by one directional light of intensity 4 and
/// linear colour `color`, read back.
fn sun_of_colour(dir: &Path, color: [f32; 3]) -> prismatic_cli::scene_file::SceneDocument {
    let mut doc = prism_document();
    doc.lights = vec![GltfLight::Directional { direction: [1.0, -2.0, 0.5], intensity: 4.0 }];
    let json = doc.to_json();
    let with_colour = format!("\"type\": \"directional\", \"color\": {}", array(color));
    let coloured = json.replacen("\"type\": \"directional\"", &with_colour, 1);
    assert_ne!(json, coloured, "the light's JSON has its type");
    let path = dir.join("sun.gltf");
    std::fs::write(&path, coloured).unwrap();
    let scene = prismatic_cli::load_scene(path.to_str().unwrap()).unwrap();
    scene.validate().unwrap();
    scene
}

/// A coloured glTF light (`KHR_lights_punctual`'s linear `color`) emits
/// its colour: a smooth spectrum whose colour per watt has the colour's
/// proportions, and an irradiance that makes it emit colour × intensity.
#[test]
fn a_lights_colour_becomes_its_spectrum() {
    let dir = tempfile::tempdir().unwrap();
    let scene = sun_of_colour(dir.path(), [1.0, 0.5, 0.2]);
    let [Light::Sun { irradiance, spectrum, .. }] = scene.scene.lights.as_slice() else { panic!() };
    assert!(matches!(spectrum, prismatic_core::model::spectrum::Spectrum::Smooth { .. }), "{spectrum}");
    let prepared = PreparedScene::new(scene.scene.clone()).unwrap();
    let emitted = prepared.light_spectra[0].rgb * *irradiance;
    let want = glam::Vec3::new(1.0, 0.5, 0.2) * 4.0;
    assert!((emitted - want).abs().max_element() < 0.01 * 4.0, "{emitted} vs {want}");
}

/// A black light is valid glTF and emits nothing: it is left out with a
/// warning (here the only light, so the importer's stand-in spot lights
/// the scene), not refused.
#[test]
fn a_black_light_is_left_out_with_a_warning() {
    let dir = tempfile::tempdir().unwrap();
    let scene = sun_of_colour(dir.path(), [0.0; 3]);
    assert!(scene.warnings.iter().any(|w| w.contains("colour is black")), "{:?}", scene.warnings);
    assert!(!scene.scene.lights.iter().any(|l| matches!(l, Light::Sun { .. })), "{:?}", scene.scene.lights);
}

/// A file brings no exposure: it is shown as viewers show it, at middle
/// grey through the default tone map; its camera's aspect ratio gives the
/// image's shape (the default square's pixel count); a spot keeps its soft
/// edge, with the axis's intensity, and its range (which its node's scale
/// leaves alone); a range of 0 is refused, naming the light.
#[test]
fn a_file_is_shown_with_its_cameras_frame_and_auto_exposure() {
    let dir = tempfile::tempdir().unwrap();
    let mut json: serde_json::Value = serde_json::from_str(&prism_document().to_json()).unwrap();
    json["cameras"][0]["perspective"]["aspectRatio"] = 1.5.into();
    let spot = &mut json["extensions"]["KHR_lights_punctual"]["lights"][0];
    spot["range"] = 20.0.into();
    spot["spot"]["innerConeAngle"] = 0.1.into();
    let path = dir.path().join("framed.gltf");
    std::fs::write(&path, json.to_string()).unwrap();
    let scene = prismatic_cli::load_scene(path.to_str().unwrap()).unwrap();
    let r = &scene.scene.render;
    assert_eq!((r.width, r.height), (490, 327), "400² pixels at 3:2");
    assert!(r.auto_exposure);
    assert_eq!(r.tone_map, prismatic_core::model::color::ToneMap::PbrNeutral);
    assert!(
        !scene.warnings.iter().any(|w| w.contains("range") || w.contains("innerConeAngle")),
        "{:?}",
        scene.warnings
    );
    let [Light::Spot { cone_deg, inner_cone_deg, power, range, .. }] = scene.scene.lights.as_slice() else {
        panic!("{:?}", scene.scene.lights)
    };
    assert_eq!(*range, Some(20.0));
    assert_eq!((*cone_deg, *inner_cone_deg), (SPOT_CONE.to_degrees(), 0.1f32.to_degrees()));
    // I₀ · 2π [(1 − cos inner) + (cos inner − cos outer)/3].
    let (ci, co) = (0.1f32.cos(), SPOT_CONE.cos());
    let want = SPOT_INTENSITY * 2.0 * std::f32::consts::PI * ((1.0 - ci) + (ci - co) / 3.0);
    assert!((power - want).abs() < 1e-4 * want, "{power} vs {want}");
    // A range must be greater than 0 (the extension's schema says so too).
    json["extensions"]["KHR_lights_punctual"]["lights"][0]["range"] = 0.0.into();
    std::fs::write(&path, json.to_string()).unwrap();
    let err = prismatic_cli::load_scene(path.to_str().unwrap()).unwrap().validate().unwrap_err().to_string();
    assert!(err.contains("KHR_lights_punctual") && err.contains("range"), "{err}");
}

/// An emissive material makes its mesh an area light (its strength from
/// `KHR_materials_emissive_strength`), and a file lit only so gets no studio.
#[test]
fn an_emissive_material_is_an_area_light() {
    let dir = tempfile::tempdir().unwrap();
    let mut doc = prism_document();
    doc.lights.clear();
    let mut json: serde_json::Value = serde_json::from_str(&doc.to_json()).unwrap();
    json["materials"][0]["emissiveFactor"] = serde_json::json!([1.0, 1.0, 1.0]);
    json["materials"][0]["extensions"]["KHR_materials_emissive_strength"] =
        serde_json::json!({ "emissiveStrength": 5.0 });
    json["extensionsUsed"].as_array_mut().unwrap().push("KHR_materials_emissive_strength".into());
    // Emission on the glass is left out, with a warning.
    json["materials"][1]["emissiveFactor"] = serde_json::json!([0.5, 0.0, 0.0]);
    let path = dir.path().join("glowing.gltf");
    std::fs::write(&path, json.to_string()).unwrap();
    let scene = prismatic_cli::load_scene(path.to_str().unwrap()).unwrap();
    scene.validate().unwrap();
    assert!(scene.scene.lights.is_empty(), "no studio for a file lit by its own emission: {:?}", scene.scene.lights);
    let warnings = scene.warnings.join("\n");
    assert!(warnings.contains("materials[1] (glass): left out: emission of glass"), "{warnings}");
    assert!(!warnings.contains("materials[0]"), "{warnings}");
    assert_eq!(scene.scene.materials[0].kind.emission(), glam::Vec3::splat(5.0));
    let prepared = PreparedScene::new(scene.scene).unwrap();
    assert!(prepared.lights.iter().all(|l| matches!(l, Light::Area { .. })));
    // The 8 m × 8 m floor glows up at 5: π A L.
    let want = std::f32::consts::PI * 64.0 * 5.0;
    assert!((prepared.total_power - want).abs() < 1e-3 * want, "{} vs {want}", prepared.total_power);
    // Its photons reach the prism above it and make a caustic.
    let s = trace::trace_photons(&prepared, &mut prismatic_core::NoProgress).stats;
    assert!(s.specular_paths > 0, "{s:?}");
}

/// An emissive texture scales the emission by its mean linear colour (the
/// mesh's flux; its pattern is named as left out).
#[test]
fn an_emissive_texture_gives_its_mean_colour() {
    use prismatic_cli::gltf_write::GltfTexture;
    let dir = tempfile::tempdir().unwrap();
    let mut doc = prism_document();
    // Half the texels white, half black: a mean of ½ in linear light.
    doc.materials[0].base_color_texture = Some(GltfTexture {
        width: 2,
        height: 1,
        pixels: vec![[255, 255, 255], [0, 0, 0]],
        nearest: true,
        wrap: [10497, 10497],
    });
    doc.meshes[0].uvs = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    let mut json: serde_json::Value = serde_json::from_str(&doc.to_json()).unwrap();
    json["materials"][0]["emissiveFactor"] = serde_json::json!([2.0, 1.0, 4.0]);
    json["materials"][0]["emissiveTexture"] = json["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"].clone();
    let path = dir.path().join("screen.gltf");
    std::fs::write(&path, json.to_string()).unwrap();
    let scene = prismatic_cli::load_scene(path.to_str().unwrap()).unwrap();
    scene.validate().unwrap();
    assert_eq!(scene.scene.materials[0].kind.emission().to_array(), [1.0, 0.5, 2.0]);
    let warnings = scene.warnings.join("\n");
    assert!(warnings.contains("materials[0] (floor): left out: emissiveTexture's pattern"), "{warnings}");
}

/// glTF's metals are metals: a `metallicFactor` of 1 gives a metal of the
/// base colour and roughness; between 0 and 1 a metal blended with a
/// diffuse base by that metalness, nothing left out; 0 a diffuse surface.
#[test]
fn metallic_materials_are_metals_of_their_base_colour_and_roughness() {
    let dir = tempfile::tempdir().unwrap();
    let load = |metallic: f32| {
        let mut doc = prism_document();
        doc.materials[0] =
            GltfMaterial { metallic, roughness: 0.3, ..GltfMaterial::diffuse("ring", [1.0, 0.766, 0.336]) };
        let path = dir.path().join("metal.gltf");
        std::fs::write(&path, doc.to_json()).unwrap();
        let scene = prismatic_cli::load_scene(path.to_str().unwrap()).unwrap();
        scene.validate().unwrap();
        (scene.scene.materials[0].kind.clone(), scene.warnings.join("\n"))
    };
    let gold = prismatic_core::MetalColor::Rgb(prismatic_core::Vec3::new(1.0, 0.766, 0.336));
    let (kind, warnings) = load(1.0);
    assert_eq!(
        kind,
        MaterialKind::Metal { color: gold, roughness: 0.3, texture: None, film: None, metalness: Metalness::WHOLE }
    );
    assert!(!warnings.contains("metal"), "{warnings}");
    for m in [0.7, 0.2] {
        let (kind, warnings) = load(m);
        let metalness = Metalness::plain(m);
        assert_eq!(kind, MaterialKind::Metal { color: gold, roughness: 0.3, texture: None, film: None, metalness });
        assert!(warnings.is_empty(), "{warnings}");
    }
    let (kind, warnings) = load(0.0);
    assert!(matches!(kind, MaterialKind::Diffuse { .. }) && warnings.is_empty(), "{kind:?}, {warnings}");
}

/// glTF's non-metals are a diffuse base under a dielectric's specular
/// layer: F0 = ((n − 1)/(n + 1))² from `KHR_materials_ior` (0.04 at its
/// default 1.5) times `KHR_materials_specular`'s colour and factor, F90
/// its factor; a blended metal's base takes the layer too, and a factor of
/// 0 leaves a Lambertian surface (as prismatic writes its diffuse ones).
#[test]
fn a_non_metal_is_a_diffuse_base_under_its_specular_layer() {
    use prismatic_core::model::metalness::SpecularLayer;
    let dir = tempfile::tempdir().unwrap();
    let load = |metallic: f32, extensions: serde_json::Value| {
        let mut doc = prism_document();
        let paint = GltfMaterial::diffuse("paint", [0.2, 0.4, 0.6]);
        doc.materials[0] = GltfMaterial { metallic, specular: 1.0, roughness: 0.4, ..paint };
        let mut json: serde_json::Value = serde_json::from_str(&doc.to_json()).unwrap();
        json["materials"][0]["extensions"] = extensions;
        let path = dir.path().join("paint.gltf");
        std::fs::write(&path, json.to_string()).unwrap();
        let scene = prismatic_cli::load_scene(path.to_str().unwrap()).unwrap_or_else(|e| panic!("{e}"));
        scene.validate().unwrap_or_else(|e| panic!("{e}"));
        assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
        scene.scene.materials[0].kind.clone()
    };
    let paint = prismatic_core::MetalColor::Rgb(prismatic_core::Vec3::new(0.2, 0.4, 0.6));
    let close = |a: SpecularLayer, b: SpecularLayer| {
        (a.f0 - b.f0).abs().max_element() < 1e-6 && (a.f90, a.ior) == (b.f90, b.ior)
    };
    let layer_of = |kind: &MaterialKind, m: f32| match kind {
        MaterialKind::Metal { color, roughness: 0.4, texture: None, film: None, metalness }
            if *color == paint && metalness.factor == m && !metalness.mapped =>
        {
            metalness.layer.unwrap_or_else(|| panic!("a layer: {kind:?}"))
        }
        other => panic!("paint of metalness {m} under a layer: {other:?}"),
    };
    let default = SpecularLayer { f0: prismatic_core::Vec3::splat(0.04), f90: 1.0, ior: 1.5 };
    assert!(close(layer_of(&load(0.0, serde_json::json!({})), 0.0), default));
    assert!(close(layer_of(&load(0.5, serde_json::json!({})), 0.5), default), "a blended metal's base");
    let tinted = load(
        0.0,
        serde_json::json!({
            "KHR_materials_ior": { "ior": 2.0 },
            "KHR_materials_specular": { "specularFactor": 0.5, "specularColorFactor": [1.0, 0.5, 20.0] }
        }),
    );
    let want = SpecularLayer { f0: prismatic_core::Vec3::new(1.0 / 18.0, 1.0 / 36.0, 0.5), f90: 0.5, ior: 2.0 };
    assert!(close(layer_of(&tinted, 0.0), want), "{tinted:?}");
    let bare = load(0.0, serde_json::json!({ "KHR_materials_specular": { "specularFactor": 0.0 } }));
    assert!(matches!(bare, MaterialKind::Diffuse { .. }), "{bare:?}");
}

/// `KHR_materials_specular`'s textures vary the layer over the mesh:
/// `specularTexture`'s alpha (in every channel of the weight map) and
/// `specularColorTexture`'s colour, with the layer's unclipped F0 for the
/// colour map to scale; nothing is left out. One on another coordinate
/// set is named and left out, the other kept.
#[test]
fn specular_textures_vary_the_layer_over_the_mesh() {
    use prismatic_cli::gltf_write::GltfTexture;
    let dir = tempfile::tempdir().unwrap();
    let mut doc = prism_document();
    let satin = GltfTexture { width: 1, height: 1, pixels: vec![[200, 150, 60]], nearest: true, wrap: [10497; 2] };
    doc.materials[0] = GltfMaterial { base_color_texture: Some(satin), ..GltfMaterial::diffuse("satin", [1.0; 3]) };
    doc.meshes[0].uvs = vec![[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]];
    let mut json: serde_json::Value = serde_json::from_str(&doc.to_json()).unwrap();
    // An RGBA image beside the file, whose alpha (77) is the layer's weight.
    image::RgbaImage::from_raw(1, 1, vec![10, 20, 30, 77]).unwrap().save(dir.path().join("gloss.png")).unwrap();
    let images = json["images"].as_array_mut().unwrap();
    images.push(serde_json::json!({ "uri": "gloss.png" }));
    let source = images.len() - 1;
    let textures = json["textures"].as_array_mut().unwrap();
    textures.push(serde_json::json!({ "source": source }));
    let gloss = textures.len() - 1;
    json["materials"][0]["extensions"] = serde_json::json!({
        "KHR_materials_ior": { "ior": 2.0 },
        "KHR_materials_specular": {
            "specularFactor": 0.5,
            "specularColorFactor": [1.0, 2.0, 30.0],
            "specularTexture": { "index": gloss },
            "specularColorTexture": { "index": 0 }
        }
    });
    let used = json["extensionsUsed"].as_array_mut().unwrap();
    used.extend(["KHR_materials_ior".into(), "KHR_materials_specular".into()]);
    let load = |json: &serde_json::Value| {
        let path = dir.path().join("satin.gltf");
        std::fs::write(&path, json.to_string()).unwrap();
        prismatic_cli::load_scene(path.to_str().unwrap()).unwrap_or_else(|e| panic!("{e}"))
    };
    let scene = load(&json);
    scene.validate().unwrap_or_else(|e| panic!("{e}"));
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    let satin = &scene.scene.materials[0];
    let MaterialKind::Metal { metalness, .. } = &satin.kind else { panic!("a layered surface: {:?}", satin.kind) };
    assert_eq!(metalness.layer.map(|l| (l.f90, l.ior)), Some((0.5, 2.0)));
    let map = satin.specular_map.as_ref().expect("the layer's map");
    let texel = |t: &Option<prismatic_core::model::scene::Texture>| t.as_ref().expect("a map").texels[0];
    assert_eq!((texel(&map.weight), texel(&map.color)), (77 | 77 << 8 | 77 << 16, 200 | 150 << 8 | 60 << 16));
    let want = prismatic_core::Vec3::new(1.0, 2.0, 30.0) / 9.0;
    assert!((map.color_f0 - want).abs().max_element() < 1e-6, "{}", map.color_f0);
    // Another coordinate set: left out, named; the weight map stays.
    json["materials"][0]["extensions"]["KHR_materials_specular"]["specularColorTexture"]["texCoord"] = 1.into();
    let scene = load(&json);
    let map = scene.scene.materials[0].specular_map.as_ref().expect("the layer's map");
    assert!(map.weight.is_some() && map.color.is_none());
    let warnings = scene.warnings.join("\n");
    assert!(warnings.contains("specularColorTexture on a texture coordinate set other than 0"), "{warnings}");
}

/// A metal's `baseColorTexture` colours it texel by texel (its reflectance
/// at normal incidence is the base colour times the texture, sRGB), with
/// nothing left out; a roughness map moved otherwise than the base colour
/// (the mesh has one set of coordinates) is left out and named.
#[test]
fn a_metals_base_colour_texture_colours_its_reflectance() {
    use prismatic_cli::gltf_write::GltfTexture;
    let dir = tempfile::tempdir().unwrap();
    let texture = |pixels: Vec<[u8; 3]>| GltfTexture { width: 2, height: 1, pixels, nearest: true, wrap: [10497; 2] };
    let mut doc = prism_document();
    doc.materials[0] = GltfMaterial {
        metallic: 1.0,
        roughness: 0.5,
        base_color_texture: Some(texture(vec![[255, 200, 90], [180, 110, 60]])),
        metallic_roughness_texture: Some(texture(vec![[0, 128, 255]; 2])),
        ..GltfMaterial::diffuse("brass", [1.0, 0.9, 0.8])
    };
    doc.meshes[0].uvs = vec![[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]];
    let scene = load_valid(dir.path(), "brass.gltf", &doc);
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    let brass = &scene.scene.materials[0];
    let MaterialKind::Metal { color, roughness: 0.5, texture: Some(colour), film: None, metalness } = &brass.kind
    else {
        panic!("a textured metal: {:?}", brass.kind)
    };
    assert_eq!(*color, prismatic_core::MetalColor::Rgb(prismatic_core::Vec3::new(1.0, 0.9, 0.8)));
    assert_eq!(*metalness, Metalness::WHOLE);
    assert_eq!(colour.texels[..], [255 | 200 << 8 | 90 << 16, 180 | 110 << 8 | 60 << 16]);
    assert!(brass.roughness_map.is_some());
    let mut json: serde_json::Value = serde_json::from_str(&doc.to_json()).unwrap();
    json["materials"][0]["pbrMetallicRoughness"]["metallicRoughnessTexture"]["extensions"] =
        serde_json::json!({ "KHR_texture_transform": { "scale": [2.0, 2.0] } });
    let path = dir.path().join("moved.gltf");
    std::fs::write(&path, json.to_string()).unwrap();
    let scene = prismatic_cli::load_scene(path.to_str().unwrap()).unwrap();
    assert!(scene.scene.materials[0].roughness_map.is_none());
    let warnings = scene.warnings.join("\n");
    assert!(
        warnings.contains("metallicRoughnessTexture with another KHR_texture_transform than baseColorTexture"),
        "{warnings}"
    );
}

/// A `normalTexture` becomes the material's normal map (its bytes as they
/// are: a normal map is linear) with its `scale`, on any kind of material;
/// the mesh's `TANGENT` is read (turned by the node, w kept), and a mesh
/// with normals but no tangents gets MikkTSpace's. Coordinate set 1 or a
/// transform other than the base colour's leave it out with a warning.
#[test]
fn a_normal_texture_is_read_with_its_scale_and_tangents() {
    use prismatic_cli::gltf_write::GltfTexture;
    use prismatic_core::Vec4;
    let dir = tempfile::tempdir().unwrap();
    let mut doc = prism_document();
    let bumps = GltfTexture { width: 1, height: 1, pixels: vec![[160, 120, 240]], nearest: false, wrap: [10497; 2] };
    doc.materials[0].normal_texture = Some((bumps.clone(), 0.7));
    doc.materials[0].metallic = 1.0;
    doc.meshes[0].uvs = vec![[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]];
    doc.meshes[0].normals = vec![[0.0, 1.0, 0.0]; 4];
    let load = |name: &str, doc: &GltfDocument| load_valid(dir.path(), name, doc);
    let scene = load("bumpy_metal.gltf", &doc);
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    let floor = &scene.scene.materials[0];
    assert!(matches!(floor.kind, MaterialKind::Metal { .. }), "{:?}", floor.kind);
    let map = floor.normal_map.as_ref().expect("the floor's normal map");
    assert_eq!((map.scale, map.texture.texels[0]), (0.7, 160 | 120 << 8 | 240 << 16));
    // The floor lies in y = 0, u along +x and v along −z, so up the image is +z: MikkTSpace's
    // tangent is +x and, as cross(+y, +x) is −z, its handedness w is −1.
    let Shape::Mesh { tangents, .. } = &scene.scene.objects[0].shape else { panic!("a mesh") };
    assert_eq!(tangents.len(), 4);
    for t in tangents {
        assert!((*t - Vec4::new(1.0, 0.0, 0.0, -1.0)).abs().max_element() < 1e-6, "{t}");
    }
    // The file's own tangents win.
    doc.meshes[0].tangents = vec![[0.0, 0.0, 1.0, 1.0]; 4];
    doc.meshes[0].translation = [0.0, 2.0, 0.0];
    let scene = load("with_tangents.gltf", &doc);
    let Shape::Mesh { tangents, .. } = &scene.scene.objects[0].shape else { panic!("a mesh") };
    assert_eq!(tangents, &vec![Vec4::new(0.0, 0.0, 1.0, 1.0); 4]);
    // Another coordinate set: left out, named.
    let mut json: serde_json::Value = serde_json::from_str(&doc.to_json()).unwrap();
    json["materials"][0]["normalTexture"]["texCoord"] = 1.into();
    let path = dir.path().join("set1.gltf");
    std::fs::write(&path, json.to_string()).unwrap();
    let scene = prismatic_cli::load_scene(path.to_str().unwrap()).unwrap();
    assert!(scene.scene.materials[0].normal_map.is_none());
    let warnings = scene.warnings.join("\n");
    assert!(warnings.contains("normalTexture on a texture coordinate set other than 0"), "{warnings}");
    // A diffuse floor whose base colour and normal map are moved differently.
    doc.materials[0].metallic = 0.0;
    doc.materials[0].base_color_texture = Some(bumps);
    let mut json: serde_json::Value = serde_json::from_str(&doc.to_json()).unwrap();
    json["materials"][0]["normalTexture"]["extensions"] =
        serde_json::json!({ "KHR_texture_transform": { "scale": [2.0, 2.0] } });
    std::fs::write(&path, json.to_string()).unwrap();
    let scene = prismatic_cli::load_scene(path.to_str().unwrap()).unwrap();
    assert!(scene.scene.materials[0].normal_map.is_none());
    let warnings = scene.warnings.join("\n");
    assert!(warnings.contains("normalTexture with another KHR_texture_transform"), "{warnings}");
}

/// glTF's `metallicRoughnessTexture` (linear): its green channel scales a
/// metal's or glass's roughness texel by texel (the material's roughness
/// map), its blue channel times `metallicFactor` is the metalness that
/// blends the metal with a diffuse base texel by texel (a material with no
/// metal anywhere is diffuse); a diffuse surface has no roughness to scale.
#[test]
fn a_metallic_roughness_texture_scales_roughness_and_says_what_is_metal() {
    use prismatic_cli::gltf_write::GltfTexture;
    let dir = tempfile::tempdir().unwrap();
    let texture = |pixels: Vec<[u8; 3]>| GltfTexture { width: 2, height: 1, pixels, nearest: true, wrap: [10497; 2] };
    let mut doc = prism_document();
    doc.materials[0].metallic = 1.0;
    doc.materials[0].roughness = 0.8;
    doc.materials[0].metallic_roughness_texture = Some(texture(vec![[0, 40, 255], [0, 200, 255]]));
    doc.meshes[0].uvs = vec![[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]];
    let load = |name: &str, doc: &GltfDocument| load_valid(dir.path(), name, doc);
    let scene = load("scuffed_metal.gltf", &doc);
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    let metal = &scene.scene.materials[0];
    assert!(matches!(metal.kind, MaterialKind::Metal { roughness: 0.8, .. }), "{:?}", metal.kind);
    let map = metal.roughness_map.as_ref().expect("the metal's roughness map");
    assert_eq!(map.texels[..], [40 << 8 | 255 << 16, 200 << 8 | 255 << 16]);
    let metalness = |m: &prismatic_core::model::scene::Material| match m.kind {
        MaterialKind::Metal { metalness, .. } => metalness,
        _ => panic!("a metal: {:?}", m.kind),
    };
    assert_eq!(metalness(metal), Metalness::WHOLE, "blue 255 everywhere: a whole metal");
    // Metal over three quarters of it: blended texel by texel by the blue channel.
    doc.materials[0].metallic_roughness_texture = Some(GltfTexture {
        width: 4,
        pixels: vec![[0, 90, 255], [0, 90, 255], [0, 90, 255], [0, 90, 0]],
        ..texture(Vec::new())
    });
    let scene = load("chipped_metal.gltf", &doc);
    assert_eq!(metalness(&scene.scene.materials[0]), Metalness { mapped: true, ..Metalness::WHOLE });
    assert!(scene.scene.materials[0].roughness_map.is_some() && scene.warnings.is_empty(), "{:?}", scene.warnings);
    // A metallicFactor of 0.4 over a blue of 255: a metalness of 0.4 everywhere.
    doc.materials[0].metallic = 0.4;
    doc.materials[0].metallic_roughness_texture = Some(texture(vec![[0, 90, 255]; 2]));
    let scene = load("half_metal.gltf", &doc);
    assert_eq!(metalness(&scene.scene.materials[0]), Metalness::plain(0.4));
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    // A non-metal's texture (blue 0) leaves nothing out.
    doc.materials[0].metallic = 1.0;
    doc.materials[0].metallic_roughness_texture = Some(texture(vec![[0, 90, 0]; 2]));
    let scene = load("plastic.gltf", &doc);
    assert!(matches!(scene.scene.materials[0].kind, MaterialKind::Diffuse { .. }));
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    // Frosted glass takes the green channel too (on the open floor, a sheet).
    doc.materials[0] = GltfMaterial {
        roughness: 0.6,
        metallic_roughness_texture: Some(texture(vec![[0, 128, 0]; 2])),
        ..GltfMaterial::glass("frosted", 1.5, 0.0)
    };
    let scene = load("frosted.gltf", &doc);
    let glass = &scene.scene.materials[scene.scene.objects[0].material];
    assert!(matches!(glass.kind, MaterialKind::Dielectric { thin: true, roughness: 0.6, .. }), "{:?}", glass.kind);
    assert!(glass.roughness_map.is_some());
    assert!(!scene.warnings.join("\n").contains("metallicRoughnessTexture"), "{:?}", scene.warnings);
}
