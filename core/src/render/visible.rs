//! Visible points (progressive photon mapping's hit points): where a
//! pixel's view rays meet diffuse surfaces that need the caustic (and
//! rough metal and glass rough enough to gather it), traced
//! once per camera and scene; every photon pass then only gathers at them.

use crate::model::image::Image;
use crate::photons::gather::RoughPoint;
use crate::plan::prepared::Hit;
use alloc::vec::Vec;
use core::f32::consts::PI;
use glam::Vec3;

/// A diffuse (or rough) surface point seen through one view path of a pixel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VisiblePoint {
    /// Surface point.
    pub point: Vec3,
    /// Unit normal facing the viewer.
    pub normal: Vec3,
    /// What a unit of reflected caustic irradiance here (irradiance times
    /// the surface's reflectance) adds to the pixel: the path's RGB factor
    /// (Fresnel factors, band weight) × exposure / π.
    pub weight: Vec3,
    /// The surface's RGB albedo here, whose reflectance spectrum reflects
    /// each gathered photon ([`crate::model::bands::BandTable::reflectance`]).
    pub albedo: Vec3,
    /// The pixel, row-major (y · width + x).
    pub pixel: u32,
    /// On rough metal or glass: where, for its gather's BSDF (`None` on a
    /// diffuse surface, whose albedo reflects what it gathers).
    pub rough: Option<RoughPoint>,
}

impl VisiblePoint {
    /// The visible point where a view ray along `toward` meets rough metal
    /// or glass at `bent` (its normal the shading normal there), for a
    /// path of RGB factor `tint` (what a unit of the gathered light, times
    /// π, adds to the pixel: `tint`/π).
    pub fn on_rough(bent: &Hit, toward: Vec3, tint: Vec3) -> Self {
        let rough = RoughPoint { object: bent.object, triangle: bent.triangle, shading: bent.normal, toward };
        let normal = if toward.dot(bent.normal) < 0.0 { bent.normal } else { -bent.normal };
        VisiblePoint { point: bent.point, normal, weight: tint / PI, albedo: Vec3::ONE, pixel: 0, rough: Some(rough) }
    }
}

/// A frame's view rays, traced: the image without caustics and the points
/// whose caustic each pass adds.
#[derive(Clone, Debug, PartialEq)]
pub struct VisiblePoints {
    /// Direct light, ambient and background, exposure applied.
    pub base: Image,
    /// The points, in the order the backend traced them (sums over them do
    /// not depend on that order: see [`crate::render::accumulation::Accumulation`]).
    pub points: Vec<VisiblePoint>,
}
