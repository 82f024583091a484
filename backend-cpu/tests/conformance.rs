//! The conformance suite on the CPU backend.

prismatic_conformance::conformance_tests!(Some(prismatic_cpu::CpuBackend::new()));
