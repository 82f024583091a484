//! The conformance suite on the scalar reference itself: the protocol's
//! promises (exact merges, any pass order, updates) hold for the
//! specification too.

prismatic_conformance::conformance_tests!(Some(prismatic_core::ReferenceBackend));
