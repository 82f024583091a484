//! The conformance suite on the GPU backend (lavapipe where there is no GPU;
//! without any adapter the suite fails under `CI=true` and is skipped elsewhere).

use prismatic_gpu::{AdapterChoice, GpuBackend, GpuOptions};

fn gpu() -> Option<GpuBackend> {
    match prismatic_gpu::GpuContext::new(AdapterChoice::Any) {
        Ok(ctx) => Some(GpuBackend::with_context(ctx, GpuOptions::default())),
        Err(e) => {
            eprintln!("no GPU adapter: {e}");
            None
        }
    }
}

prismatic_conformance::conformance_tests!(gpu());
