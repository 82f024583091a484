//! Every backend that exists, so that a test body is written once and run on
//! each (the scalar reference first: it is the specification).

use prismatic_core::{Backend, Image, NoProgress, PhotonMap, PreparedScene, ReferenceBackend};
use prismatic_cpu::CpuBackend;

/// The reference and every backend built in this workspace.
pub fn every_backend() -> Vec<Box<dyn Backend>> {
    vec![Box::new(ReferenceBackend), Box::new(CpuBackend::new())]
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
