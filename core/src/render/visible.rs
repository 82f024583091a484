//! Visible points (progressive photon mapping's hit points): where a
//! pixel's view rays meet diffuse surfaces that need the caustic, traced
//! once per camera and scene; every photon pass then only gathers at them.

use crate::model::image::Image;
use alloc::vec::Vec;
use glam::Vec3;

/// A diffuse surface point seen through one view path of a pixel.
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
