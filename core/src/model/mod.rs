//! Layer 1, model: what the user described (the scene, its validation, meshes,
//! environment maps)
//! and what every backend exchanges (spectral bands and the CIE tables behind
//! them, dispersion, colour, the colour of each wavelength and the reflectance
//! of each albedo and of measured metals, which materials are drawn as
//! metals, images, the photon and its map).

pub mod bands;
pub mod cie;
pub mod color;
pub mod dispersion;
pub mod environment;
pub mod image;
pub mod light_range;
pub mod mesh;
pub mod metalness;
pub mod metals;
pub mod photon;
pub mod reflectance;
pub mod rgb_spectrum;
pub mod scene;
pub mod spectrum;
pub mod validate;
pub mod wavelength_rgb;
