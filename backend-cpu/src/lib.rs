//! prismatic-cpu: the packet-SIMD CPU backend.
//!
//! Photons are traced eight to a packet (`wide::f32x8`, structure of
//! arrays, masks instead of branches) on all cores with rayon; work is cut
//! into fixed chunks of emission indices, so the photon map is the same
//! whatever the thread count. View rays go eight pixels to a packet, and a
//! pass gathers at the visible points from packet grids. Each stage has a
//! scalar twin of the same job in `prismatic-core`, which the parity tests
//! compare it with; the renders are the core's
//! [`HostRender`] over [`PacketKernels`].

mod bvh;
pub mod emit;
mod form_factor;
mod grid;
mod indirect;
mod intersect;
mod kernels;
pub mod optics;
mod pass;
mod ray;
pub mod simd;
mod trace;
mod view;

pub use grid::CpuGrid;
pub use kernels::PacketKernels;

use prismatic_core::render::host::HostRender;
use prismatic_core::{Backend, BackendError, PreparedScene, Render};
use std::sync::Arc;

/// White photons per work item: large enough to amortise a packet's set-up,
/// small enough to balance the threads.
pub const TRACE_CHUNK: u32 = 1024;

/// The CPU backend: makes renders on rayon's global pool (all cores) or on
/// a pool of its own.
#[derive(Clone, Default)]
pub struct CpuBackend {
    pool: Option<Arc<rayon::ThreadPool>>,
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
        Ok(CpuBackend { pool: Some(Arc::new(pool)) })
    }

    /// Threads its renders use.
    pub fn threads(&self) -> usize {
        self.pool.as_ref().map_or_else(rayon::current_num_threads, |p| p.current_num_threads())
    }
}

impl Backend for CpuBackend {
    fn name(&self) -> &'static str {
        "cpu"
    }

    fn prepare(&mut self, scene: &PreparedScene) -> Result<Box<dyn Render>, BackendError> {
        Ok(Box::new(HostRender::new(PacketKernels::new(self.pool.clone()), scene)))
    }
}
