//! Photon emission: where white photon `index` starts, where it goes, and which light sent it.

use crate::geometry::primitive::{basis, cone_direction};
use crate::model::scene::Light;
use crate::optics::scatter::offset_origin;
use crate::plan::prepared::PreparedScene;

use crate::sampling::sobol::photon_f32;
use crate::sampling::spot_cone::SpotCone;
use crate::util::math::{sin_cos_turns, sqrt};
use crate::util::rng::{dim, random_f32};
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
    /// Flux multiplier: 1 without a projection map; with one, the photon's
    /// share of its light's emission (0: aimed outside the light, not traced).
    pub weight: f32,
}

/// The light that sends white photon `index` (chosen by power, [`dim::LIGHT`]).
#[inline]
pub fn light_of(scene: &PreparedScene, seed: u32, index: u32) -> usize {
    let u = random_f32(seed, index, dim::LIGHT);
    scene.light_cdf.iter().position(|&c| u < c).unwrap_or(scene.light_cdf.len() - 1)
}

/// Emits white photon `index` of the pass. Lights are chosen with
/// probability proportional to their power, so every photon carries the same
/// flux, Σ power / photons, times its projection-map weight.
pub fn emit(scene: &PreparedScene, seed: u32, index: u32) -> Emitted {
    emit_with(scene, seed, index, true)
}

/// Emits photon `index` over its light's whole distribution, never aimed
/// by a projection map: indirect light's photons
/// ([`crate::photons::indirect`]), for which every surface counts.
pub fn emit_unaimed(scene: &PreparedScene, seed: u32, index: u32) -> Emitted {
    emit_with(scene, seed, index, false)
}

fn emit_with(scene: &PreparedScene, seed: u32, index: u32, aimed: bool) -> Emitted {
    let light = light_of(scene, seed, index);
    // The light's own two-dimensional sample: a direction, or a point on a beam's disc.
    let sequence = scene.scene.render.photon_sequence;
    let u1 = photon_f32(sequence, seed, index, dim::DIRECTION);
    let u2 = photon_f32(sequence, seed, index, dim::DIRECTION + 1);
    let source = &scene.emitters[light];
    if let Some(projection) = scene.plan.projections[light].as_ref().filter(|_| aimed) {
        let u_target = random_f32(seed, index, dim::TARGET);
        let s = match source {
            Light::Area { vertices, .. } => {
                let (origin, normal) = area_origin(vertices, seed, index);
                projection.sample_area(origin, normal, u_target, u1, u2)
            }
            _ => projection.sample(source, u_target, u1, u2),
        };
        return Emitted { origin: s.origin, direction: s.direction, light, weight: s.weight };
    }
    match source {
        Light::Spot { position, direction, cone_deg, inner_cone_deg, .. } => {
            let axis = direction.normalize();
            let cos_t = SpotCone::new(*cone_deg, *inner_cone_deg).sample_cos(u1);
            Emitted { origin: *position, direction: cone_direction(axis, cos_t, u2), light, weight: 1.0 }
        }
        Light::Point { position, .. } => {
            let z = 1.0 - 2.0 * u1;
            let r = sqrt((1.0 - z * z).max(0.0));
            let (sin_phi, cos_phi) = sin_cos_turns(u2);
            Emitted { origin: *position, direction: Vec3::new(r * cos_phi, r * sin_phi, z), light, weight: 1.0 }
        }
        Light::Beam { position, direction, radius, .. } => {
            let axis = direction.normalize();
            let (t, b) = basis(axis);
            let r = radius * sqrt(u1);
            let (sin_phi, cos_phi) = sin_cos_turns(u2);
            let origin = *position + (t * cos_phi + b * sin_phi) * r;
            Emitted { origin, direction: axis, light, weight: 1.0 }
        }
        Light::Area { vertices, .. } => {
            // A cosine-weighted direction out of its front.
            let (origin, normal) = area_origin(vertices, seed, index);
            Emitted { origin, direction: cone_direction(normal, sqrt(1.0 - u1), u2), light, weight: 1.0 }
        }
        Light::Sun { .. } | Light::Environment { .. } => {
            unreachable!("a sun emits as its beam, an environment as its suns' (PreparedScene::emitters)")
        }
    }
}

/// Where white photon `index` leaves area light `vertices`: a uniform point
/// of the triangle ([`dim::AREA`]) pushed off it to its front, and its unit
/// front normal.
#[inline]
pub fn area_origin(vertices: &[Vec3; 3], seed: u32, index: u32) -> (Vec3, Vec3) {
    let [a, b, c] = *vertices;
    let s = sqrt(random_f32(seed, index, dim::AREA));
    let w2 = random_f32(seed, index, dim::AREA + 1);
    let point = a + (b - a) * (s * (1.0 - w2)) + (c - a) * (s * w2);
    let normal = (b - a).cross(c - a).normalize();
    (offset_origin(point, normal, normal), normal)
}
