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

use crate::geometry::primitive::basis;
use crate::model::scene::Light;
use crate::plan::reach::light_reaches;
use crate::util::math::{cos, radians, sin_cos_turns, sqrt};
use alloc::vec::Vec;
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
            // A sun is aimed as the beam it emits from, an environment as
            // its suns' (`PreparedScene::emitters`); an area light's photons
            // leave every point of it, which one cone per target cannot hold.
            Light::Sun { .. } | Light::Environment { .. } | Light::Area { .. } => return None,
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
                let (origin, inside) = match light {
                    Light::Spot { position, direction, cone_deg, .. } => {
                        (*position, d.dot(direction.normalize()) >= cos(radians(*cone_deg)))
                    }
                    Light::Point { position, .. } => (*position, true),
                    Light::Beam { position, .. } => (*position, false),
                    Light::Sun { .. } | Light::Environment { .. } | Light::Area { .. } => {
                        unreachable!("a projection map holds spot, point and beam lights only (Projection::new)")
                    }
                };
                let covering = axis.iter().zip(cos_max).filter(|(a, c)| d.dot(**a) >= **c).count().max(1);
                ProjectedSample { origin, direction: d, weight: weight(inside, self.scale, covering) }
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
            (Targets::Discs { .. }, _) => ProjectedSample { origin: Vec3::ZERO, direction: Vec3::Z, weight: 0.0 },
        }
    }
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

/// A unit direction at polar cosine `cos_t` around `axis`, azimuth `u · 2π`
/// (the same construction as the emitter's).
#[inline]
pub fn cone_direction(axis: Vec3, cos_t: f32, u: f32) -> Vec3 {
    let sin_t = sqrt((1.0 - cos_t * cos_t).max(0.0));
    let (sin_phi, cos_phi) = sin_cos_turns(u);
    let (t, b) = basis(axis);
    (t * (sin_t * cos_phi) + b * (sin_t * sin_phi) + axis * cos_t).normalize()
}
