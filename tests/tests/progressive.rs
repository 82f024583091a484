//! Progressive rendering on every backend: the image converges with passes,
//! dense caustics get small radii, the sums do not depend on the threads,
//! and one pass at the scene's radius is the paper's frame. (Exact merges,
//! pass order and updates are the conformance suite's.)

use prismatic_core::render::host::HostRender;
use prismatic_core::render::reference::ScalarKernels;
use prismatic_core::{Backend, Image, NoProgress, PreparedScene, ReferenceBackend, Render};
use prismatic_cpu::CpuBackend;
use prismatic_tests::backends::{every_backend, fixed};
use prismatic_tests::builtin;
use prismatic_tests::parity::compare_images;
use prismatic_tests::tolerance::Tolerance;

/// A render of `scene` on `backend` after passes `0..passes`.
fn progressive(backend: &mut dyn Backend, scene: &PreparedScene, passes: u32) -> Box<dyn Render> {
    let name = backend.name();
    let mut render = backend.prepare(scene).unwrap_or_else(|e| panic!("{name}: prepare: {e}"));
    for k in 0..passes {
        render.run_pass(k, &mut NoProgress).unwrap_or_else(|e| panic!("{name}: pass {k}: {e}"));
    }
    render
}

/// Root mean square difference of linear RGB over all pixels.
fn rmse(a: &Image, b: &Image) -> f64 {
    let sum: f64 = a.pixels.iter().zip(&b.pixels).map(|(x, y)| f64::from((*x - *y).length_squared())).sum();
    (sum / a.pixels.len() as f64).sqrt()
}

fn small(name: &str, photons: u32) -> PreparedScene {
    builtin(name, |r| {
        (r.width, r.height, r.photons) = (80, 80, photons);
    })
}

#[test]
fn error_against_a_long_render_falls_with_passes_on_every_backend() {
    for (name, photons) in [("sphere", 20_000), ("prism", 4_000)] {
        let scene = small(name, photons);
        let long = progressive(&mut CpuBackend::new(), &scene, 64).image().unwrap();
        for mut backend in every_backend() {
            // One render read after 1, 4 and 16 passes: its image after n
            // passes is the render of passes 0..n.
            let mut render = progressive(backend.as_mut(), &scene, 0);
            let mut errors = Vec::new();
            for k in 0..16 {
                render.run_pass(k, &mut NoProgress).unwrap_or_else(|e| panic!("{}: pass {k}: {e}", backend.name()));
                if [1, 4, 16].contains(&(k + 1)) {
                    errors.push(rmse(&render.image().unwrap(), &long));
                }
            }
            // Monotone within noise: each quadrupling of passes lowers the error by a tenth at least.
            assert!(
                errors[1] < 0.9 * errors[0] && errors[2] < 0.9 * errors[1],
                "{name} on {}: RMSE after 1, 4, 16 passes {errors:?}",
                backend.name()
            );
        }
    }
}

#[test]
fn every_backend_converges_to_the_reference_image() {
    let scene = small("sphere", 20_000);
    let mut expected = progressive(&mut ReferenceBackend, &scene, 4);
    for mut backend in every_backend().into_iter().skip(1) {
        let mut got = progressive(backend.as_mut(), &scene, 4);
        let (name, tol) = (backend.name(), Tolerance::of(backend.arithmetic()));
        compare_images(&expected.base().unwrap(), &got.base().unwrap(), tol)
            .unwrap_or_else(|e| panic!("{name}: image without caustics: {e}"));
        compare_images(&expected.image().unwrap(), &got.image().unwrap(), tol)
            .unwrap_or_else(|e| panic!("{name}: 4 passes: {e}"));
    }
}

#[test]
fn a_dense_caustic_gets_a_smaller_radius_than_sparse_regions() {
    let scene = small("sphere", 65_000);
    let r0 = scene.scene.render.radius;
    let mut render = HostRender::new(ScalarKernels, &scene);
    let radii = render.first_radii(&mut NoProgress).to_vec();
    let points = render.visible_points(&mut NoProgress).points.clone();
    assert_eq!(radii.len(), points.len());
    // The spot's axis passes through the sphere's centre and meets the
    // floor at (0.5, 0, 0.1): the caustic is there; far from it the
    // floor gets no caustic photons.
    let (mut caustic, mut far) = (Vec::new(), Vec::new());
    for (p, &r) in points.iter().zip(&radii) {
        let d = ((p.point.x - 0.5).powi(2) + (p.point.z - 0.1).powi(2)).sqrt();
        if p.point.y.abs() < 1e-3 && d < 0.15 {
            caustic.push(r);
        } else if p.point.y.abs() < 1e-3 && d > 2.0 {
            far.push(r);
        }
    }
    assert!(!caustic.is_empty() && !far.is_empty(), "points in both regions");
    let mean = |v: &[f32]| v.iter().sum::<f32>() / v.len() as f32;
    assert!(mean(&caustic) < 0.5 * r0, "caustic radius {} of {r0}", mean(&caustic));
    assert!(far.iter().all(|&r| r == r0), "sparse points keep the scene's radius");
    // Every backend's first radii span the same range.
    let range = render.stats().unwrap().first_radii.unwrap();
    for mut backend in every_backend().into_iter().skip(1) {
        let (lo, hi) = progressive(backend.as_mut(), &scene, 1).stats().unwrap().first_radii.unwrap();
        let name = backend.name();
        assert!(
            (lo - range.0).abs() <= 1e-3 * r0 && (hi - range.1).abs() <= 1e-3 * r0,
            "{name}: {lo}..{hi} vs {range:?}"
        );
    }
}

#[test]
fn the_same_bits_whatever_the_thread_count() {
    let scene = small("sphere", 20_000);
    let mut one = progressive(&mut CpuBackend::with_threads(1).expect("pool"), &scene, 3);
    let mut two = progressive(&mut CpuBackend::with_threads(2).expect("pool"), &scene, 3);
    assert_eq!(one.base().unwrap(), two.base().unwrap());
    assert_eq!(one.stats().unwrap().first_radii, two.stats().unwrap().first_radii);
    assert_eq!(one.sums().unwrap(), two.sums().unwrap());
}

#[test]
fn one_pass_at_the_scenes_radius_is_the_paper_frame() {
    // With fixed radii there is no pilot: every point gathers within the
    // scene's radius, and the pass's image is the paper's frame, built
    // here from the core's kernels directly: the photons of pass 0
    // gathered at every visible point within R.
    for name in ["sphere", "prism"] {
        let scene = fixed(&small(name, 20_000));
        let mut render = progressive(&mut ReferenceBackend, &scene, 1);
        let pass = prismatic_core::plan::schedule::pass_scene(&scene, 0);
        let map = prismatic_core::photons::trace::trace_photons(&pass, &mut NoProgress);
        let view = prismatic_core::render::view::visible_points(&scene, 0, &mut NoProgress);
        let radii = vec![scene.scene.render.radius; view.points.len()];
        let found = prismatic_core::render::reference::gather_pass(&pass, &map, &view.points, &radii);
        let mut sums = prismatic_core::Accumulation::new(80, 80);
        sums.add_pass(0, &view.points, &found.irradiance, &found.splats);
        assert_eq!(render.image().unwrap(), sums.image(&view.base), "{name}");
        assert_eq!(render.stats().unwrap().first_radii, Some((radii[0], radii[0])), "{name}");
    }
}
