//! Projection maps (after Jensen): each light emits caustic photons only
//! toward the mirrors and glass it can reach.
//!
//! A photon whose first hit is diffuse never becomes a caustic photon, so
//! sampling only the directions (spot, point) or disc positions (beam) that
//! lead to a specular object's bounding sphere loses nothing. To stay
//! unbiased each photon is weighted by the ratio of the sampled measure to
//! the light's own (Σ target measure / light measure), divided by the number
//! of targets that cover its sample (targets may overlap); samples outside
//! the light's own cone or disc get weight 0 and are not traced.

use crate::geometry::primitive::{basis, cone_direction};
use crate::model::scene::Light;
use crate::plan::reach::light_reaches;
use crate::sampling::spot_cone::SpotCone;
use crate::util::math::{cos, radians, sin_cos_turns, sqrt};
use alloc::vec::Vec;
use core::f32::consts::PI;
use glam::Vec3;

/// Where a light's photons are aimed.
#[derive(Clone, Debug, PartialEq)]
pub enum Targets {
    /// Cones of directions from the light (spot and point lights).
    Cones {
        /// Unit axis of each cone.
        axis: Vec<Vec3>,
        /// Cosine of each cone's half-angle.
        cos_max: Vec<f32>,
    },
    /// Discs on the emitting plane (beams).
    Discs {
        /// Centre of each disc, on the beam's emitting plane.
        center: Vec<Vec3>,
        /// Radius of each disc.
        radius: Vec<f32>,
    },
    /// Bounding spheres, each seen in a cone from wherever on an area light
    /// a photon starts ([`Projection::sample_area`]).
    Spheres {
        /// Centre of each sphere.
        center: Vec<Vec3>,
        /// Radius of each sphere.
        radius: Vec<f32>,
        /// The probability of aiming at each (the differences of the CDF).
        probability: Vec<f32>,
    },
}

/// A light's projection map.
#[derive(Clone, Debug, PartialEq)]
pub struct Projection {
    /// The targets.
    pub targets: Targets,
    /// Cumulative probability of choosing each target (by its measure).
    pub cdf: Vec<f32>,
    /// Σ target measure / light measure: the weight of a sample covered once.
    pub scale: f32,
}

/// A sampled emission: origin, unit direction, flux weight (0: not emitted).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProjectedSample {
    /// Start point.
    pub origin: Vec3,
    /// Unit direction.
    pub direction: Vec3,
    /// Flux multiplier of the photon.
    pub weight: f32,
}

impl Projection {
    /// The projection map of `light` onto the bounding spheres `spheres`
    /// (of the scene's mirrors and glass), or `None` when it would not save
    /// anything (the light sits inside a target, or the targets cover as
    /// much as the light emits into).
    pub fn new(light: &Light, spheres: &[(Vec3, f32)]) -> Option<Projection> {
        let (targets, measures, light_measure) = match light {
            Light::Spot { position, cone_deg, .. } => {
                let (axis, cos_max) = cones(light, *position, spheres)?;
                let m = cos_max.iter().map(|c| 1.0 - c).collect::<Vec<_>>();
                (Targets::Cones { axis, cos_max }, m, 1.0 - cos(radians(*cone_deg)))
            }
            Light::Point { position, .. } => {
                let (axis, cos_max) = cones(light, *position, spheres)?;
                let m = cos_max.iter().map(|c| 1.0 - c).collect::<Vec<_>>();
                (Targets::Cones { axis, cos_max }, m, 2.0)
            }
            Light::Beam { position, direction, radius, .. } => {
                let a = direction.normalize();
                let (mut center, mut radii) = (Vec::new(), Vec::new());
                for &(c, r) in spheres.iter().filter(|(c, r)| light_reaches(light, *c, *r)) {
                    center.push(c - a * (c - *position).dot(a));
                    radii.push(r);
                }
                let m = radii.iter().map(|r| r * r).collect::<Vec<_>>();
                (Targets::Discs { center, radius: radii }, m, radius * radius)
            }
            Light::Area { vertices, .. } => return area_projection(light, vertices, spheres),
            // A sun is aimed as the beam it emits from, an environment as
            // its suns' (`PreparedScene::emitters`).
            Light::Sun { .. } | Light::Environment { .. } => return None,
        };
        let total: f32 = measures.iter().sum();
        if !total.is_finite() || total >= light_measure {
            return None;
        }
        let mut acc = 0.0;
        let mut cdf: Vec<f32> = measures
            .iter()
            .map(|m| {
                acc += m;
                acc / total
            })
            .collect();
        if let Some(last) = cdf.last_mut() {
            *last = 1.0;
        }
        Some(Projection { targets, cdf, scale: total / light_measure })
    }

