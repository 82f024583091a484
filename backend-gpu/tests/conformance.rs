//! The conformance suite on the GPU backend (lavapipe where there is no GPU;
//! without any adapter the suite fails under `CI=true` and is skipped elsewhere).

use prismatic_gpu::{GpuBackend, GpuOptions, test_context};

fn gpu() -> Option<GpuBackend> {
    test_context("the GPU conformance suite").map(|ctx| GpuBackend::with_context(ctx, GpuOptions::default()))
}

prismatic_conformance::conformance_tests!(gpu());
