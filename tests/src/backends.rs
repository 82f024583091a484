//! Every backend that exists, so that a test body is written once and run on
//! each (the scalar reference first: it is the specification).

use prismatic_core::{Backend, Image, NoProgress, PhotonMap, PreparedScene, ReferenceBackend};
use prismatic_cpu::CpuBackend;
use prismatic_gpu::{AdapterChoice, GpuBackend, GpuOptions};

/// The GPU backend on the best adapter there is (lavapipe on machines
/// without a GPU). Without any adapter: under `CI=true` the test fails
/// (CI installs lavapipe, so a missing adapter is a broken machine);
/// elsewhere it says it is skipping and returns `None`.
pub fn gpu_backend(options: GpuOptions) -> Option<GpuBackend> {
    match prismatic_gpu::GpuContext::new(AdapterChoice::Any) {
        Ok(ctx) => Some(GpuBackend::with_context(ctx, options)),
        Err(e) if std::env::var_os("CI").is_some() => panic!("CI=true and no GPU adapter: {e}"),
        Err(e) => {
            eprintln!("SKIPPING the gpu backend on this machine: {e}");
            None
        }
    }
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

/// Traces `scene`'s photons on `backend`, panicking with the backend's name on error.
pub fn trace(backend: &mut dyn Backend, scene: &PreparedScene) -> PhotonMap {
    let name = backend.name();
    backend.trace_photons(scene, &mut NoProgress).unwrap_or_else(|e| panic!("{name}: trace: {e}"))
}

/// Traces and renders `scene` on `backend`.
pub fn trace_and_render(backend: &mut dyn Backend, scene: &PreparedScene) -> (PhotonMap, Image) {
    let map = trace(backend, scene);
    let name = backend.name();
    let image = backend.render(scene, &map, &mut NoProgress).unwrap_or_else(|e| panic!("{name}: render: {e}"));
    (map, image)
}
