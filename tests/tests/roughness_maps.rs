//! Roughness maps (glTF's `metallicRoughnessTexture`, green channel) on
//! every backend: a texel's green scales a metal's or rough glass's
//! roughness there, so a surface is as rough as each texel says. The
//! closed forms are the ones `metals.rs` and `rough_glass.rs` hold plain
//! roughness to: half of a rough metal's reflection within 2·atan α of
//! the mirror direction (head on), half of each band's refraction within
//! its median facet's deviation.

use crate::rough_glass::{INDICES, beam_into_a_block, median_radius, radii_of_band, rough};
use prismatic_core::model::dispersion::Dispersion;
use prismatic_core::model::metalness::Metalness;
use prismatic_core::model::scene::{Filter, Light, Material, MaterialKind, Sampler, Shape, Texture};
use prismatic_core::{MetalColor, PreparedScene, Scene, Vec3};
use prismatic_tests::backends::{every_backend, frame, trace};
use prismatic_tests::{
    TRIANGLE_WITH_UVS, UNIT_SPHERE, beam_onto_a_wall, one_material_scene_file, prepare, view_through_a_sheet,
};

/// An image of one row of texels whose green channels are `greens`
/// (red and blue 0: glTF's non-metal), read nearest.
fn greens(greens: &[u8]) -> Texture {
    Texture {
        name: "roughness".into(),
        width: greens.len() as u32,
        height: 1,
        texels: greens.iter().map(|&g| u32::from(g) << 8).collect::<Vec<u32>>().into(),
        sampler: Sampler { filter: Filter::Nearest, ..Sampler::default() },
    }
}

/// A metal reflecting every facet's light (F0 = 1) of `roughness`, scaled by `map`.
fn metal(roughness: f32, map: Option<Texture>) -> Material {
    let kind = MaterialKind::Metal {
        color: MetalColor::Rgb(Vec3::ONE),
        roughness,
        texture: None,
        film: None,
        metalness: Metalness::WHOLE,
    };
    Material { roughness_map: map, ..Material::new("metal", kind) }
}

/// A thin beam along +x meets `metal` head on at (0, 0, `z`): a 2×2
/// square in the plane x = 0 whose texture coordinates run u from 0 to 1
/// along +z; what it reflects lands on a white wall at x = −3.
pub(crate) fn beam_at_a_square(metal: Material, z: f32, photons: u32) -> PreparedScene {
    let corners = [(-1.0, -1.0), (-1.0, 1.0), (1.0, 1.0), (1.0, -1.0)];
    let square = Shape::Mesh {
        positions: corners.iter().map(|&(y, z)| Vec3::new(0.0, y, z)).collect(),
        triangles: vec![[0, 1, 2], [0, 2, 3]],
        uvs: corners.iter().map(|&(y, z)| [(z + 1.0) * 0.5, (1.0 - y) * 0.5].into()).collect(),
        normals: Vec::new(),
        tangents: Vec::new(),
    };
    let mut scene: Scene = beam_onto_a_wall(photons, metal, square).scene;
    scene.lights = vec![Light::Beam {
        position: Vec3::new(-1.0, 0.0, z),
        direction: Vec3::X,
        radius: 1e-3,
        power: 1.0,
        spectrum: Default::default(),
    }];
    scene.objects[1].shape = Shape::Plane { point: Vec3::new(-3.0, 0.0, 0.0), normal: Vec3::X };
    prepare(scene)
}

/// The share of the photons of `scene` landing on the wall within `radius`
/// of (y, z) = (0, `z`), on each backend.
fn shares_within(scene: &PreparedScene, z: f32, radius: f64, photons: u32) -> Vec<(String, f64)> {
    every_backend()
        .into_iter()
        .map(|mut backend| {
            let map = trace(backend.as_mut(), scene);
            let offset = |p: &[f32; 3]| f64::from(p[1]).hypot(f64::from(p[2] - z));
            let inside = map.photons.iter().filter(|p| offset(&p.position) < radius).count();
            (backend.name().to_string(), inside as f64 / f64::from(photons))
        })
        .collect()
}

/// A metal of roughness 0.8 under a map of two texels: green 0 (u < ½:
/// polished there) and green 128 (u > ½: roughness 0.8 · 128/255). The
/// beam on the second texel spreads as that roughness does; on the first
/// it comes straight back.
#[test]
fn a_maps_green_scales_a_metals_roughness_texel_by_texel() {
    const PHOTONS: u32 = 20_000;
    let roughness = 0.8f64 * (128.0 / 255.0);
    let alpha = roughness * roughness;
    let radius = 3.0 * (2.0 * alpha.atan()).tan();
    let mapped = || metal(0.8, Some(greens(&[0, 128])));
    let rough = beam_at_a_square(mapped(), 0.5, PHOTONS);
    for (name, inside) in shares_within(&rough, 0.5, radius, PHOTONS) {
        let sd = (0.25 / f64::from(PHOTONS)).sqrt();
        assert!((inside - 0.5).abs() < 5.0 * sd, "{name}: {inside:.4} within {radius:.4}, not half");
    }
    let polished = beam_at_a_square(mapped(), -0.5, PHOTONS);
    for (name, inside) in shares_within(&polished, -0.5, 0.01, PHOTONS) {
        assert!(inside > 0.999, "{name}: only {inside:.4} straight back off the polished texel");
    }
}

