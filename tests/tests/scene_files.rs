//! Scene files: the built-in scenes parse and validate, and bad files get a
//! message with the file, the key, the line and the reason.

use prismatic_cli::builtin::BUILTIN_SCENES;
use prismatic_cli::scene_file::{SceneFileError, parse};
use prismatic_core::model::bands::BandSpec;
use prismatic_core::model::dispersion::{Dispersion, Glass};
use prismatic_core::model::metalness::Metalness;
use prismatic_core::model::scene::{Estimator, MaterialKind, PhotonSequence, Shape, ThinFilm, WavelengthSampling};
use prismatic_core::{MetalColor, NamedMetal, Vec3};

const MINIMAL: &str = r#"
[camera]
position = [0, 1, 5]
look_at = [0, 0, 0]

[[light]]
kind = "point"
position = [0, 4, 0]
power = 10

[material.white]
kind = "diffuse"

[[object]]
shape = "plane"
material = "white"
point = [0, 0, 0]
normal = [0, 1, 0]
"#;

fn error_of(source: &str) -> SceneFileError {
    match parse(source, "test.toml", None) {
        Ok(doc) => doc.validate().expect_err("the scene should be rejected"),
        Err(e) => e,
    }
}

/// Asserts the error names `key` on the first line containing `at` (no line
/// when `at` is `None`) and says `reason`.
fn assert_error(source: &str, key: &str, at: Option<&str>, reason: &str) {
    let line = at.map(|text| {
        source.lines().position(|l| l.contains(text)).unwrap_or_else(|| panic!("{text:?} is not in the source")) + 1
    });
    let e = error_of(source);
    assert_eq!(e.file, "test.toml");
    assert_eq!(e.key, key, "{e}");
    assert_eq!(e.line, line, "{e}");
    assert!(e.reason.contains(reason), "reason {:?} should contain {reason:?}", e.reason);
    let shown = e.to_string();
    assert!(shown.starts_with("test.toml:") && shown.contains(key), "{shown}");
}

#[test]
fn built_in_scenes_parse_and_validate() {
    for b in &BUILTIN_SCENES {
        let doc = parse(b.source, b.name, None).unwrap_or_else(|e| panic!("{e}"));
        doc.validate().unwrap_or_else(|e| panic!("{e}"));
        let lit = !doc.scene.lights.is_empty() || doc.scene.objects.iter().any(|o| doc.scene.emits(o));
        assert!(!doc.scene.objects.is_empty() && lit, "{}", b.name);
    }
}

#[test]
fn the_minimal_scene_gets_defaults() {
    let doc = parse(MINIMAL, "m.toml", None).unwrap();
    doc.validate().unwrap();
    let r = &doc.scene.render;
    assert_eq!(r.width, 400);
    // The fastest configuration that converges to the true spectrum.
    assert_eq!((r.bands, r.wavelengths, r.light_tracing), (BandSpec::Physical(32), WavelengthSampling::Hero, true));
    assert_eq!((r.estimator, r.photon_sequence), (Estimator::Density, PhotonSequence::Sobol));
    assert_eq!(doc.scene.camera.fov_deg, 45.0);
}