    /// Samples a photon of `light` with random numbers `u_target` (which
    /// target) and `u1`, `u2` (where in it).
    pub fn sample(&self, light: &Light, u_target: f32, u1: f32, u2: f32) -> ProjectedSample {
        let Some(j) = self.cdf.iter().position(|&c| u_target < c).or(self.cdf.len().checked_sub(1)) else {
            return ProjectedSample { origin: Vec3::ZERO, direction: Vec3::Z, weight: 0.0 };
        };
        match (&self.targets, light) {
            (Targets::Cones { axis, cos_max }, _) => {
                let cos_t = 1.0 - u1 * (1.0 - cos_max[j]);
                let d = cone_direction(axis[j], cos_t, u2);
                // The light's density there over a uniform cone's (its soft edge).
                let (origin, density) = match light {
                    Light::Spot { position, direction, cone_deg, inner_cone_deg, .. } => {
                        let cone = SpotCone::new(*cone_deg, *inner_cone_deg);
                        let f = cone.falloff(d.dot(direction.normalize()));
                        // Exactly f for a hard edge (its measure is 1 − cos_outer).
                        (*position, f * ((1.0 - cone.cos_outer) / cone.measure()))
                    }
                    Light::Point { position, .. } => (*position, 1.0),
                    Light::Beam { position, .. } => (*position, 0.0),
                    Light::Sun { .. } | Light::Environment { .. } | Light::Area { .. } => {
                        unreachable!("a projection map holds spot, point and beam lights only (Projection::new)")
                    }
                };
                let covering = axis.iter().zip(cos_max).filter(|(a, c)| d.dot(**a) >= **c).count().max(1);
                let w = weight(density > 0.0, self.scale, covering);
                ProjectedSample { origin, direction: d, weight: w * density }
            }
            (Targets::Discs { center, radius }, Light::Beam { position, direction, radius: beam_radius, .. }) => {
                let a = direction.normalize();
                let (t, b) = basis(a);
                let r = radius[j] * sqrt(u1);
                let (sin_phi, cos_phi) = sin_cos_turns(u2);
                let origin = center[j] + (t * cos_phi + b * sin_phi) * r;
                let inside = (origin - *position).length_squared() <= beam_radius * beam_radius;
                let covering = center
                    .iter()
                    .zip(radius)
                    .filter(|(c, r)| (origin - **c).length_squared() <= **r * **r)
                    .count()
                    .max(1);
                ProjectedSample { origin, direction: a, weight: weight(inside, self.scale, covering) }
            }
            (Targets::Discs { .. } | Targets::Spheres { .. }, _) => {
                ProjectedSample { origin: Vec3::ZERO, direction: Vec3::Z, weight: 0.0 }
            }
        }
    }