/// Frosted glass of roughness 1 under a map of green 179 (roughness
/// 179/255 ≈ 0.70) spreads each band by its own index as glass of that
/// roughness does.
#[test]
fn a_maps_green_scales_rough_glasss_roughness() {
    const PHOTONS: u32 = 14_000;
    let (roughness, floor) = (179.0f64 / 255.0, 1.0f32);
    let alpha = roughness * roughness;
    let glass =
        Material { roughness_map: Some(greens(&[179])), ..rough(Dispersion::PerBand(INDICES.to_vec()), false, 1.0) };
    let scene = beam_into_a_block(glass, PHOTONS, floor);
    for mut backend in every_backend() {
        let name = backend.name();
        let map = trace(backend.as_mut(), &scene);
        for (band, n) in INDICES.iter().enumerate() {
            let radii = radii_of_band(&map, band);
            let median = median_radius(alpha, f64::from(*n), f64::from(floor));
            let share = radii.iter().filter(|&&r| r < median).count() as f64 / radii.len() as f64;
            let sd = (0.25 / radii.len() as f64).sqrt();
            assert!((share - 0.5).abs() < 5.0 * sd, "{name}, band {band} (n {n}): {share:.4} within the median");
        }
    }
}

/// Seen by the camera, a surface under a map of one green texel is the
/// surface of the roughness it scales to: a rough metal's and a frosted
/// sheet's highlights of a point light (of 1 kW, beside the camera), and
/// what they scatter toward the camera, on every backend.
#[test]
fn in_view_a_uniform_map_is_the_roughness_it_scales_to() {
    let scale = 153.0 / 255.0;
    let sheet = |roughness: f32, map: Option<Texture>| Material {
        roughness_map: map,
        ..rough(Dispersion::Constant(1.5), true, roughness)
    };
    let cases = [
        ("rough metal", metal(0.9, Some(greens(&[153]))), metal(0.9 * scale, None)),
        ("frosted sheet", sheet(0.9, Some(greens(&[153]))), sheet(0.9 * scale, None)),
    ];
    for (case, mapped, plain) in cases {
        let lit = |material: Material| prepare(lit_beside_the_camera(view_through_a_sheet(material).scene));
        assert_the_same_images(case, &lit(mapped), &lit(plain), 0.1);
    }
}

/// `scene` lit by a point light of 1 kW beside its camera instead.
pub(crate) fn lit_beside_the_camera(mut scene: Scene) -> Scene {
    scene.lights = vec![Light::Point {
        position: Vec3::new(-5.0, 0.0, 5.0),
        power: 1000.0,
        spectrum: Default::default(),
        range: None,
    }];
    scene
}

/// On every backend, the image of `got` is that of `want` within 1e-4 of
/// its brightest pixel, which is above `lit`.
pub(crate) fn assert_the_same_images(case: &str, got: &PreparedScene, want: &PreparedScene, lit: f32) {
    for mut backend in every_backend() {
        let name = backend.name();
        let (_, got) = frame(backend.as_mut(), got);
        let (_, want) = frame(backend.as_mut(), want);
        let brightest = want.pixels.iter().map(|p| p.max_element()).fold(0.0, f32::max);
        assert!(brightest > lit, "{case}: {name}: nothing lit ({brightest})");
        for (g, w) in got.pixels.iter().zip(&want.pixels) {
            assert!((*g - *w).abs().max_element() < 1e-4 * brightest, "{case}: {name}: {g} where {w}");
        }
    }
}

/// A scene file gives a metal or a dielectric a `roughness_map` (a PNG
/// beside it, its green read as linear bytes); what makes no sense is
/// refused with its key.
#[test]
fn scene_files_give_metals_and_glass_roughness_maps() {
    let dir = tempfile::tempdir().unwrap();
    image::RgbImage::from_raw(1, 1, vec![10, 90, 200]).unwrap().save(dir.path().join("scuffs.png")).unwrap();
    let check = |material: &str, shape: &str| one_material_scene_file(dir.path(), material, shape);
    let (quad, sphere) = (TRIANGLE_WITH_UVS, UNIT_SPHERE);
    let metal_file = "kind = \"metal\"\ncolor = \"gold\"\nroughness = 0.5\nroughness_map = \"scuffs.png\"";
    let glass_file = "kind = \"dielectric\"\nior = 1.5\nthin = true\nroughness = 0.5\nroughness_map = \"scuffs.png\"";
    for material in [metal_file, glass_file] {
        let doc = check(material, quad).unwrap_or_else(|e| panic!("{e}"));
        let map = doc.scene.materials[0].roughness_map.as_ref().expect("the roughness map");
        assert_eq!(map.texels[0], 10 | 90 << 8 | 200 << 16);
    }
    for (material, shape, key, reason) in [
        ("kind = \"diffuse\"\nroughness_map = \"scuffs.png\"", quad, "material.m.roughness_map", "unknown key"),
        (&metal_file.replace("scuffs", "missing"), quad, "material.m.roughness_map", "cannot read texture"),
        (metal_file, sphere, "object[0].material", "roughness map"),
    ] {
        let e = check(material, shape).map(|_| ()).unwrap_err();
        assert!(e.key == key && e.reason.contains(reason), "{material} / {shape}: {e}");
    }
    // A library's scene: a mirror has no roughness to scale.
    let mut scene = view_through_a_sheet(metal(0.5, Some(greens(&[90])))).scene;
    scene.materials[0].kind = MaterialKind::Mirror;
    let e = scene.validate().unwrap_err();
    assert!(e.key.ends_with("roughness_map") && e.reason.contains("has none"), "{e}");
}