#[test]
fn every_ior_form_parses() {
    let forms = [
        ("1.5", Dispersion::Constant(1.5)),
        ("\"bk7\"", Glass::Bk7.dispersion()),
        ("{ cauchy = [1.5, 0.004] }", Dispersion::Cauchy { a: 1.5, b: 0.004 }),
        ("{ abbe = [1.5168, 64.17] }", Dispersion::Abbe { nd: 1.5168, vd: 64.17 }),
        (
            "{ sellmeier = { b = [1.0, 0.2], c = [0.006, 0.02] } }",
            Dispersion::Sellmeier { b: vec![1.0, 0.2], c: vec![0.006, 0.02] },
        ),
        (
            "{ bands = [1.5, 1.51, 1.52, 1.53, 1.54, 1.55, 1.56] }",
            Dispersion::PerBand(vec![1.5, 1.51, 1.52, 1.53, 1.54, 1.55, 1.56]),
        ),
    ];
    for (text, expected) in forms {
        // Seven bands, for the per-band form's seven indices.
        let source = format!(
            "[render]\nbands = \"paper7\"\n{MINIMAL}\n[material.g]\nkind = \"dielectric\"\nior = {text}\n\n[[object]]\nshape = \"sphere\"\nmaterial = \"g\"\ncenter = [0, 1, 0]\nradius = 0.5\n"
        );
        let doc = parse(&source, "ior.toml", None).unwrap_or_else(|e| panic!("{text}: {e}"));
        doc.validate().unwrap_or_else(|e| panic!("{text}: {e}"));
        let g = doc.scene.materials.iter().find(|m| m.name == "g").unwrap();
        assert_eq!(
            g.kind,
            MaterialKind::Dielectric {
                dispersion: expected,
                outside: Dispersion::Constant(1.0),
                attenuation: None,
                thin: false,
                film: None,
                roughness: 0.0,
            },
            "{text}"
        );
    }
}

#[test]
fn inline_meshes_and_prisms_parse() {
    let source = format!(
        "{MINIMAL}\n[[object]]\nshape = \"mesh\"\nmaterial = \"white\"\npositions = [[0,0,0],[1,0,0],[0,1,0]]\ntriangles = [[0,1,2]]\n\n\
         [[object]]\nshape = \"prism\"\nmaterial = \"white\"\nvertices = [[0,0,0],[1,0,0],[0,1,0]]\nextrude = [0,0,1]\n"
    );
    let doc = parse(&source, "shapes.toml", None).unwrap();
    doc.validate().unwrap();
    assert!(matches!(&doc.scene.objects[1].shape, Shape::Mesh { triangles, .. } if triangles == &vec![[0, 1, 2]]));
    assert!(matches!(doc.scene.objects[2].shape, Shape::Prism { .. }));
}

#[test]
fn syntax_errors_name_the_line() {
    let e = error_of("[camera]\nposition = [0, 1\n");
    assert_eq!(e.line, Some(2), "{e}");
    assert!(e.reason.contains("syntax"), "{e}");
}

#[test]
fn unknown_keys_are_rejected() {
    let source = MINIMAL.replace("kind = \"point\"", "kind = \"point\"\ncolour = [1, 1, 1]");
    assert_error(&source, "light[0].colour", Some("colour"), "unknown key");
    assert_error(&format!("{MINIMAL}\n[renderer]\nwidth = 3\n"), "renderer", Some("[renderer]"), "unknown key");
}

#[test]
fn wrong_types_are_rejected() {
    assert_error(
        &MINIMAL.replace("power = 10", "power = \"bright\""),
        "light[0].power",
        Some("power ="),
        "must be a number",
    );
    assert_error(
        &MINIMAL.replace("position = [0, 1, 5]", "position = [0, 1]"),
        "camera.position",
        Some("position = [0, 1]"),
        "three numbers",
    );
    assert_error(&format!("[render]\nwidth = 1.5\n{MINIMAL}"), "render.width", Some("width"), "whole number");
}

#[test]
fn values_that_make_no_sense_are_rejected_with_their_line() {
    assert_error(&MINIMAL.replace("power = 10", "power = nan"), "light[0].power", Some("power ="), "finite");
    assert_error(&MINIMAL.replace("power = 10", "power = -1"), "light[0].power", Some("power ="), "greater than 0");
    assert_error(
        &MINIMAL.replace("normal = [0, 1, 0]", "normal = [0, 0, 0]"),
        "object[0].normal",
        Some("normal ="),
        "zero-length",
    );
    assert_error(&format!("[render]\nbands = 0\n{MINIMAL}"), "render.bands", Some("bands ="), "1 to 256");
    assert_error(&format!("[render]\nbands = 300\n{MINIMAL}"), "render.bands", Some("bands ="), "1 to 256");
    assert_error(&format!("[render]\nradius = inf\n{MINIMAL}"), "render.radius", Some("radius ="), "finite");
    assert_error(&format!("[render]\nphotons = 4000000000\n{MINIMAL}"), "render.photons", Some("photons ="), "memory");
    assert_error(
        &format!("[render]\ntone_map = \"aces\"\n{MINIMAL}"),
        "render.tone_map",
        Some("tone_map"),
        "clamp, reinhard, pbr_neutral or agx",
    );
}

