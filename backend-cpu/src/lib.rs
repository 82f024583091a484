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
mod progressive;
mod render;
mod simd;
mod trace;

pub use grid::CpuGrid;

use prismatic_core::backend::{Backend, BackendError, Progress, Stage};
use prismatic_core::photon::{Photon, TraceStats};
use prismatic_core::progressive::PassGather;
use prismatic_core::visible::{VisiblePoint, VisiblePoints};
use prismatic_core::{Image, PhotonMap, PreparedScene};
use rayon::prelude::*;

/// White photons per work item: large enough to amortise a packet's set-up,
/// small enough to balance the threads.
pub const TRACE_CHUNK: u32 = 1024;

/// The CPU backend. It keeps its per-chunk buffers between frames, so an
/// engine that traces every frame into the same [`PhotonMap`]
/// ([`CpuBackend::trace_into`]) allocates nothing after the first.
pub struct CpuBackend {
    pool: Option<rayon::ThreadPool>,
    chunks: Vec<ChunkBuffer>,
    /// The photon map of the last progressive pass (its memory is reused).
    pass_map: PhotonMap,
    /// The grid levels of the last progressive pass (rebuilt in place).
    pass_grids: progressive::PassGrids,
}

/// One work item's unsorted output and sort scratch.
#[derive(Default)]
struct ChunkBuffer {
    photons: Vec<Photon>,
    offsets: Vec<u32>,
    stats: TraceStats,
}

impl CpuBackend {
    /// Uses rayon's global pool (all cores).
    pub fn new() -> Self {
        CpuBackend { pool: None, chunks: Vec::new(), pass_map: PhotonMap::default(), pass_grids: Default::default() }
    }

    /// Uses exactly `threads` threads (for scaling measurements).
    pub fn with_threads(threads: usize) -> Result<Self, BackendError> {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .map_err(|e| BackendError::Device(format!("cannot start {threads} threads: {e}")))?;
        Ok(CpuBackend {
            pool: Some(pool),
            chunks: Vec::new(),
            pass_map: PhotonMap::default(),
            pass_grids: Default::default(),
        })
    }

    /// Traces the scene's photons into `map`, reusing its memory.
    pub fn trace_into(&mut self, scene: &PreparedScene, map: &mut PhotonMap) {
        let CpuBackend { pool, chunks, .. } = self;
        match pool {
            Some(pool) => pool.install(|| trace_chunks(scene, chunks, map)),
            None => trace_chunks(scene, chunks, map),
        }
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
    let mut map = PhotonMap::default();
    trace_chunks(scene, &mut Vec::new(), &mut map);
    map
}

/// Traces fixed chunks of emissions in parallel (each unsorted into its own
/// buffer), then sorts each chunk straight into its slice of the map.
fn trace_chunks(scene: &PreparedScene, chunks: &mut Vec<ChunkBuffer>, map: &mut PhotonMap) {
    // The effect plan may skip the photon pass altogether.
    let total = if scene.plan.caustics.on { scene.scene.render.photons } else { 0 };
    let ctx = trace::TraceContext::new(scene);
    let n_chunks = total.div_ceil(TRACE_CHUNK) as usize;
    chunks.resize_with(n_chunks.max(chunks.len()), ChunkBuffer::default);
    let range = |c: usize| c as u32 * TRACE_CHUNK..((c as u32 + 1) * TRACE_CHUNK).min(total);
    chunks[..n_chunks].par_iter_mut().enumerate().for_each(|(c, buf)| {
        buf.stats = trace::trace_chunk(&ctx, range(c), &mut buf.photons);
    });
    let stored: usize = chunks[..n_chunks].iter().map(|b| b.photons.len()).sum();
    map.photons.clear();
    map.photons.resize(stored, Photon::default());
    map.stats = TraceStats::default();
    let mut slices = Vec::with_capacity(n_chunks);
    let mut rest = map.photons.as_mut_slice();
    for buf in &chunks[..n_chunks] {
        let (head, tail) = rest.split_at_mut(buf.photons.len());
        slices.push(head);
        rest = tail;
        map.stats.merge(&buf.stats);
    }
    chunks[..n_chunks].par_iter_mut().zip(slices).enumerate().for_each(|(c, (buf, dest))| {
        let r = range(c);
        trace::canonical_order(&buf.photons, r.start, r.len(), &mut buf.offsets, dest);
    });
}

impl Backend for CpuBackend {
    fn name(&self) -> &'static str {
        "cpu"
    }

    fn trace_photons(&mut self, scene: &PreparedScene, progress: &mut dyn Progress) -> Result<PhotonMap, BackendError> {
        let mut map = PhotonMap::default();
        self.trace_into(scene, &mut map);
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
        let image = self.install(|| render(scene, photons));
        let h = u64::from(scene.scene.render.height);
        progress.advance(Stage::Render, h, h);
        Ok(image)
    }

    fn visible_points(
        &mut self,
        scene: &PreparedScene,
        progress: &mut dyn Progress,
    ) -> Result<VisiblePoints, BackendError> {
        let points = self.install(|| render::visible_points(scene));
        let h = u64::from(scene.scene.render.height);
        progress.advance(Stage::Render, h, h);
        Ok(points)
    }

    fn gather_pass(
        &mut self,
        scene: &PreparedScene,
        points: &[VisiblePoint],
        radii: &[f32],
    ) -> Result<PassGather, BackendError> {
        // The pass's map is kept for the next pass (no allocation after the first).
        let (mut map, mut grids) = (std::mem::take(&mut self.pass_map), std::mem::take(&mut self.pass_grids));
        self.trace_into(scene, &mut map);
        let found = self.install(|| progressive::gather_pass(scene, &map, points, radii, &mut grids));
        (self.pass_map, self.pass_grids) = (map, grids);
        Ok(found)
    }
}

/// Builds the grid and renders the image with the CPU backend's packets on the current rayon pool.
pub fn render(scene: &PreparedScene, photons: &PhotonMap) -> Image {
    render_with_grid(scene, &CpuGrid::build(&photons.photons, scene.scene.render.radius))
}

/// Renders the image from an already built grid (ray tracing and gather).
pub fn render_with_grid(scene: &PreparedScene, grid: &CpuGrid) -> Image {
    render::render(scene, grid)
}
