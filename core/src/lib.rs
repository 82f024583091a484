//! prismatic-core: the executable specification of prismatic.
//!
//! A `no_std` + `alloc` crate that owns everything a backend needs to agree on:
//! the scene model and its validation, spectral bands and dispersion models,
//! the photon and photon-map types (GPU-ready, `#[repr(C)]` + `Pod`), the
//! counter-based RNG, scalar geometry and optics, the scalar reference photon
//! tracer and renderer, the gather estimators, the spatial hash grid, and the
//! [`Backend`] trait. It knows nothing of threads, SIMD, GPUs or files.

#![cfg_attr(not(feature = "std"), no_std)]

#[cfg(all(feature = "std", target_os = "none"))]
compile_error!("feature `std` cannot be used on a bare-metal target: build with --no-default-features");

extern crate alloc;

pub mod backend;
pub mod bands;
pub mod camera;
pub mod cie;
pub mod color;
pub mod dispersion;
pub mod effects;
pub mod emit;
pub mod gather;
pub mod geometry;
pub mod grid;
pub mod image;
pub mod math;
pub mod mesh;
pub mod optics;
pub mod photon;
pub mod prepared;
pub mod progressive;
pub mod projection;
pub mod render;
pub mod rng;
pub mod scene;
pub mod tolerance;
pub mod trace;
pub mod visible;

pub use backend::{Backend, BackendError, NoProgress, Progress, ReferenceBackend, Stage};
pub use bands::{Band, BandSpec, BandTable};
pub use dispersion::{Dispersion, Glass};
pub use effects::{Effect, EffectPlan};
pub use image::Image;
pub use photon::{Photon, PhotonMap, TraceStats};
pub use prepared::PreparedScene;
pub use scene::{
    Camera, Checker, Estimator, Light, Material, Object, RenderSettings, Scene, SceneError, Shape, WavelengthSampling,
};

/// Re-exported so that users of the scene model need not depend on glam themselves.
pub use glam::Vec3;