#[test]
fn missing_and_unknown_materials_are_rejected() {
    assert_error(
        &MINIMAL.replace("material = \"white\"", "material = \"chalk\""),
        "object[0].material",
        Some("chalk"),
        "unknown material \"chalk\"",
    );
    let dielectric_plane = MINIMAL.replace("kind = \"diffuse\"", "kind = \"dielectric\"\nior = 1.5");
    assert_error(&dielectric_plane, "object[0].material", Some("material = \"white\""), "closed shape");
    assert_error(
        &MINIMAL.replace("[[object]]\nshape = \"plane\"\n", "[[object]]\n"),
        "object[0].shape",
        Some("[[object]]"),
        "missing",
    );
}

#[test]
fn per_band_tables_must_match_the_band_count() {
    let source = format!(
        "[render]\nbands = \"paper3\"\n{MINIMAL}\n[material.g]\nkind = \"dielectric\"\nior = {{ bands = [1.5, 1.6] }}\n\n\
         [[object]]\nshape = \"sphere\"\nmaterial = \"g\"\ncenter = [0, 1, 0]\nradius = 0.5\n"
    );
    assert_error(&source, "material.g.ior.bands", Some("ior = "), "3 bands");
}

#[test]
fn unknown_glass_names_list_the_known_ones() {
    let source = format!(
        "{MINIMAL}\n[material.g]\nkind = \"dielectric\"\nior = \"unobtainium\"\n\n[[object]]\nshape = \"sphere\"\nmaterial = \"g\"\ncenter = [0, 1, 0]\nradius = 0.5\n"
    );
    assert_error(&source, "material.g.ior", Some("unobtainium"), "bk7");
}

#[test]
fn the_guides_example_is_a_valid_scene() {
    let guide = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/src/guide/scene-files.md");
    let section = std::fs::read_to_string(guide).unwrap();
    let start = section.find("```toml\n").expect("the scene-file guide has a TOML example") + "```toml\n".len();
    let example = &section[start..start + section[start..].find("```").unwrap()];
    let doc = parse(example, "scene-files.md", None).unwrap_or_else(|e| panic!("{e}"));
    doc.validate().unwrap_or_else(|e| panic!("{e}"));
}

/// A glass scene whose `ior` is `{ table = "glass.csv" }`, read from `dir`.
fn table_scene(dir: &std::path::Path, csv: &str) -> Result<prismatic_cli::scene_file::SceneDocument, SceneFileError> {
    std::fs::write(dir.join("glass.csv"), csv).unwrap();
    let source = format!(
        "[render]\nbands = 64\n{MINIMAL}\n[material.g]\nkind = \"dielectric\"\nior = {{ table = \"glass.csv\" }}\n\n\
         [[object]]\nshape = \"sphere\"\nmaterial = \"g\"\ncenter = [0, 1, 0]\nradius = 0.5\n"
    );
    let doc = parse(&source, "test.toml", Some(dir))?;
    doc.validate()?;
    Ok(doc)
}

/// N-BK7 sampled every 10 nm from 370 to 790 nm, wavelengths in µm (as
/// refractiveindex.info exports), with `edit` applied to the rows.
fn bk7_csv(edit: impl Fn(&mut Vec<(f32, f32)>)) -> String {
    let bk7 = Glass::Bk7.dispersion();
    let mut rows: Vec<(f32, f32)> =
        (37..=79).map(|k| (k as f32 / 100.0, bk7.ior_at(k as f32 * 10.0).unwrap())).collect();
    edit(&mut rows);
    rows.iter().fold(String::from("wl,n\n"), |s, (l, n)| s + &format!("{l},{n}\n"))
}

