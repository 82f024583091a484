//! The conformance suite on the GPU backend (lavapipe where there is no GPU;
//! without any adapter the suite fails under `CI=true` and is skipped elsewhere).

use prismatic_gpu::{GpuBackend, GpuOptions};

fn gpu() -> Option<GpuBackend> {
    GpuBackend::for_test("the GPU conformance suite", GpuOptions::default())
}

prismatic_conformance::conformance_tests!(gpu());
