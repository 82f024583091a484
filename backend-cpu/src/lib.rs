//! prismatic-cpu: the packet-SIMD CPU backend.
//!
//! Photons are traced eight to a packet (`wide::f32x8`, structure of
//! arrays, masks instead of branches) on all cores with rayon; work is cut
//! into fixed chunks of emission indices, so the photon map is the same
//! whatever the thread count. Each stage has a scalar twin of the same name
//! in `prismatic-core`, which the parity tests compare it with.

mod emit;
mod grid;
mod intersect;
mod render;
mod simd;
mod trace;

pub use grid::CpuGrid;

use prismatic_core::backend::{Backend, BackendError, Progress, Stage};
use prismatic_core::{Image, PhotonMap, PreparedScene};
use rayon::prelude::*;

/// White photons per work item: large enough to amortise a packet's set-up,
/// small enough to balance the threads.
pub const TRACE_CHUNK: u32 = 4096;

/// The CPU backend.
pub struct CpuBackend {
    pool: Option<rayon::ThreadPool>,
}

impl CpuBackend {
    /// Uses rayon's global pool (all cores).
    pub fn new() -> Self {
        CpuBackend { pool: None }
    }

    /// Uses exactly `threads` threads (for scaling measurements).
    pub fn with_threads(threads: usize) -> Result<Self, BackendError> {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .map_err(|e| BackendError::Device(format!("cannot start {threads} threads: {e}")))?;
        Ok(CpuBackend { pool: Some(pool) })
    }

    fn install<R: Send>(&self, work: impl FnOnce() -> R + Send) -> R {
        match &self.pool {
            Some(pool) => pool.install(work),
            None => work(),
        }
    }
}

impl Default for CpuBackend {
    fn default() -> Self {
        Self::new()
    }
}

/// Traces the scene's photons in packets on the current rayon pool.
pub fn trace_photons(scene: &PreparedScene) -> PhotonMap {
    let total = scene.scene.render.photons;
    let ctx = trace::TraceContext::new(scene);
    let chunks: Vec<_> = (0..total.div_ceil(TRACE_CHUNK))
        .into_par_iter()
        .map(|c| trace::trace_chunk(&ctx, c * TRACE_CHUNK..((c + 1) * TRACE_CHUNK).min(total)))
        .collect();
    let mut map = PhotonMap::default();
    map.photons.reserve(chunks.iter().map(|c| c.0.len()).sum());
    for (photons, stats) in chunks {
        map.photons.extend_from_slice(&photons);
        map.stats.merge(&stats);
    }
    map
}

impl Backend for CpuBackend {
    fn name(&self) -> &'static str {
        "cpu"
    }

    fn trace_photons(&mut self, scene: &PreparedScene, progress: &mut dyn Progress) -> Result<PhotonMap, BackendError> {
        let map = self.install(|| trace_photons(scene));
        let total = u64::from(scene.scene.render.photons);
        progress.advance(Stage::Trace, total, total);
        Ok(map)
    }

    fn render(
        &mut self,
        scene: &PreparedScene,
        photons: &PhotonMap,
        progress: &mut dyn Progress,
    ) -> Result<Image, BackendError> {
        let image = self.install(|| {
            let grid = CpuGrid::build(&photons.photons, scene.scene.render.radius);
            render::render(scene, &grid)
        });
        let h = u64::from(scene.scene.render.height);
        progress.advance(Stage::Render, h, h);
        Ok(image)
    }
}

/// Builds the grid and renders the image with the CPU backend's packets on the current rayon pool.
pub fn render(scene: &PreparedScene, photons: &PhotonMap) -> Image {
    let grid = CpuGrid::build(&photons.photons, scene.scene.render.radius);
    render::render(scene, &grid)
}