#[test]
fn measured_tables_are_read_from_csv_next_to_the_scene() {
    let dir = tempfile::tempdir().unwrap();
    let doc = table_scene(dir.path(), &bk7_csv(|_| {})).unwrap_or_else(|e| panic!("{e}"));
    let g = doc.scene.materials.iter().find(|m| m.name == "g").unwrap();
    let MaterialKind::Dielectric { dispersion: table @ Dispersion::Table { .. }, .. } = &g.kind else {
        panic!("{:?}", g.kind)
    };
    // Linear between rows 10 nm apart: within 2e-5 of the Sellmeier curve.
    let (bands, bk7) = (prismatic_core::model::bands::BandTable::new(BandSpec::Physical(64)), Glass::Bk7.dispersion());
    for b in 0..bands.len() {
        let (got, want) = (table.ior_for_band(&bands, b), bk7.ior_for_band(&bands, b));
        assert!((got - want).abs() < 2e-5, "band {b}: {got} vs {want}");
    }
}

#[test]
fn bad_measured_tables_name_the_file_line_and_reason() {
    let dir = tempfile::tempdir().unwrap();
    let cases: [(String, &str); 5] = [
        (bk7_csv(|r| r.swap(3, 4)), "glass.csv:6: wavelengths must increase: 0.4 after 0.41"),
        (bk7_csv(|r| r[5].1 = f32::NAN), "glass.csv:7: \"NaN\" is not a finite number"),
        (bk7_csv(|r| r.retain(|(l, _)| *l >= 0.4)), "covers 400–790 nm; it must cover the visible range 380–780 nm"),
        (bk7_csv(|r| r[2].1 = 0.5), "row 3: an index of refraction must be between 1 and 5, got 0.5"),
        ("wl,n\n".into(), "glass.csv:1: has no rows"),
    ];
    for (csv, reason) in cases {
        let e = table_scene(dir.path(), &csv).map(|_| ()).expect_err(reason);
        assert_eq!(e.key, "material.g.ior.table", "{e}");
        assert!(e.reason.contains(reason), "{e}: expected {reason:?}");
    }
}

/// A sphere of coloured glass beside `MINIMAL`'s floor; `keys` are the glass's extra lines.
fn coloured_glass(keys: &str) -> String {
    format!(
        "{MINIMAL}\n[material.amber]\nkind = \"dielectric\"\nior = 1.5\n{keys}\n\n[[object]]\nshape = \"sphere\"\nmaterial = \"amber\"\ncenter = [0, 1, 0]\nradius = 0.5\n"
    )
}

#[test]
fn coloured_glass_parses_and_bad_attenuation_is_rejected_with_its_line() {
    let doc =
        parse(&coloured_glass("attenuation_color = [0.9, 0.5, 0.2]\nattenuation_distance = 2"), "test.toml", None)
            .expect("parses");
    doc.validate().expect("valid");
    let amber = doc.scene.materials.iter().find(|m| m.name == "amber").expect("the amber material");
    let MaterialKind::Dielectric { attenuation: Some(a), .. } = &amber.kind else {
        panic!("coloured glass expected, got {:?}", amber.kind)
    };
    assert_eq!((a.color.to_array(), a.distance), ([0.9, 0.5, 0.2], 2.0));
    assert_error(
        &coloured_glass("attenuation_color = [0.9, 0.5, 0.2]"),
        "material.amber.attenuation_distance",
        Some("[material.amber]"),
        "missing",
    );
    assert_error(
        &coloured_glass("attenuation_color = [0.9, 0, 0.2]\nattenuation_distance = 2"),
        "material.amber.attenuation_color",
        Some("attenuation_color"),
        "(0, 1]",
    );
    assert_error(
        &coloured_glass("attenuation_color = [0.9, 0.5, 0.2]\nattenuation_distance = -2"),
        "material.amber.attenuation_distance",
        Some("attenuation_distance"),
        "greater than 0",
    );
}

