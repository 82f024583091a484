//! The CPU backend against the scalar reference: photon maps and images on
//! every built-in scene and on random scenes, and independence of the
//! thread count.

use prismatic_cli::load_scene;
use prismatic_core::{Backend, NoProgress, PreparedScene, ReferenceBackend};
use prismatic_cpu::CpuBackend;
use prismatic_tests::parity::{Output, assert_parity};
use prismatic_tests::random_scene::random_scene;

fn run(backend: &mut dyn Backend, scene: &PreparedScene) -> Output {
    let map = backend.trace_photons(scene, &mut NoProgress).expect("trace");
    let image = backend.render(scene, &map, &mut NoProgress).expect("render");
    Output { backend: backend.name(), map, image }
}

/// The parity test body, written once: any backend against the reference.
fn check(case: &str, scene: &PreparedScene, backend: &mut dyn Backend) {
    let expected = run(&mut ReferenceBackend, scene);
    let got = run(backend, scene);
    assert!(got.map.is_canonical(), "{case}: {} map not in canonical order", got.backend);
    assert!(
        !expected.map.photons.is_empty() || scene.scene.render.photons == 0,
        "{case}: no caustic photons to compare"
    );
    assert_parity(case, scene, &expected, &got);
}

#[test]
fn cpu_matches_the_reference_on_every_built_in_scene() {
    for (name, photons) in [("sphere", 30_000), ("prism", 4_000), ("recombine", 4_000), ("rainbow", 60_000)] {
        let mut doc = load_scene(name).unwrap();
        doc.scene.render.photons = photons;
        doc.scene.render.width = 96;
        doc.scene.render.height = 96;
        let scene = PreparedScene::new(doc.scene).unwrap();
        check(&format!("cpu-{name}"), &scene, &mut CpuBackend::new());
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
    let outputs: Vec<Output> = [1, 2, 3].map(|t| run(&mut CpuBackend::with_threads(t).unwrap(), &scene)).into();
    for o in &outputs[1..] {
        assert_eq!(o.map.photons, outputs[0].map.photons);
        assert_eq!(o.image.pixels, outputs[0].image.pixels);
    }
}
