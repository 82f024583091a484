//! The CPU backend against the scalar reference: photon maps and images on
//! every built-in scene and on random scenes, and independence of the
//! thread count.

use prismatic_cli::load_scene;
use prismatic_core::{Backend, PreparedScene, ReferenceBackend};
use prismatic_cpu::CpuBackend;
use prismatic_tests::backends::trace;
use prismatic_tests::parity::{Output, assert_parity, parity_photons};
use prismatic_tests::random_scene::random_scene;

/// The parity test body, written once: any backend against the reference.
fn check(case: &str, scene: &PreparedScene, backend: &mut dyn Backend) {
    let expected = Output::frame(&mut ReferenceBackend, scene);
    let got = Output::frame(backend, scene);
    assert!(got.map.is_canonical(), "{case}: {} map not in canonical order", got.backend);
    assert!(
        !expected.map.photons.is_empty() || scene.scene.render.photons == 0,
        "{case}: no caustic photons to compare"
    );
    assert_parity(case, scene, &expected, &got);
}

/// Every built-in scene (`prismatic_cli::builtin::names`).
#[test]
fn cpu_matches_the_reference_on_every_built_in_scene() {
    for name in prismatic_cli::builtin::names() {
        let mut doc = load_scene(name).unwrap();
        doc.scene.render.photons = parity_photons(name);
        doc.scene.render.width = 96;
        doc.scene.render.height = 96;
        let scene = PreparedScene::new(doc.scene).unwrap();
        check(&format!("cpu-{name}"), &scene, &mut CpuBackend::new());
    }
}

/// Coloured lights: their photons start as paths at the light (the CPU
/// backend hands them to the core's tracer), their direct light in colour.
#[test]
fn cpu_matches_the_reference_under_coloured_lights() {
    for (case, scene) in prismatic_tests::parity::coloured_light_scenes() {
        check(&format!("cpu-{case}"), &scene, &mut CpuBackend::new());
    }
}

#[test]
fn cpu_matches_the_reference_on_random_scenes() {
    for seed in 1..=16 {
        let scene = PreparedScene::new(random_scene(seed, 3_000, 40)).unwrap_or_else(|e| panic!("seed {seed}: {e}"));
        check(&format!("cpu-random-{seed}"), &scene, &mut CpuBackend::new());
    }
}

#[test]
fn cpu_photon_map_and_image_do_not_depend_on_the_thread_count() {
    let scene = PreparedScene::new(random_scene(3, 20_000, 48)).unwrap();
    let outputs: Vec<Output> =
        [1, 2, 3].map(|t| Output::frame(&mut CpuBackend::with_threads(t).unwrap(), &scene)).into();
    for o in &outputs[1..] {
        assert_eq!(o.map.photons, outputs[0].map.photons);
        assert_eq!(o.image.pixels, outputs[0].image.pixels);
    }
}

#[test]
fn cpu_matches_the_reference_with_projection_maps_on_every_light_kind() {
    use prismatic_core::model::scene::{Light, Object, Shape};
    use prismatic_core::{Glass, Vec3};
    use prismatic_tests::{camera, glass, settings, white};
    // A wide beam, a wide spot and a point light over two small glass spheres:
    // every light gets a projection map, and the light choice mixes them.
    let scene = prismatic_core::Scene {
        render: settings(6_000, prismatic_core::BandSpec::Paper7),
        camera: camera(),
        lights: vec![
            Light::Beam {
                position: Vec3::new(0.0, 6.0, 0.0),
                direction: -Vec3::Y,
                radius: 3.0,
                power: 5.0,
                spectrum: Default::default(),
            },
            Light::Spot {
                position: Vec3::new(-3.0, 5.0, 1.0),
                direction: Vec3::new(3.0, -4.0, -1.0),
                cone_deg: 50.0,
                inner_cone_deg: 50.0,
                power: 5.0,
                spectrum: Default::default(),
                range: None,
            },
            Light::Point { position: Vec3::new(2.0, 4.0, 2.0), power: 5.0, spectrum: Default::default(), range: None },
        ],
        materials: vec![glass("glass", Glass::Bk7.dispersion()), white("floor")],
        objects: vec![
            Object { shape: Shape::Sphere { center: Vec3::new(0.0, 1.0, 0.0), radius: 0.5 }, material: 0 },
            Object { shape: Shape::Sphere { center: Vec3::new(1.2, 0.7, -0.5), radius: 0.4 }, material: 0 },
            Object { shape: Shape::Plane { point: Vec3::ZERO, normal: Vec3::Y }, material: 1 },
        ],
    };
    let scene = PreparedScene::new(scene).unwrap();
    assert!(scene.plan.projections.iter().all(Option::is_some), "{}", scene.plan.explain());
    let expected = Output::frame(&mut ReferenceBackend, &scene);
    let got = Output::frame(&mut CpuBackend::new(), &scene);
    assert!(!expected.map.photons.is_empty());
    assert_eq!(expected.map.photons, got.map.photons, "projected emission differs between the backends");
    assert_parity("cpu-projection", &scene, &expected, &got);

    // Unbiased for every light kind: the caustic flux matches emission over
    // the whole of each light, with 20× the photons (noise ≈ 1 %; allow 4 %).
    let flux_stored = |photons: u32, projection_maps: bool| {
        let mut s = scene.scene.clone();
        (s.render.photons, s.render.projection_maps) = (photons, projection_maps);
        trace(&mut CpuBackend::new(), &PreparedScene::new(s).unwrap()).stats.flux_stored
    };
    let (aimed, whole) = (flux_stored(40_000, true), flux_stored(800_000, false));
    assert!((aimed - whole).abs() < 0.04 * whole, "caustic flux {aimed} aimed vs {whole} unaimed");
}
