//! Progressive rendering on every backend: the image converges with passes,
//! dense caustics get small radii, the sums do not depend on threads, and
//! partial renders merge into the image of one run.

use prismatic_core::progressive::ProgressiveRender;
use prismatic_core::{Backend, Image, NoProgress, PreparedScene};
use prismatic_cpu::CpuBackend;
use prismatic_tests::backends::every_backend;
use prismatic_tests::builtin;
use prismatic_tests::parity::compare_images;

/// `passes` passes of `scene` on `backend`, from pass `first`.
fn progressive(backend: &mut dyn Backend, scene: &PreparedScene, first: u32, passes: u32) -> ProgressiveRender {
    let name = backend.name();
    let mut render =
        ProgressiveRender::prepare(backend, scene, &mut NoProgress).unwrap_or_else(|e| panic!("{name}: prepare: {e}"));
    for k in first..first + passes {
        render.run_pass(backend, k).unwrap_or_else(|e| panic!("{name}: pass {k}: {e}"));
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
        let mut cpu = CpuBackend::new();
        let long = progressive(&mut cpu, &scene, 0, 64).image();
        for mut backend in every_backend() {
            let errors: Vec<f64> =
                [1, 4, 16].iter().map(|&n| rmse(&progressive(backend.as_mut(), &scene, 0, n).image(), &long)).collect();
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
    let expected = progressive(&mut prismatic_core::ReferenceBackend, &scene, 0, 4);
    for mut backend in every_backend().into_iter().skip(1) {
        let got = progressive(backend.as_mut(), &scene, 0, 4);
        let name = backend.name();
        compare_images(&expected.points().base, &got.points().base)
            .unwrap_or_else(|e| panic!("{name}: image without caustics: {e}"));
        compare_images(&expected.image(), &got.image()).unwrap_or_else(|e| panic!("{name}: 4 passes: {e}"));
    }
}

#[test]
fn a_dense_caustic_gets_a_smaller_radius_than_sparse_regions() {
    let scene = small("sphere", 65_000);
    let r0 = scene.scene.render.radius;
    for mut backend in every_backend() {
        let render = progressive(backend.as_mut(), &scene, 0, 0);
        let radii = render.initial_radii();
        let points = &render.points().points;
        assert_eq!(radii.len(), points.len());
        // The spot's axis passes through the sphere's centre and meets the
        // floor at (0.5, 0, 0.1): the caustic is there; far from it the
        // floor gets no caustic photons.
        let (mut caustic, mut far) = (Vec::new(), Vec::new());
        for (p, &r) in points.iter().zip(radii) {
            let d = ((p.point.x - 0.5).powi(2) + (p.point.z - 0.1).powi(2)).sqrt();
            if p.point.y.abs() < 1e-3 && d < 0.15 {
                caustic.push(r);
            } else if p.point.y.abs() < 1e-3 && d > 2.0 {
                far.push(r);
            }
        }
        let name = backend.name();
        assert!(!caustic.is_empty() && !far.is_empty(), "{name}: points in both regions");
        let mean = |v: &[f32]| v.iter().sum::<f32>() / v.len() as f32;
        assert!(mean(&caustic) < 0.5 * r0, "{name}: caustic radius {} of {r0}", mean(&caustic));
        assert!(far.iter().all(|&r| r == r0), "{name}: sparse points keep the scene's radius");
    }
}

#[test]
fn the_same_bits_whatever_the_thread_count() {
    let scene = small("sphere", 20_000);
    let one = progressive(&mut CpuBackend::with_threads(1).expect("pool"), &scene, 0, 3);
    let two = progressive(&mut CpuBackend::with_threads(2).expect("pool"), &scene, 0, 3);
    assert_eq!(one.points().base, two.points().base);
    assert_eq!(one.initial_radii(), two.initial_radii());
    assert_eq!(one.accumulation(), two.accumulation());
    assert_eq!(one.image(), two.image());
}

#[test]
fn partial_renders_merge_into_the_image_of_one_run() {
    let scene = small("prism", 4_000);
    let mut cpu = CpuBackend::new();
    let whole = progressive(&mut cpu, &scene, 0, 6);
    let first = progressive(&mut cpu, &scene, 0, 2);
    let second = progressive(&mut cpu, &scene, 2, 4);
    let mut merged = second.accumulation().clone();
    merged.merge(first.accumulation()).expect("disjoint passes");
    assert_eq!(merged.passes, [(0, 6)]);
    assert_eq!(&merged, whole.accumulation());
    assert_eq!(merged.image(&first.points().base), whole.image());
    // A pass in both is refused.
    assert!(merged.merge(first.accumulation()).is_err());
}

#[test]
fn gpu_passes_in_bucket_segments_and_several_bindings_match_the_reference() {
    // Segments of 16 photons per bucket (many gather dispatches per level)
    // and photon maps over several storage bindings.
    let options = prismatic_gpu::GpuOptions { window_photons: Some(50_000), gather_span: Some(16) };
    let Some(mut gpu) = prismatic_tests::backends::gpu_backend(options) else { return };
    let scene = small("sphere", 20_000);
    let expected = progressive(&mut prismatic_core::ReferenceBackend, &scene, 0, 2);
    let got = progressive(&mut gpu, &scene, 0, 2);
    compare_images(&expected.image(), &got.image()).unwrap_or_else(|e| panic!("gpu in segments: {e}"));
}

#[test]
fn one_pass_at_the_scenes_radius_is_the_fixed_radius_frame() {
    // Visible points + a gather at R + the fixed-point sums give the image
    // of trace + render with the same photons: the two paths agree.
    for name in ["sphere", "prism"] {
        let scene = small(name, 20_000);
        let map = prismatic_core::trace::trace_photons(&scene);
        let frame = prismatic_core::render::render(&scene, &map);
        let points = prismatic_core::render::visible_points_with_progress(&scene, &mut NoProgress);
        let radii = vec![scene.scene.render.radius; points.points.len()];
        let found = prismatic_core::progressive::gather_pass(&scene, &map, &points.points, &radii);
        let mut sums = prismatic_core::progressive::Accumulation::new(80, 80);
        sums.add_pass(0, &points.points, &found.irradiance);
        compare_images(&frame, &sums.image(&points.base)).unwrap_or_else(|e| panic!("{name}: {e}"));
    }
}
