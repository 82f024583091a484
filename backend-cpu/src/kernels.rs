//! The CPU backend's kernels for the core's host driver: packet view rays,
//! packet photon passes in fixed chunks of emissions, packet grids and
//! gathers, light tracing over the photons in parallel (the core's
//! connection, one photon at a time), each timed on the host. The buffers
//! stay from pass to pass, so a render allocates nothing after its first
//! pass.

use crate::pass::PassGrids;
use crate::{TRACE_CHUNK, indirect, trace, view};
use prismatic_core::model::photon::{Photon, TraceStats};
use prismatic_core::photons::light_tracing::{CameraConnection, Splat};
use prismatic_core::photons::trace::trace_range;
use prismatic_core::render::host::{HostKernels, PassGather};
use prismatic_core::render::visible::{VisiblePoint, VisiblePoints};
use prismatic_core::{PhotonMap, PreparedScene, Progress, Stage, StageTimes};
use rayon::prelude::*;
use std::sync::Arc;
use std::time::Instant;

/// The packet kernels of one render.
pub struct PacketKernels {
    pool: Option<Arc<rayon::ThreadPool>>,
    chunks: Vec<ChunkBuffer>,
    /// The photon map of the last pass (its memory is reused).
    pass_map: PhotonMap,
    /// The grid levels of the last pass (rebuilt in place).
    grids: PassGrids,
    /// Host time per stage of the last pass (and of the view rays before it).
    times: StageTimes,
}

/// One work item's unsorted output and sort scratch.
#[derive(Default)]
struct ChunkBuffer {
    photons: Vec<Photon>,
    offsets: Vec<u32>,
    stats: TraceStats,
}

impl PacketKernels {
    /// Kernels on `pool` (`None`: rayon's global pool).
    pub fn new(pool: Option<Arc<rayon::ThreadPool>>) -> Self {
        PacketKernels {
            pool,
            chunks: Vec::new(),
            pass_map: PhotonMap::default(),
            grids: PassGrids::default(),
            times: StageTimes::default(),
        }
    }

    fn install<R: Send>(&self, work: impl FnOnce() -> R + Send) -> R {
        match &self.pool {
            Some(pool) => pool.install(work),
            None => work(),
        }
    }

    /// Traces the scene's photons into `map`, reusing its memory.
    fn trace_into(&mut self, scene: &PreparedScene, map: &mut PhotonMap) {
        let PacketKernels { pool, chunks, .. } = self;
        match pool {
            Some(pool) => pool.install(|| trace_chunks(scene, chunks, map)),
            None => trace_chunks(scene, chunks, map),
        }
    }
}

impl HostKernels for PacketKernels {
    fn name(&self) -> &'static str {
        "cpu"
    }

    fn visible_points(&mut self, scene: &PreparedScene, pass: u32, progress: &mut dyn Progress) -> VisiblePoints {
        let start = Instant::now();
        let points = self.install(|| view::visible_points(scene, pass));
        self.times = StageTimes { view: start.elapsed(), ..StageTimes::default() };
        let h = u64::from(scene.scene.render.height);
        progress.advance(Stage::View, h, h);
        points
    }

    fn trace(&mut self, scene: &PreparedScene, progress: &mut dyn Progress) -> PhotonMap {
        let mut map = PhotonMap::default();
        self.trace_into(scene, &mut map);
        let total = u64::from(scene.traced_photons());
        progress.advance(Stage::Photons, total, total);
        map
    }

    fn pass(&mut self, scene: &PreparedScene, points: &[VisiblePoint], radii: &[f32]) -> PassGather {
        // The pass's map and grids are kept for the next pass (no allocation after the first).
        let (mut map, mut grids) = (std::mem::take(&mut self.pass_map), std::mem::take(&mut self.grids));
        let view = std::mem::take(&mut self.times.view);
        let start = Instant::now();
        self.trace_into(scene, &mut map);
        let traced = Instant::now();
        self.install(|| grids.rebuild(scene, &map, points, radii));
        let gridded = Instant::now();
        let (irradiance, photons) = self.install(|| grids.gather(scene, &map, points, radii));
        let splats = self.install(|| splat_photons(scene, &map.photons));
        self.times = StageTimes { view, photons: traced - start, grid: gridded - traced, gather: gridded.elapsed() };
        let stats = map.stats;
        (self.pass_map, self.grids) = (map, grids);
        PassGather { irradiance, photons, splats, stats }
    }

    fn stage_times(&self) -> Option<StageTimes> {
        Some(self.times)
    }
}

/// The core's light tracing of `photons` in parallel (the same splats in
/// the same order as `prismatic_core::photons::light_tracing::splat_photons`).
fn splat_photons(scene: &PreparedScene, photons: &[Photon]) -> Vec<Splat> {
    if !scene.scene.render.light_tracing {
        return Vec::new();
    }
    let connection = CameraConnection::new(scene);
    photons.par_iter().with_min_len(TRACE_CHUNK as usize).filter_map(|p| connection.splat(p)).collect()
}

/// Traces fixed chunks of emissions in parallel (each unsorted into its own
/// buffer), then sorts each chunk straight into its slice of the map.
fn trace_chunks(scene: &PreparedScene, chunks: &mut Vec<ChunkBuffer>, map: &mut PhotonMap) {
    let total = scene.traced_photons();
    let ctx = trace::TraceContext::new(scene);
    let n_chunks = total.div_ceil(TRACE_CHUNK) as usize;
    chunks.resize_with(n_chunks.max(chunks.len()), ChunkBuffer::default);
    let range = |c: usize| c as u32 * TRACE_CHUNK..((c as u32 + 1) * TRACE_CHUNK).min(total);
    let caustic = scene.caustic_photons();
    chunks[..n_chunks].par_iter_mut().enumerate().for_each(|(c, buf)| {
        // Caustic photons in packets, then indirect light's.
        let r = range(c);
        if ctx.facets {
            // A metal's or rough glass's facets are the core's scalar rule:
            // a scene with either traces its photons one by one with it.
            buf.photons.clear();
            buf.stats = TraceStats::default();
            trace_range(scene, r, &mut buf.photons, &mut buf.stats);
            return;
        }
        buf.stats = trace::trace_chunk(&ctx, r.start..r.end.min(caustic), &mut buf.photons);
        indirect::trace_indirect_packets(&ctx, r.start.max(caustic)..r.end, &mut buf.photons, &mut buf.stats);
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
