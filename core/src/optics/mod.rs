//! Layer 4, optics: every scattering function. Reflection, refraction and
//! Fresnel at an interface, absorption inside coloured glass, what a surface
//! does to light, and the one place a path chooses its branch at glass.

pub mod absorption;
pub mod fresnel;
pub mod metal;
pub mod microfacet;
pub mod rough_glass;
pub mod scatter;
pub mod surface;
pub mod thin_film;
