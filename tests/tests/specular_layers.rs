//! A diffuse base under a dielectric's specular layer (glTF's non-metals,
//! and the base of its blended metals), on every backend: the camera sees
//! Schlick's reflection from F0 to F90 over the base's share 1 − max F;
//! photons reflect off the layer with its Fresnel, and what it does not
//! reflect reaches the base.

use crate::metals::{GOLD, assert_beam_goes_on, folded_beam, metal_in_view, schlick};
use crate::thin_film::assert_band_shares;
use prismatic_core::model::bands::{BandSpec, BandTable};
use prismatic_core::model::metalness::{Metalness, SpecularLayer};
use prismatic_core::model::scene::{Light, Material, MaterialKind, ThinFilm};
use prismatic_core::{MetalColor, PreparedScene, Vec3};
use prismatic_tests::backends::{every_backend, frame, trace};
use prismatic_tests::{TRIANGLE_WITH_UVS, prepare};
use std::f64::consts::FRAC_1_SQRT_2;

/// glTF's default layer: F0 0.04, F90 1.
fn gltf_layer() -> SpecularLayer {
    SpecularLayer::gltf(1.5, 1.0, Vec3::ONE).unwrap()
}

/// A polished surface of colour `color` (the base's albedo and the metal's
/// F0), metalness `m`, its base under glTF's default layer.
fn layered(color: Vec3, m: f32) -> Material {
    let metalness = Metalness { layer: Some(gltf_layer()), ..Metalness::plain(m) };
    let kind =
        MaterialKind::Metal { color: MetalColor::Rgb(color), roughness: 0.0, texture: None, film: None, metalness };
    Material::new("layered", kind)
}

/// A polished metal of colour `color` and metalness `m`, no layer.
fn blended(color: Vec3, m: f32) -> Material {
    let metalness = if m >= 1.0 { Metalness::WHOLE } else { Metalness::plain(m) };
    let kind =
        MaterialKind::Metal { color: MetalColor::Rgb(color), roughness: 0.0, texture: None, film: None, metalness };
    Material::new("blended", kind)
}

/// glTF's default layer's Fresnel at cosine `cos`, in f64: Schlick's from 0.04 to 1.
fn layer_fresnel(cos: f64) -> f64 {
    schlick(0.04, cos)
}

/// [`metal_in_view`] under a light bright enough that the diffuse base's
/// pixel weighs in these tests' comparisons (under the shared scene's
/// light of power 1 it is about 3e-4, and a wrong base share changed the
/// pixel by less than their tolerances).
fn lit_in_view(material: Material) -> PreparedScene {
    let mut scene = metal_in_view(material);
    let Light::Point { power, .. } = &mut scene.lights[0] else { unreachable!("metal_in_view's point light") };
    *power = 1000.0;
    prepare(scene)
}

/// The camera sees the base's share (1 − m)(1 − F) of the diffuse image,
/// m of the whole metal's and (1 − m) F of the background the layer
/// reflects (radiance 1), F the layer's Fresnel at 45°.
#[test]
fn in_view_a_polished_layer_reflects_schlicks_share_over_its_base() {
    let f = layer_fresnel(FRAC_1_SQRT_2) as f32;
    let image = |material: Material, backend: &mut dyn prismatic_core::Backend| {
        frame(backend, &lit_in_view(material)).1.pixels[4]
    };
    for mut backend in every_backend() {
        let name = backend.name();
        let base = image(blended(GOLD, 0.0), backend.as_mut());
        assert!(base.max_element() > 0.1, "{name}: the base is lit: {base}");
        let whole = image(blended(GOLD, 1.0), backend.as_mut());
        for m in [0.0f32, 0.5] {
            let got = image(layered(GOLD, m), backend.as_mut());
            let want = (1.0 - m) * (1.0 - f) * base + m * whole + Vec3::splat((1.0 - m) * f);
            let tolerance = 1e-4 * want.max_element().max(1.0);
            assert!((got - want).abs().max_element() < tolerance, "{name}, metalness {m}: {got}, want {want}");
        }
        // The layer shows: a plastic is not its bare base.
        let plastic = image(layered(GOLD, 0.0), backend.as_mut());
        assert!((plastic - base).abs().max_element() > 0.02, "{name}: {plastic} vs {base}");
    }
}

/// A beam meeting a polished layered disc at 45° goes on with the specular
/// part's Fresnel: m Schlick(F0 metal) + (1 − m) F_layer. (The plan aims
/// no caustic photons at a plastic, so its caustic is traced on a plan
/// that simulates everything.)
#[test]
fn a_polished_layer_reflects_its_fresnel_share_of_a_beam() {
    const PHOTONS: u32 = 20_000;
    for m in [0.0f32, 0.4] {
        let mut scene = prepare(folded_beam(layered(Vec3::splat(0.6), m), PHOTONS, BandSpec::Paper7));
        scene.simulate_everything();
        let m64 = f64::from(m);
        let want = m64 * schlick(0.6, FRAC_1_SQRT_2) + (1.0 - m64) * layer_fresnel(FRAC_1_SQRT_2);
        assert_beam_goes_on(&scene, PHOTONS, want, &format!("metalness {m}"));
    }
}