#[test]
fn a_films_keys_parse_and_bad_films_are_rejected_with_their_line() {
    let film_of = |keys: &str| {
        let doc = parse(&coloured_glass(keys), "test.toml", None).expect("parses");
        doc.validate().expect("valid");
        let amber = doc.scene.materials.iter().find(|m| m.name == "amber").expect("the amber material");
        let MaterialKind::Dielectric { film, .. } = amber.kind else { panic!("glass expected, got {:?}", amber.kind) };
        film
    };
    assert_eq!(film_of("film_thickness_nm = 300\nfilm_ior = 2.4"), Some(ThinFilm::new(2.4, 300.0)));
    // The index defaults to glTF's iridescenceIor.
    assert_eq!(film_of("film_thickness_nm = 300"), Some(ThinFilm::new(1.3, 300.0)));
    let part = film_of("film_thickness_nm = 300\nfilm_factor = 0.25");
    assert_eq!(part, Some(ThinFilm { factor: 0.25, ..ThinFilm::new(1.3, 300.0) }));
    assert_eq!(film_of(""), None);
    assert_error(&coloured_glass("film_ior = 2.4"), "material.amber.film_ior", Some("film_ior"), "film_thickness_nm");
    let factor_alone = coloured_glass("film_factor = 0.5");
    assert_error(&factor_alone, "material.amber.film_factor", Some("film_factor"), "film_thickness_nm");
    assert_error(
        &coloured_glass("film_thickness_nm = 300\nfilm_factor = 1.5"),
        "material.amber.film_factor",
        Some("film_factor"),
        "0 to 1",
    );
    assert_error(
        &coloured_glass("film_thickness_nm = -5"),
        "material.amber.film_thickness_nm",
        Some("film_thickness_nm"),
        "0 to 20000 nm",
    );
    assert_error(
        &coloured_glass("film_thickness_nm = 300\nfilm_ior = 0.5"),
        "material.amber.film_ior",
        Some("film_ior"),
        "between 1 and 5",
    );
}

fn with_metal(keys: &str) -> String {
    format!(
        "{MINIMAL}\n[material.ring]\nkind = \"metal\"\n{keys}\n\n[[object]]\nshape = \"sphere\"\nmaterial = \"ring\"\ncenter = [0, 1, 0]\nradius = 0.5\n"
    )
}

#[test]
fn a_metals_keys_parse_named_metals_too_and_bad_metals_are_rejected_with_their_line() {
    let metal_of = |keys: &str| {
        let doc = parse(&with_metal(keys), "test.toml", None).expect("parses");
        doc.validate().expect("valid");
        doc.scene.materials.iter().find(|m| m.name == "ring").expect("the ring material").kind.clone()
    };
    assert_eq!(
        metal_of("color = [0.9, 0.6, 0.5]\nroughness = 0.3"),
        MaterialKind::Metal {
            color: MetalColor::Rgb(Vec3::new(0.9, 0.6, 0.5)),
            roughness: 0.3,
            texture: None,
            film: None,
            metalness: Metalness::WHOLE,
        }
    );
    // A measured metal; polished unless a roughness is given.
    assert_eq!(
        metal_of("color = \"gold\""),
        MaterialKind::Metal {
            color: MetalColor::Measured(NamedMetal::Gold),
            roughness: 0.0,
            texture: None,
            film: None,
            metalness: Metalness::WHOLE,
        }
    );
    assert_error(&with_metal("roughness = 0.3"), "material.ring.color", Some("[material.ring]"), "missing");
    assert_error(
        &with_metal("color = \"brass\""),
        "material.ring.color",
        Some("color"),
        "silver, aluminium, gold, copper",
    );
    assert_error(&with_metal("color = [0.9, 1.2, 0.5]"), "material.ring.color", Some("color"), "at most all light");
    assert_error(
        &with_metal("color = \"gold\"\nroughness = 1.5"),
        "material.ring.roughness",
        Some("roughness"),
        "between 0 and 1",
    );
    assert_error(&with_metal("color = \"gold\"\nior = 1.5"), "material.ring.ior", Some("ior"), "unknown key");
}

