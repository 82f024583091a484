//! prismatic-core: the executable specification of prismatic.
//!
//! A `no_std` + `alloc` crate that owns everything a backend needs to agree on:
//! the scene model and its validation, spectral bands and dispersion models,
//! the photon and photon-map types (GPU-ready, `#[repr(C)]` + `Pod`), the
//! counter-based RNG, scalar geometry and optics, the gather estimators,
//! the spatial hash grid, the pass schedule, the exact sums, the render
//! protocol ([`Backend`], [`Render`]) and the scalar reference backend. It
//! knows nothing of threads, SIMD, GPUs or files (with `std`, a mesh's
//! hierarchy is built by obvhs, which may use threads of its own).
//!
//! Its modules form four layers, each using only the ones above it (and
//! [`progress`], a leaf every layer may use):
//!
//! | layer | modules | what |
//! |---|---|---|
//! | model | `scene`, `validate`, `bands`, `cie`, `color`, `dispersion`, `image`, `mesh` | what the user described |
//! | kernels | `math`, `rng`, `sobol`, `tolerance`, `ray`, `triangle`, `texture`, `bvh`, `bvh_build`, `geometry`, `camera`, `optics`, `photon`, `grid`, `gather`, `visible` | pure functions, mirrored in packets and WGSL |
//! | plan | `surface`, `reach`, `projection`, `effects`, `prepared`, `schedule` | what a render of this scene will do |
//! | pipeline | `emit`, `trace`, `view`, `connect`, `accumulation`, `protocol`, `host`, `reference` | the reference backend and the protocol |

#![cfg_attr(not(feature = "std"), no_std)]

#[cfg(all(feature = "std", target_os = "none"))]
compile_error!("feature `std` cannot be used on a bare-metal target: build with --no-default-features");

extern crate alloc;

pub mod progress;

pub mod bands;
pub mod cie;
pub mod color;
pub mod dispersion;
pub mod image;
pub mod mesh;
pub mod scene;
pub mod validate;

pub mod bvh;
pub mod bvh_build;
pub mod camera;
pub mod gather;
pub mod geometry;
pub mod grid;
pub mod math;
pub mod optics;
pub mod photon;
pub mod pixel_sample;
pub mod ray;
pub mod rng;
pub mod sobol;
pub mod texture;
pub mod tolerance;
pub mod triangle;
pub mod visible;

pub mod absorption;
pub mod effects;
pub mod prepared;
pub mod projection;
pub mod reach;
pub mod schedule;
pub mod surface;

pub mod accumulation;
pub mod connect;
pub mod emit;
pub mod host;
pub mod protocol;
pub mod reference;
pub mod trace;
pub mod view;

pub use accumulation::{Accumulation, MergeError};
pub use bands::{Band, BandSpec, BandTable};
pub use dispersion::{Dispersion, Glass};
pub use effects::{Effect, EffectPlan};
pub use image::Image;
pub use photon::{Photon, PhotonMap, TraceStats};
pub use prepared::PreparedScene;
pub use progress::{NoProgress, Progress, Stage, StageTimes};
pub use protocol::{Backend, BackendError, Change, Render, RenderStats};
pub use reference::ReferenceBackend;
pub use scene::{
    Camera, Checker, Estimator, Light, Material, Object, PhotonSequence, RadiusMode, RenderSettings, Scene, SceneError,
    Shape, Texture, ViewPaths, WavelengthSampling,
};

/// Re-exported so that users of the scene model need not depend on glam themselves.
pub use glam::Vec3;
