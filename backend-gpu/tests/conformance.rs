//! The conformance suite on the GPU backend (lavapipe where there is no GPU;
//! without any adapter the suite fails under `CI=true` and is skipped elsewhere).

use prismatic_gpu::{GpuBackend, GpuOptions, test_context};
use std::sync::OnceLock;

/// One device and one compile of the pipelines for the whole suite.
static GPU: OnceLock<Option<GpuBackend>> = OnceLock::new();

fn gpu() -> Option<GpuBackend> {
    let shared = GPU.get_or_init(|| {
        test_context("the GPU conformance suite").map(|ctx| GpuBackend::with_context(ctx, GpuOptions::default()))
    });
    shared.as_ref().map(|gpu| gpu.with_options(GpuOptions::default()))
}

prismatic_conformance::conformance_tests!(gpu());