#[test]
fn frosted_glass_parses_and_a_roughness_out_of_range_is_rejected_with_its_line() {
    let glass = |keys: &str| {
        format!(
            "{MINIMAL}\n[material.frosted]\nkind = \"dielectric\"\nior = 1.5\n{keys}\n\n[[object]]\nshape = \"sphere\"\nmaterial = \"frosted\"\ncenter = [0, 1, 0]\nradius = 0.5\n"
        )
    };
    let doc = parse(&glass("roughness = 0.4"), "test.toml", None).expect("parses");
    doc.validate().expect("valid");
    let kind = &doc.scene.materials.iter().find(|m| m.name == "frosted").expect("the glass").kind;
    assert!(matches!(kind, MaterialKind::Dielectric { roughness, .. } if *roughness == 0.4), "{kind:?}");
    for bad in ["roughness = 1.5", "roughness = -0.1"] {
        assert_error(&glass(bad), "material.frosted.roughness", Some("roughness"), "between 0 and 1");
    }
}

#[test]
fn a_sun_parses_and_needs_a_direction_and_a_positive_irradiance() {
    let sun = "kind = \"sun\"\ndirection = [1, -2, 0]\nirradiance = 5";
    let source = MINIMAL.replace("kind = \"point\"\nposition = [0, 4, 0]\npower = 10", sun);
    let doc = parse(&source, "test.toml", None).expect("parses");
    doc.validate().expect("valid");
    assert!(matches!(doc.scene.lights[0], prismatic_core::model::scene::Light::Sun { irradiance: 5.0, .. }));
    assert_error(
        &source.replace("irradiance = 5", "irradiance = 0"),
        "light[0].irradiance",
        Some("irradiance"),
        "greater than 0",
    );
    assert_error(&source.replace("irradiance = 5", "power = 5"), "light[0].power", Some("power"), "unknown key");
}

/// `MINIMAL`'s floor replaced by a textured quad: `material` is the
/// textured material's extra lines, `mesh` the quad's (positions,
/// triangles, and uvs or an OBJ path).
fn textured(material: &str, mesh: &str) -> String {
    let floor = "[[object]]\nshape = \"plane\"\nmaterial = \"white\"\npoint = [0, 0, 0]\nnormal = [0, 1, 0]\n";
    let quad = "positions = [[-1, 0, -1], [1, 0, -1], [1, 0, 1], [-1, 0, 1]]\ntriangles = [[0, 2, 1], [0, 3, 2]]";
    let mesh = mesh.replace("QUAD", quad);
    MINIMAL.replace(floor, "")
        + &format!(
            "[material.tiles]\nkind = \"diffuse\"\n{material}\n\n[[object]]\nshape = \"mesh\"\nmaterial = \"tiles\"\n{mesh}\n"
        )
}

/// A 2×1 PNG (red, then blue) in `dir`.
fn write_png(dir: &std::path::Path, name: &str) {
    image::RgbImage::from_raw(2, 1, vec![255, 0, 0, 0, 0, 255]).unwrap().save(dir.join(name)).unwrap();
}

