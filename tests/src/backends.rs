//! Every backend that exists, so that a test body is written once and run on
//! each (the scalar reference first: it is the specification), and the two
//! read-outs most tests want, through the render protocol: a pass's photon
//! map, and the paper's fixed-radius frame.

use prismatic_core::model::scene::RadiusMode;
use prismatic_core::{Backend, Image, NoProgress, PhotonMap, PreparedScene, ReferenceBackend};
use prismatic_cpu::CpuBackend;
use prismatic_gpu::{GpuBackend, GpuOptions};

/// The GPU backend on the best adapter there is (lavapipe on machines
/// without a GPU), with `options`. Without any adapter: under `CI=true` the
/// test fails (CI installs lavapipe, so a missing adapter is a broken
/// machine); elsewhere it says it is skipping and returns `None`. The
/// process's tests share one device ([`GpuBackend::for_test`]).
pub fn gpu_backend(options: GpuOptions) -> Option<GpuBackend> {
    GpuBackend::for_test("the gpu backend", options)
}

/// The reference, the CPU backend and the GPU backend (outside CI, only
/// where the machine has an adapter; see [`gpu_backend`]).
pub fn every_backend() -> Vec<Box<dyn Backend>> {
    let mut backends: Vec<Box<dyn Backend>> = vec![Box::new(ReferenceBackend), Box::new(CpuBackend::new())];
    if let Some(gpu) = gpu_backend(GpuOptions::default()) {
        backends.push(Box::new(gpu));
    }
    backends
}

/// The photon map of pass 0 of `scene` on `backend`, panicking with the backend's name on error.
pub fn trace(backend: &mut dyn Backend, scene: &PreparedScene) -> PhotonMap {
    let name = backend.name();
    let mut render = backend.prepare(scene).unwrap_or_else(|e| panic!("{name}: prepare: {e}"));
    render.photon_map(0, &mut NoProgress).unwrap_or_else(|e| panic!("{name}: photon map: {e}"))
}

/// `scene` with the paper's fixed radius: every pass gathers within the
/// scene's radius at every point (the rest of the prepared scene, a plan
/// a test forced included, as it is).
pub fn fixed(scene: &PreparedScene) -> PreparedScene {
    let mut fixed = scene.clone();
    fixed.scene.render.radius_mode = RadiusMode::Fixed;
    fixed
}

/// The paper's frame of `scene` on `backend`: pass 0 gathered within the
/// scene's radius at every point, and that pass's photon map.
pub fn frame(backend: &mut dyn Backend, scene: &PreparedScene) -> (PhotonMap, Image) {
    let name = backend.name();
    let mut render = backend.prepare(&fixed(scene)).unwrap_or_else(|e| panic!("{name}: prepare: {e}"));
    render.run_pass(0, &mut NoProgress).unwrap_or_else(|e| panic!("{name}: pass: {e}"));
    let image = render.image().unwrap_or_else(|e| panic!("{name}: image: {e}"));
    let map = render.photon_map(0, &mut NoProgress).unwrap_or_else(|e| panic!("{name}: photon map: {e}"));
    (map, image)
}

/// The image of passes 0..`passes` of `scene` (as given, not fixed) on `backend`.
pub fn image_after(backend: &mut dyn Backend, scene: &PreparedScene, passes: u32) -> Image {
    let name = backend.name();
    let mut render = backend.prepare(scene).unwrap_or_else(|e| panic!("{name}: prepare: {e}"));
    for pass in 0..passes {
        render.run_pass(pass, &mut NoProgress).unwrap_or_else(|e| panic!("{name}: pass {pass}: {e}"));
    }
    render.image().unwrap_or_else(|e| panic!("{name}: image: {e}"))
}

/// That aiming photons changed nothing but the noise: the aimed and the
/// unaimed frame of one scene store the same caustic flux (2 %) and give
/// the same image within photon noise (3 % of its L1 norm).
pub fn assert_same_caustic(name: &str, (aimed_map, aimed): (&PhotonMap, &Image), (map, image): (&PhotonMap, &Image)) {
    let (fa, fw) = (aimed_map.stats.flux_stored, map.stats.flux_stored);
    assert!((fa - fw).abs() < 0.02 * fw, "{name}: stored flux {fa} vs {fw}");
    let diff: f64 = aimed.pixels.iter().zip(&image.pixels).map(|(a, b)| f64::from((*a - *b).abs().element_sum())).sum();
    let total: f64 = image.pixels.iter().map(|p| f64::from(p.element_sum())).sum();
    assert!(diff < 0.03 * total, "{name}: images differ by {:.2} % (L1)", 100.0 * diff / total);
}

/// Asserts that each backend's frame of `scene` (seen by `camera`, `side`
/// pixels square, from straight above a floor at y = 0) shows in each
/// pixel the red channel `want(c)`, within `tolerance`, where c is the
/// cosine between the pixel's ray and straight down.
pub fn assert_floor_from_above(
    scene: &PreparedScene,
    camera: &prismatic_core::model::scene::Camera,
    side: u32,
    want: impl Fn(f32) -> f32,
    tolerance: f32,
) {
    let pinhole = prismatic_core::geometry::camera::PinholeCamera::new(camera, side, side);
    for mut backend in every_backend() {
        let name = backend.name();
        let (_, image) = frame(backend.as_mut(), scene);
        for y in 0..side {
            for x in 0..side {
                let c = -pinhole.ray(x, y).direction.normalize().y;
                let (got, want) = (image.pixels[(y * side + x) as usize].x, want(c));
                assert!((got - want).abs() <= tolerance, "{name}: pixel ({x}, {y}) at cos {c}: {got} vs {want}");
            }
        }
    }
}

/// The cosines between straight down and each pixel's ray of `camera`
/// (`side` pixels square), for counting what an image holds.
pub fn pixel_cosines(camera: &prismatic_core::model::scene::Camera, side: u32) -> Vec<f32> {
    let pinhole = prismatic_core::geometry::camera::PinholeCamera::new(camera, side, side);
    (0..side * side).map(|i| -pinhole.ray(i % side, i / side).direction.normalize().y).collect()
}
