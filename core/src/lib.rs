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
//! Its modules live in eight layer folders. A folder uses only the folders
//! below it in this table (a test, `tests/layers.rs`, reads the sources and
//! keeps it true), so a new module's place follows from what it uses:
//!
//! | layer | folder | modules | what |
//! |---|---|---|---|
//! | 7 | [`render`] | `visible`, `view`, `layer`, `aov`, `accumulation`, `protocol`, `host`, `reference` | the camera's side (or an engine's frame), the exact sums, the render protocol and the scalar reference backend |
//! | 6 | [`photons`] | `emit`, `wavelengths`, `path`, `trace`, `indirect`, `grid`, `reflects`, `gather`, `light_tracing` | the light's side: photons from emission to the gather and to the camera, caustic and indirect |
//! | 5 | [`plan`] | `area`, `area_aims`, `reach`, `projection`, `effects`, `prepared`, `drawn_suns`, `drawn_triangles`, `schedule` | what a render of this scene will do |
//! | 4 | [`optics`] | `fresnel`, `microfacet`, `metal`, `rough_glass`, `thin_film`, `absorption`, `surface`, `scatter` | every scattering function, and the one branch choice at glass |
//! | 3 | [`geometry`] | `ray`, `triangle`, `primitive`, `bvh`, `bvh_build`, `camera`, `texture`, `shading`, `normal_map`, `form_factor` | rays, intersections, hierarchies, the camera, textures, shading normals, normal maps, form factors |
//! | 2 | [`sampling`] | `sobol`, `pixel_sample`, `light_spectrum`, `environment`, `spot_cone` | the low-discrepancy numbers paths draw, the wavelengths lights emit, what an environment sends each way, a spot's cone |
//! | 1 | [`model`] | `scene`, `validate`, `mesh`, `environment`, `light_range`, `bands`, `cie`, `color`, `dispersion`, `image`, `photon`, `wavelength_rgb`, `reflectance`, `metals`, `metalness`, `spectrum`, `rgb_spectrum` | what the user described and what backends exchange |
//! | 0 | [`util`] | `math`, `rng`, `tolerance`, `progress` | float math with and without `std`, random numbers, tolerances, progress |
//!
//! Layers 0–4 are pure functions that the CPU's packets and the WGSL
//! shaders mirror (the twin tests compare them); layers 5–7 are the scalar
//! pipeline, the definition of right that every backend is compared with.

#![cfg_attr(not(feature = "std"), no_std)]

#[cfg(all(feature = "std", target_os = "none"))]
compile_error!("feature `std` cannot be used on a bare-metal target: build with --no-default-features");

extern crate alloc;

pub mod geometry;
pub mod model;
pub mod optics;
pub mod photons;
pub mod plan;
pub mod render;
pub mod sampling;
pub mod util;

pub use model::bands::{Band, BandSpec, BandTable};
pub use model::dispersion::{Dispersion, Glass};
pub use model::image::Image;
pub use model::metals::{MetalColor, NamedMetal};
pub use model::photon::{Photon, PhotonMap, TraceStats};
pub use model::scene::{
    Camera, Checker, Estimator, Light, Material, NormalMap, Object, PhotonSequence, RadiusMode, RenderSettings, Scene,
    SceneError, Shape, Texture, ViewPaths, WavelengthSampling,
};
pub use plan::effects::{Effect, EffectPlan};
pub use plan::prepared::PreparedScene;
pub use render::accumulation::{Accumulation, MergeError};
pub use render::layer::LayerFrame;
pub use render::protocol::{Arithmetic, Backend, BackendError, Change, Render, RenderStats};
pub use render::reference::ReferenceBackend;
pub use util::progress::{NoProgress, Progress, Stage, StageTimes};

/// Re-exported so that users of the scene model need not depend on glam themselves.
pub use glam::{Vec3, Vec4};
