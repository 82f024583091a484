//! What can reach what, judged with bounding spheres: an object's bounds,
//! whether a light can send light into a sphere, whether the camera can
//! see into one. The effect plan and the projection maps decide with them.

use crate::model::scene::{Camera, Light, Shape};
use crate::util::math::{asin, cos, radians, sqrt};
use glam::Vec3;

/// A bounding sphere (centre, radius) of a shape; infinite radius for planes.
pub fn bounds(shape: &Shape) -> (Vec3, f32) {
    let around = |points: &[Vec3]| {
        let center = points.iter().copied().sum::<Vec3>() / points.len().max(1) as f32;
        (center, points.iter().map(|p| (*p - center).length()).fold(0.0, f32::max))
    };
    match shape {
        Shape::Sphere { center, radius } => (*center, *radius),
        Shape::Plane { point, .. } => (*point, f32::INFINITY),
        Shape::Disk { center, radius, .. } => (*center, *radius),
        Shape::Prism { vertices, extrude } => {
            let [a, b, c] = *vertices;
            around(&[a, b, c, a + *extrude, b + *extrude, c + *extrude])
        }
        Shape::Mesh { positions, .. } => around(positions),
    }
}

/// Can `light` send light into the sphere (centre `c`, radius `r`)? Not
/// beyond its range, where its first segment ends
/// ([`crate::model::light_range`]).
pub fn light_reaches(light: &Light, c: Vec3, r: f32) -> bool {
    if !r.is_finite() {
        return true;
    }
    match light {
        Light::Point { position, range, .. } => within_range(*position, *range, c, r),
        Light::Spot { position, direction, cone_deg, range, .. } => {
            if !within_range(*position, *range, c, r) {
                return false;
            }
            let to = c - *position;
            let dist = to.length();
            if dist <= r {
                return true;
            }
            let angle = to.normalize().dot(direction.normalize()).clamp(-1.0, 1.0);
            let spread = radians(*cone_deg) + asin((r / dist).min(1.0));
            spread >= core::f32::consts::PI || angle >= cos(spread)
        }
        Light::Beam { position, direction, radius, .. } => {
            let axis = direction.normalize();
            let along = (c - *position).dot(axis);
            let off_axis = (c - *position - axis * along).length();
            along > -r && off_axis <= radius + r
        }
        Light::Area { vertices: [v0, v1, v2], .. } => {
            // In front of its plane (it emits from its front face only).
            let normal = (*v1 - *v0).cross(*v2 - *v0).normalize();
            (c - *v0).dot(normal) > -r
        }
        Light::Sun { .. } | Light::Environment { .. } => true,
    }
}

/// Whether some point of the sphere (centre `c`, radius `r`) is nearer
/// than `range` to a light at `position` (always, without a range).
fn within_range(position: Vec3, range: Option<f32>, c: Vec3, r: f32) -> bool {
    range.is_none_or(|range| (c - position).length() - r < range)
}

/// The beam a sun's photons leave from: a disc across the sun's direction
/// that covers the spheres of `targets` (the scene's mirrors and glass),
/// placed beyond every bounded object of `scene_bounds` as seen from the
/// sun, with the sun's irradiance over its area. A photon that would miss
/// every target could only light a diffuse surface directly, which the view
/// pass ray traces, so nothing outside the disc is lost. With no targets
/// the disc covers every bounded object (or the unit sphere).
pub fn sun_beam(
    direction: Vec3,
    irradiance: f32,
    spectrum: &crate::model::spectrum::Spectrum,
    targets: &[(Vec3, f32)],
    scene_bounds: &[(Vec3, f32)],
) -> Light {
    let axis = direction.normalize();
    let finite: alloc::vec::Vec<(Vec3, f32)> = scene_bounds.iter().copied().filter(|b| b.1.is_finite()).collect();
    let cover = if !targets.is_empty() { targets } else { &finite[..] };
    let (center, radius) = if cover.is_empty() {
        (Vec3::ZERO, 1.0)
    } else {
        let center = cover.iter().map(|b| b.0).sum::<Vec3>() / cover.len() as f32;
        (center, cover.iter().map(|(c, r)| (*c - center).length() + r).fold(0.0, f32::max))
    };
    // Back from the centre, past every bounded object on the sun's side.
    let back = finite.iter().map(|(c, r)| (center - *c).dot(axis) + r).fold(radius, f32::max);
    let position = center - axis * (back * 1.01 + 1e-3);
    Light::Beam {
        position,
        direction: axis,
        radius,
        power: irradiance * core::f32::consts::PI * radius * radius,
        spectrum: spectrum.clone(),
    }
}

/// Can the camera see into the sphere (centre `c`, radius `r`)? Tests the
/// sphere against the cone that circumscribes the view frustum.
pub fn camera_sees(camera: &Camera, aspect: f32, c: Vec3, r: f32) -> bool {
    if !r.is_finite() {
        return true;
    }
    let forward = (camera.look_at - camera.position).normalize();
    let to = c - camera.position;
    let dist = to.length();
    if dist <= r {
        return true;
    }
    let half_v = radians(camera.fov_deg) * 0.5;
    let tan_v = crate::util::math::tan(half_v);
    let half_diag = crate::util::math::atan2(tan_v * sqrt(1.0 + aspect * aspect), 1.0);
    let spread = half_diag + asin((r / dist).min(1.0));
    spread >= core::f32::consts::PI || to.normalize().dot(forward) >= cos(spread)
}
