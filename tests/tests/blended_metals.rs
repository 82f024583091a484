//! Metals blended with a diffuse base by a metalness m (glTF's
//! metallic-roughness model), on every backend: the camera sees (1 − m)
//! of a diffuse surface of the metal's colour and m of the whole metal;
//! photons are stored on it whatever m is, and m of them go on as the
//! metal.

use crate::metals::{GOLD, assert_beam_goes_on, folded_beam, metal_in_view, schlick};
use prismatic_core::model::bands::BandSpec;
use prismatic_core::model::metalness::Metalness;
use prismatic_core::model::scene::{Material, MaterialKind, Shape};
use prismatic_core::{MetalColor, Vec3};
use prismatic_tests::backends::{every_backend, frame, trace};
use prismatic_tests::{TRIANGLE_WITH_UVS, prepare};

/// A polished metal of colour `color` and metalness `metalness`.
fn blended(color: Vec3, metalness: Metalness) -> Material {
    let kind =
        MaterialKind::Metal { color: MetalColor::Rgb(color), roughness: 0.0, texture: None, film: None, metalness };
    Material::new("blended", kind)
}

/// A diffuse surface of albedo `albedo`.
fn diffuse(albedo: Vec3) -> Material {
    Material::new("diffuse", MaterialKind::Diffuse { albedo, checker: None, texture: None, emission: Vec3::ZERO })
}

#[test]
fn in_view_a_blended_metal_is_the_mix_of_its_diffuse_base_and_the_whole_metal() {
    let m = 0.3;
    let image = |material: Material, backend: &mut dyn prismatic_core::Backend| {
        frame(backend, &prepare(metal_in_view(material))).1.pixels
    };
    for mut backend in every_backend() {
        let name = backend.name();
        let whole = image(blended(GOLD, Metalness::WHOLE), backend.as_mut());
        let base = image(diffuse(GOLD), backend.as_mut());
        let mixed = image(blended(GOLD, Metalness::plain(m)), backend.as_mut());
        for (k, got) in mixed.iter().enumerate() {
            let want = (1.0 - m) * base[k] + m * whole[k];
            let tolerance = 1e-4 * want.max_element().max(1.0);
            assert!((*got - want).abs().max_element() < tolerance, "{name}, pixel {k}: {got}, want {want}");
        }
        // The diffuse part is seen: the mix differs from the whole metal.
        assert!((mixed[4] - whole[4]).abs().max_element() > 0.01, "{name}: {} vs {}", mixed[4], whole[4]);
    }
}

#[test]
fn a_blended_metal_passes_on_its_metalness_share_of_the_light() {
    const PHOTONS: u32 = 20_000;
    let m = 0.4;
    let scene = prepare(folded_beam(blended(Vec3::splat(0.6), Metalness::plain(m)), PHOTONS, BandSpec::Paper7));
    let want = f64::from(m) * schlick(0.6, std::f64::consts::FRAC_1_SQRT_2);
    assert_beam_goes_on(&scene, PHOTONS, want, "m × Schlick's");
}

#[test]
fn photons_are_stored_on_a_blended_metal_whatever_its_metalness() {
    const PHOTONS: u32 = 5_000;
    let mirror = Material::new("mirror", MaterialKind::Mirror);
    for m in [0.0, 0.5, 1.0] {
        // The beam folded by a mirror onto a blended wall (metalness 1 and
        // no map: a whole metal, which stores nothing).
        let mut scene = folded_beam(mirror.clone(), PHOTONS, BandSpec::Paper7);
        scene.materials[scene.objects[1].material] = blended(Vec3::splat(0.8), Metalness::plain(m));
        let Shape::Plane { .. } = scene.objects[1].shape else { unreachable!("the wall") };
        let scene = prepare(scene);
        for mut backend in every_backend() {
            let name = backend.name();
            let map = trace(backend.as_mut(), &scene);
            let on_wall = map.photons.iter().filter(|p| (p.pos().y - 3.0).abs() < 1e-3).count();
            let want = if m < 1.0 { PHOTONS as usize } else { 0 };
            assert_eq!(on_wall, want, "{name}, metalness {m}");
        }
    }
}

/// A scene file blends a metal with `metalness` (glTF's `metallicFactor`)
/// and reads it texel by texel from its `roughness_map`'s blue channel
/// with `metalness_from_map`; a metalness outside 0 to 1, or one read
/// from a map the metal lacks, is refused with its key.
#[test]
fn scene_files_blend_metals_by_their_metalness() {
    let dir = tempfile::tempdir().unwrap();
    image::RgbImage::from_raw(1, 1, vec![0, 255, 128]).unwrap().save(dir.path().join("worn.png")).unwrap();
    let check = |material: &str| prismatic_tests::one_material_scene_file(dir.path(), material, TRIANGLE_WITH_UVS);
    let metalness = |material: &str| match check(material).unwrap_or_else(|e| panic!("{e}")).scene.materials[0].kind {
        MaterialKind::Metal { metalness, .. } => metalness,
        ref other => panic!("a metal: {other:?}"),
    };
    let metal = "kind = \"metal\"\ncolor = [0.9, 0.6, 0.3]";
    assert_eq!(metalness(metal), Metalness::WHOLE);
    assert_eq!(metalness(&format!("{metal}\nmetalness = 0.25")), Metalness::plain(0.25));
    let mapped = format!("{metal}\nroughness = 0.5\nroughness_map = \"worn.png\"\nmetalness_from_map = true");
    assert_eq!(metalness(&mapped), Metalness { mapped: true, ..Metalness::WHOLE });
    for (material, reason) in [
        (format!("{metal}\nmetalness = 1.5"), "between 0 and 1"),
        (format!("{metal}\nmetalness_from_map = true"), "no roughness_map"),
    ] {
        let e = check(&material).map(|_| ()).unwrap_err();
        assert!(e.key == "material.m.metalness" && e.reason.contains(reason), "{material}: {e}");
    }
}