    /// Samples the direction of a photon that leaves an area light at
    /// `origin` (unit front normal `normal`): into the cone from `origin`
    /// of the sphere that `u_target` chooses, at (`u1`, `u2`) within it.
    /// Its weight is the light's cosine-weighted density over the mixture
    /// of the cones' uniform densities, (cos θ / π) / Σⱼ pⱼ [in cone j] /
    /// (2π (1 − cos θⱼ)), so every direction toward a sphere keeps its
    /// expected flux (0 behind the light: not traced).
    pub fn sample_area(&self, origin: Vec3, normal: Vec3, u_target: f32, u1: f32, u2: f32) -> ProjectedSample {
        let Targets::Spheres { center, radius, probability } = &self.targets else {
            return ProjectedSample { origin, direction: normal, weight: 0.0 };
        };
        let j = self.cdf.iter().position(|&c| u_target < c).unwrap_or(self.cdf.len() - 1);
        let (axis, gap) = sphere_cone(origin, center[j], radius[j]);
        let direction = cone_direction(axis, 1.0 - u1 * gap, u2);
        let mut density = 0.0;
        for k in 0..center.len() {
            let (axis, gap) = sphere_cone(origin, center[k], radius[k]);
            if direction.dot(axis) >= 1.0 - gap {
                density += probability[k] / (2.0 * PI * gap);
            }
        }
        let cos_n = direction.dot(normal);
        let weight = if cos_n > 0.0 && density > 0.0 { cos_n / PI / density } else { 0.0 };
        ProjectedSample { origin, direction, weight }
    }
}

/// The cone in which a sphere (centre `c`, radius `r`) is seen from `p`,
/// outside it: unit axis, and 1 − cos of its half-angle, written
/// s²/(1 + cos) (s = r/d) so that a far sphere's small cone keeps its digits.
#[inline]
pub fn sphere_cone(p: Vec3, c: Vec3, r: f32) -> (Vec3, f32) {
    let to = c - p;
    let d = sqrt(to.length_squared());
    let s2 = (r / d) * (r / d);
    (to / d, s2 / (1.0 + sqrt(1.0 - s2)))
}

/// The projection map of an area light (`vertices`) onto the spheres in
/// front of it: each chosen by its cosine-weighted solid angle seen from
/// the triangle's centre (sin² θ cos α, at least a twentieth of sin² θ, so
/// that a sphere low over the light's horizon keeps a chance); `None` when
/// a sphere comes as near the triangle as its own size (a cone from every
/// point of it would not exist) or the spheres fill the light's emission.
fn area_projection(light: &Light, vertices: &[Vec3; 3], spheres: &[(Vec3, f32)]) -> Option<Projection> {
    let [a, b, c] = *vertices;
    let normal = (b - a).cross(c - a).normalize();
    let centre = (a + b + c) / 3.0;
    let size = vertices.iter().map(|v| (*v - centre).length()).fold(0.0, f32::max);
    let (mut center, mut radius, mut measure) = (Vec::new(), Vec::new(), Vec::new());
    for &(c, r) in spheres {
        let d = (c - centre).length();
        if !r.is_finite() || d <= r + size {
            return None;
        }
        if light_reaches(light, c, r) {
            let sin2 = (r / d) * (r / d);
            center.push(c);
            radius.push(r);
            measure.push(sin2 * ((c - centre) / d).dot(normal).max(0.05));
        }
    }
    let total: f32 = measure.iter().sum();
    if center.is_empty() || !total.is_finite() || total >= 1.0 {
        return None;
    }
    let probability: Vec<f32> = measure.iter().map(|m| m / total).collect();
    let mut acc = 0.0;
    let mut cdf: Vec<f32> = probability
        .iter()
        .map(|p| {
            acc += p;
            acc
        })
        .collect();
    if let Some(last) = cdf.last_mut() {
        *last = 1.0;
    }
    Some(Projection { targets: Targets::Spheres { center, radius, probability }, cdf, scale: total })
}

#[inline]
fn weight(inside: bool, scale: f32, covering: usize) -> f32 {
    if inside { scale / covering as f32 } else { 0.0 }
}

/// Target cones from `position` (of `light`) toward each sphere it reaches;
/// `None` when the light sits inside one.
fn cones(light: &Light, position: Vec3, spheres: &[(Vec3, f32)]) -> Option<(Vec<Vec3>, Vec<f32>)> {
    let (mut axis, mut cos_max) = (Vec::new(), Vec::new());
    for &(c, r) in spheres {
        let d = (c - position).length();
        if d <= r || !r.is_finite() {
            return None;
        }
        if light_reaches(light, c, r) {
            axis.push((c - position) / d);
            cos_max.push(sqrt(1.0 - (r / d) * (r / d)));
        }
    }
    Some((axis, cos_max))
}
