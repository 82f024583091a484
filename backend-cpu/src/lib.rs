//! prismatic-cpu: the packet-SIMD CPU backend (photon tracing in 8-lane
//! packets with `wide`, threads over packets, hash-grid gather).
//!
//! Not built yet: `prismatic --backend cpu` says so and points to
//! `--backend reference`. Until then the scalar reference in
//! `prismatic-core` is the only backend.