#[test]
fn textures_are_read_beside_the_scene_with_their_sampler_and_the_mesh_uvs() {
    use prismatic_core::model::scene::{Filter, Wrap};
    let dir = tempfile::tempdir().unwrap();
    write_png(dir.path(), "tiles.png");
    let source = textured(
        "texture = \"tiles.png\"\ntexture_filter = \"nearest\"\ntexture_wrap = \"mirrored_repeat\"",
        "QUAD\nuvs = [[0, 0], [2, 0], [2, 2], [0, 2]]",
    );
    let doc = parse(&source, "test.toml", Some(dir.path())).unwrap_or_else(|e| panic!("{e}"));
    doc.validate().unwrap_or_else(|e| panic!("{e}"));
    let tiles = doc.scene.materials.iter().find(|m| m.name == "tiles").unwrap();
    let MaterialKind::Diffuse { albedo, texture: Some(t), .. } = &tiles.kind else { panic!("{:?}", tiles.kind) };
    assert_eq!(*albedo, prismatic_core::Vec3::ONE, "an image shows as it is by default");
    assert_eq!((t.width, t.height, &t.texels[..]), (2, 1, &[255, 255 << 16][..]));
    assert_eq!(
        (t.sampler.filter, t.sampler.wrap_u, t.sampler.wrap_v),
        (Filter::Nearest, Wrap::MirroredRepeat, Wrap::MirroredRepeat)
    );
    let Some(Shape::Mesh { uvs, .. }) = doc.scene.objects.last().map(|o| &o.shape) else { panic!("a mesh") };
    assert_eq!(uvs[2].to_array(), [2.0, 2.0]);
}

#[test]
fn obj_texture_coordinates_reach_the_mesh() {
    let dir = tempfile::tempdir().unwrap();
    write_png(dir.path(), "tiles.png");
    let obj = "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nvt 0 1\nvt 1 1\nvt 1 0\nvt 0 0\nf 1/1 3/3 2/2\nf 1/1 4/4 3/3\n";
    std::fs::write(dir.path().join("quad.obj"), obj).unwrap();
    let doc = parse(&textured("texture = \"tiles.png\"", "path = \"quad.obj\""), "test.toml", Some(dir.path()))
        .unwrap_or_else(|e| panic!("{e}"));
    doc.validate().unwrap_or_else(|e| panic!("{e}"));
    let Some(Shape::Mesh { uvs, positions, .. }) = doc.scene.objects.last().map(|o| &o.shape) else { panic!("a mesh") };
    // OBJ's v runs up the image: vt (0, 1) is the image's top-left corner, glTF's (0, 0).
    assert_eq!(uvs[0].to_array(), [0.0, 0.0]);
    assert_eq!(positions[0].to_array(), [-1.0, 0.0, -1.0]);
}

#[test]
fn bad_textures_name_the_image_key_and_reason() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("broken.png"), b"not a png").unwrap();
    write_png(dir.path(), "tiles.png");
    let with_uvs = "QUAD\nuvs = [[0, 0], [1, 0], [1, 1], [0, 1]]";
    let cases = [
        (textured("texture = \"missing.png\"", with_uvs), "material.tiles.texture", "cannot read texture"),
        (textured("texture = \"broken.png\"", with_uvs), "material.tiles.texture", "broken.png"),
        (
            textured("texture = \"tiles.png\"\ntexture_wrap = \"tile\"", with_uvs),
            "material.tiles.texture_wrap",
            "unknown wrap",
        ),
        (textured("texture_filter = \"nearest\"", with_uvs), "material.tiles.texture_filter", "names none"),
        (textured("texture = \"tiles.png\"", "QUAD"), "object[0].material", "texture coordinates (uvs)"),
        (
            textured("texture = \"tiles.png\"", "QUAD\nuvs = [[0, 0], [1, 0]]"),
            "object[0].uvs",
            "2 texture coordinates for 4 positions",
        ),
        (
            textured("texture = \"tiles.png\"", "QUAD\nuvs = [[0, 0], [1, 0], [1], [0, 1]]"),
            "object[0].uvs[2]",
            "must be [u, v]",
        ),
    ];
    for (source, key, reason) in cases {
        let e = match parse(&source, "test.toml", Some(dir.path())) {
            Ok(doc) => doc.validate().expect_err(reason),
            Err(e) => e,
        };
        assert_eq!(e.key, key, "{e}");
        assert!(e.reason.contains(reason), "{e}: expected {reason:?}");
    }
}

