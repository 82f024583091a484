//! The conformance suite on the scalar reference itself. Its "matches the
//! reference" bodies compare the reference with itself here, so this binary
//! checks determinism (the same scene and seed give the same bits twice)
//! and the protocol's promises (exact merges, any pass order, updates) on
//! the specification; the backends' own suites are the parity tests.

prismatic_conformance::conformance_tests!(Some(prismatic_core::ReferenceBackend));
