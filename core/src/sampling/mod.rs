//! Layer 2, sampling: the low-discrepancy numbers photons and view paths draw
//! (Owen-scrambled Sobol points, the per-pixel sampler) and the wavelength
//! distributions of lights' spectra, an environment's radiance and its
//! median cut into directional lights, and the directions of a spot's soft-edged cone.

pub mod environment;
pub mod light_spectrum;
pub mod pixel_sample;
pub mod sobol;
pub mod spot_cone;