/// `MINIMAL`'s light with `spectrum = VALUE` (and the render settings `render`).
fn lit_by(value: &str, render: &str) -> String {
    let light = format!("kind = \"point\"\nposition = [0, 4, 0]\npower = 10\nspectrum = {value}");
    format!("[render]\n{render}\n{}", MINIMAL.replace("kind = \"point\"\nposition = [0, 4, 0]\npower = 10", &light))
}

#[test]
fn light_spectra_parse_in_every_form_and_bad_ones_are_rejected() {
    use prismatic_core::model::spectrum::{Illuminant, Lamp, Spectrum};
    for (value, expected) in [
        ("\"D65\"", Spectrum::Illuminant(Illuminant::D65)),
        ("\"a\"", Spectrum::Illuminant(Illuminant::A)),
        ("\"F11\"", Spectrum::Illuminant(Illuminant::F11)),
        ("\"E\"", Spectrum::EqualEnergy),
        ("\"mercury\"", Spectrum::Lamp(Lamp::Mercury)),
        ("\"Hydrogen\"", Spectrum::Lamp(Lamp::Hydrogen)),
        ("{ blackbody = 2700 }", Spectrum::Blackbody { kelvin: 2700.0 }),
        ("{ nm = [400, 700], power = [1, 2] }", Spectrum::Tabulated { nm: vec![400.0, 700.0], power: vec![1.0, 2.0] }),
        ("{ rgb = [1, 0.5, 0.2] }", Spectrum::from_rgb([1.0, 0.5, 0.2]).0),
        ("{ rgb = [0.5, 0.5, 0.5] }", Spectrum::EqualEnergy),
    ] {
        let doc = parse(&lit_by(value, "bands = 16"), "test.toml", None).unwrap_or_else(|e| panic!("{value}: {e}"));
        doc.validate().unwrap_or_else(|e| panic!("{value}: {e}"));
        assert_eq!(doc.scene.lights[0].spectrum(), &expected, "{value}");
    }
    let bad = |value: &str, key: &str, reason: &str| {
        assert_error(&lit_by(value, "bands = 16"), key, Some("spectrum"), reason);
    };
    bad("\"D50\"", "light[0].spectrum", "unknown spectrum \"D50\"; expected a name (E, D65, A, F11, mercury");
    bad("{ blackbody = 100 }", "light[0].spectrum.blackbody", "between 500 and 100000 K");
    bad("{ blackbody = 3000, nm = [400] }", "light[0].spectrum.nm", "unknown key; expected blackbody");
    bad("{ nm = [400, 500], power = [1] }", "light[0].spectrum", "as many powers as wavelengths");
    bad("{ nm = [500, 400], power = [1, 1] }", "light[0].spectrum.nm", "strictly increasing");
    bad("{ nm = [400, 500], power = [1, -1] }", "light[0].spectrum.power", "not negative");
    bad("{ nm = [800, 900], power = [1, 1] }", "light[0].spectrum", "no power between 380 and 780 nm");
    bad("3", "light[0].spectrum", "must be a name");
    bad("{ rgb = [1, -0.5, 0] }", "light[0].spectrum.rgb", "no negative channel");
    bad("{ rgb = [1, 0, 0], blackbody = 3000 }", "light[0].spectrum.rgb", "unknown key; expected blackbody");
    // The paper's presets colour by their bands, made for white light.
    let paper = lit_by("\"mercury\"", "bands = \"paper7\"\nwavelengths = \"hero\"");
    assert_error(&paper, "light[0].spectrum", Some("spectrum"), "needs physically based bands");
    let split = lit_by("\"mercury\"", "bands = \"paper7\"\nwavelengths = \"split\"");
    parse(&split, "test.toml", None).unwrap().validate().expect("the paper's split bands take a lamp's band shares");
}
