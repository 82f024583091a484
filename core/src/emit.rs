//! Photon emission: where white photon `index` starts, where it goes, and which light sent it.

use crate::geometry::basis;
use crate::math::{cos, radians, sin_cos_turns, sqrt};
use crate::prepared::PreparedScene;
use crate::rng::{dim, random_f32};
use crate::scene::Light;
use glam::Vec3;

/// A white photon as it leaves its light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Emitted {
    /// Start point.
    pub origin: Vec3,
    /// Unit direction.
    pub direction: Vec3,
    /// Index of the light.
    pub light: usize,
}

/// Emits white photon `index` of the pass. Lights are chosen with
/// probability proportional to their power, so every photon carries the same
/// flux, Σ power / photons.
pub fn emit(scene: &PreparedScene, seed: u32, index: u32) -> Emitted {
    let u = random_f32(seed, index, dim::LIGHT);
    let light = scene.light_cdf.iter().position(|&c| u < c).unwrap_or(scene.light_cdf.len() - 1);
    let u1 = random_f32(seed, index, dim::DIRECTION);
    let u2 = random_f32(seed, index, dim::DIRECTION + 1);
    match &scene.scene.lights[light] {
        Light::Spot { position, direction, cone_deg, .. } => {
            let axis = direction.normalize();
            let cos_max = cos(radians(*cone_deg));
            let cos_t = 1.0 - u1 * (1.0 - cos_max);
            Emitted { origin: *position, direction: cone_direction(axis, cos_t, u2), light }
        }
        Light::Point { position, .. } => {
            let z = 1.0 - 2.0 * u1;
            let r = sqrt((1.0 - z * z).max(0.0));
            let (sin_phi, cos_phi) = sin_cos_turns(u2);
            Emitted { origin: *position, direction: Vec3::new(r * cos_phi, r * sin_phi, z), light }
        }
        Light::Beam { position, direction, radius, .. } => {
            let axis = direction.normalize();
            let (t, b) = basis(axis);
            let r = radius * sqrt(random_f32(seed, index, dim::POSITION));
            let (sin_phi, cos_phi) = sin_cos_turns(random_f32(seed, index, dim::POSITION + 1));
            let origin = *position + (t * cos_phi + b * sin_phi) * r;
            Emitted { origin, direction: axis, light }
        }
    }
}

/// A unit direction at polar cosine `cos_t` around `axis`, azimuth `u · 2π`.
#[inline]
fn cone_direction(axis: Vec3, cos_t: f32, u: f32) -> Vec3 {
    let sin_t = sqrt((1.0 - cos_t * cos_t).max(0.0));
    let (sin_phi, cos_phi) = sin_cos_turns(u);
    let (t, b) = basis(axis);
    (t * (sin_t * cos_phi) + b * (sin_t * sin_phi) + axis * cos_t).normalize()
}