/// Indirect light's photons, the beam on a layered disc of base albedo a
/// at 45°, one bounce allowed: the layer reflects F and passes the rest
/// to the base, whose roulette absorbs 1 − a of it, so (1 − F)(1 − a) of
/// the flux is absorbed (without the pass, all that the layer does not
/// reflect would be lost).
#[test]
fn what_a_layer_does_not_reflect_reaches_its_base() {
    const PHOTONS: u32 = 20_000;
    let albedo = 0.5;
    let mut scene = folded_beam(layered(Vec3::splat(albedo), 0.0), 0, BandSpec::Paper7);
    (scene.render.indirect_photons, scene.render.max_depth) = (PHOTONS, 1);
    let scene = prepare(scene);
    let want = (1.0 - layer_fresnel(FRAC_1_SQRT_2)) * (1.0 - f64::from(albedo));
    for mut backend in every_backend() {
        let name = backend.name();
        let s = trace(backend.as_mut(), &scene).stats;
        let got = s.flux_absorbed / s.flux_emitted;
        let sd = (want * (1.0 - want) / f64::from(PHOTONS)).sqrt();
        assert!((got - want).abs() < 5.0 * sd, "{name}: {got:.4} absorbed, want {want:.4}; {s:?}");
        let balance = s.flux_absorbed + s.flux_escaped + s.flux_depth_limited - s.flux_emitted;
        assert!(balance.abs() < 1e-4 * s.flux_emitted, "{name}: {s:?}");
    }
}

/// The film of [`filmed_plastic`]: a high-index coating.
const FILM: ThinFilm = ThinFilm::new(2.4, 300.0);

/// A polished plastic of albedo `albedo` under glTF's default layer (a base
/// of index 1.5) and [`FILM`] on it (glTF's iridescence on a non-metal).
fn filmed_plastic(albedo: Vec3) -> Material {
    let mut material = layered(albedo, 0.0);
    let MaterialKind::Metal { film, .. } = &mut material.kind else { unreachable!("a layered base") };
    *film = Some(FILM);
    material
}

/// [`FILM`]'s reflectance over a base of index 1.5 for light meeting it at
/// cosine `cos`, at `lambda_nm`: the mean of the s and p Airy sums with
/// real amplitudes (no total reflection here), in f64.
fn filmed_layer(cos: f64, lambda_nm: f64) -> f64 {
    let (n0, n1, n2, d) = (1.0, f64::from(FILM.ior), 1.5, f64::from(FILM.thickness_nm));
    let sin2 = 1.0 - cos * cos;
    let (c0, c1, c2) = (cos, (1.0 - sin2 / (n1 * n1)).sqrt(), (1.0 - sin2 / (n2 * n2)).sqrt());
    let airy = |r01: f64, r12: f64| {
        let phase = (4.0 * std::f64::consts::PI * n1 * d * c1 / lambda_nm).cos();
        (r01 * r01 + r12 * r12 + 2.0 * r01 * r12 * phase) / (1.0 + r01 * r01 * r12 * r12 + 2.0 * r01 * r12 * phase)
    };
    let s = airy((n0 * c0 - n1 * c1) / (n0 * c0 + n1 * c1), (n1 * c1 - n2 * c2) / (n1 * c1 + n2 * c2));
    let p = airy((n1 * c0 - n0 * c1) / (n1 * c0 + n0 * c1), (n2 * c1 - n1 * c2) / (n2 * c1 + n1 * c2));
    0.5 * (s + p)
}

/// Under a film the layer reflects each wavelength by the film's Airy sum
/// over the base: a beam at 45° on a filmed plastic goes on band by band
/// with it (photons split into the bands there), and in view a white path
/// takes Σ C_b F(λ_b) of the background and the base the rest's share
/// 1 − max of that.
#[test]
fn a_film_on_a_layer_reflects_each_wavelength_by_its_airy_sum() {
    const PHOTONS: u32 = 20_000;
    let bands = BandTable::new(BandSpec::Paper7);
    let want: Vec<f64> = bands.bands().iter().map(|b| filmed_layer(FRAC_1_SQRT_2, f64::from(b.lambda_nm))).collect();
    let (lo, hi) = want.iter().fold((1.0f64, 0.0f64), |(lo, hi), &r| (lo.min(r), hi.max(r)));
    assert!(hi - lo > 0.2, "the film colours the light: {want:?}");
    let mut beam = prepare(folded_beam(filmed_plastic(Vec3::splat(0.6)), PHOTONS, BandSpec::Paper7));
    beam.simulate_everything();
    let tint: Vec3 = bands.bands().iter().zip(&want).map(|(b, &r)| b.weight * r as f32).sum();
    let image = |material: Material, backend: &mut dyn prismatic_core::Backend| {
        frame(backend, &lit_in_view(material)).1.pixels[4]
    };
    for mut backend in every_backend() {
        let name = backend.name();
        let map = trace(backend.as_mut(), &beam);
        assert_band_shares(&map, PHOTONS, &want, &format!("{name}, went on"));
        let base = image(blended(GOLD, 0.0), backend.as_mut());
        assert!(base.max_element() > 0.1, "{name}: the base is lit: {base}");
        let got = image(filmed_plastic(GOLD), backend.as_mut());
        let expected = tint + (1.0 - tint.max_element()) * base;
        assert!((got - expected).abs().max_element() < 2e-4, "{name}: {got}, want {expected}");
    }
}

/// A plastic is no caustic caster to aim at: a scene of a light and
/// layered surfaces alone plans no caustics, and a plastic beside glass
/// is not one of its specular objects.
#[test]
fn the_plan_aims_photons_at_metals_and_glass_not_at_plastics() {
    let mut scene = folded_beam(layered(Vec3::splat(0.6), 0.0), 1000, BandSpec::Paper7);
    let plan = |scene: &prismatic_core::Scene| PreparedScene::new(scene.clone()).unwrap().plan.clone();
    let caustics = plan(&scene).caustics;
    assert!(!caustics.on && caustics.reason.contains("no mirror or glass"), "{caustics:?}");
    scene.materials[0] = layered(Vec3::splat(0.6), 0.3);
    assert!(plan(&scene).caustics.on, "some metal: a caster");
}

/// A scene file's diffuse surface takes a specular layer with `specular`,
/// `specular_ior` and `specular_color` (and then `roughness`); a metal's
/// base too; what cannot be is refused with its key.
#[test]
fn scene_files_put_a_specular_layer_on_a_diffuse_surface() {
    let dir = tempfile::tempdir().unwrap();
    let check = |material: &str| prismatic_tests::one_material_scene_file(dir.path(), material, TRIANGLE_WITH_UVS);
    let kind =
        |material: &str| check(material).unwrap_or_else(|e| panic!("{material}: {e}")).scene.materials[0].kind.clone();
    let paint = "kind = \"diffuse\"\nalbedo = [0.2, 0.4, 0.6]";
    let MaterialKind::Metal { color, roughness, metalness, .. } =
        kind(&format!("{paint}\nspecular = 1\nroughness = 0.3"))
    else {
        panic!("a layered diffuse surface")
    };
    assert_eq!((color, roughness), (MetalColor::Rgb(Vec3::new(0.2, 0.4, 0.6)), 0.3));
    assert_eq!(metalness, Metalness::layered(gltf_layer()));
    let MaterialKind::Metal { metalness, .. } =
        kind(&format!("{paint}\nspecular_ior = 2.0\nspecular_color = [1, 0.5, 1]"))
    else {
        panic!("a layered diffuse surface")
    };
    let f0 = metalness.layer.unwrap().f0;
    assert!((f0 - Vec3::new(1.0, 0.5, 1.0) / 9.0).abs().max_element() < 1e-6, "{f0}");
    assert!(matches!(kind(paint), MaterialKind::Diffuse { .. }), "no layer without its keys");
    let metal = "kind = \"metal\"\ncolor = [0.9, 0.6, 0.3]\nmetalness = 0.5\nspecular = 0.5";
    let MaterialKind::Metal { metalness, .. } = kind(metal) else { panic!("a metal") };
    assert_eq!(metalness.layer.map(|l| l.f90), Some(0.5));
    for (material, key, reason) in [
        (format!("{paint}\nspecular = 1.5"), "specular", "between 0 and 1"),
        (format!("{paint}\nroughness = 0.3"), "roughness", "give specular"),
        (format!("{paint}\nfilm_thickness_nm = 300"), "film_thickness_nm", "give specular"),
        (format!("{paint}\nspecular = 1\nemission = [1, 1, 1]"), "emission", "specular layer"),
        (format!("{paint}\nspecular_ior = nan"), "specular_ior", "at least 1"),
        (format!("{paint}\nspecular_color = [1, -1, 1]"), "specular_color", "between 0 and specular"),
        ("kind = \"diffuse\"\nspecular = 1\nalbedo = [0.5, -0.1, 0.5]".into(), "albedo", "not be negative"),
    ] {
        let e = check(&material).map(|_| ()).expect_err(&material);
        assert!(e.key == format!("material.m.{key}") && e.reason.contains(reason), "{material}: {e}");
    }
}
