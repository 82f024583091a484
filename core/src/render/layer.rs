//! The caustic layer: caustic irradiance in an engine's own frame, for the
//! engine's lighting to add to its surfaces (irradiance × albedo / π), in
//! place of prismatic's whole image.
//!
//! The engine hands its frame ([`LayerFrame`]): per pixel, the view depth
//! and normal of its nearest opaque surface (its depth and normal
//! prepass), seen by the scene's camera. Each caustic photon is projected
//! into that frame and counts where the engine sees the surface it landed
//! on: it lies on the plane of the pixel's surface ([`LAYER_PLANE_REL`]),
//! and it arrived on the side the camera sees. No view rays and no scene
//! intersections: the engine's depth buffer is the visibility test, so
//! the engine's own occluders (which prismatic's scene does not hold)
//! hide the caustic. The estimator is light tracing's
//! ([`crate::photons::light_tracing`]) without the BRDF: a photon of flux
//! Φ adds to pixel j's mean irradiance over the surface the pixel sees
//!
//! ```text
//! ΔE_j = Φ · (−v·n) / (A · s³)
//! ```
//!
//! (v = x − eye, n the surface's normal facing the eye, s the depth along
//! the optical axis, A the pixel's area on the image plane at distance 1):
//! a light-traced image's pixel on a diffuse surface of albedo ρ is
//! exactly ρ/π times the layer's.

use crate::geometry::camera::PinholeCamera;
use crate::model::photon::Photon;
use crate::photons::light_tracing::{Splat, importance_scale};
use crate::plan::prepared::PreparedScene;
use crate::util::tolerance::LAYER_PLANE_REL;
use alloc::vec::Vec;
use core::f32::consts::PI;
use glam::Vec3;

/// An engine's frame, seen by the scene's camera at the scene's image
/// size: per pixel (row-major, y down) the depth of the engine's nearest
/// opaque surface along the camera's optical axis (its view-space depth;
/// not finite, or 0, where the pixel sees no surface) and that surface's
/// world-space unit normal (either side).
#[derive(Clone, Debug, PartialEq)]
pub struct LayerFrame {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// View-space depth per pixel.
    pub depth: Vec<f32>,
    /// World-space normal per pixel.
    pub normal: Vec<Vec3>,
}

impl LayerFrame {
    /// The frame prismatic's own camera sees: at each pixel's centre, the
    /// first surface of the scene that the camera's ray meets (glass and
    /// mirrors included, as in an engine's depth prepass). What an engine
    /// showing the same scene would hand over; the tests and the CLI's
    /// layer use it.
    pub fn seen_by_camera(scene: &PreparedScene) -> LayerFrame {
        let r = &scene.scene.render;
        let camera = PinholeCamera::new(&scene.scene.camera, r.width, r.height);
        let pixels = (r.width * r.height) as usize;
        let (mut depth, mut normal) = (Vec::with_capacity(pixels), Vec::with_capacity(pixels));
        for y in 0..r.height {
            for x in 0..r.width {
                let ray = camera.ray(x, y);
                match scene.intersect(&ray, f32::INFINITY) {
                    Some(hit) => {
                        depth.push((hit.point - camera.origin).dot(camera.forward));
                        normal.push(hit.normal);
                    }
                    None => {
                        depth.push(f32::INFINITY);
                        normal.push(Vec3::ZERO);
                    }
                }
            }
        }
        LayerFrame { width: r.width, height: r.height, depth, normal }
    }

    /// Whether the frame fits `scene`'s image: its size, one depth and one
    /// normal per pixel.
    pub fn fits(&self, scene: &PreparedScene) -> bool {
        let r = &scene.scene.render;
        let pixels = (self.width as usize) * (self.height as usize);
        (self.width, self.height) == (r.width, r.height) && self.depth.len() == pixels && self.normal.len() == pixels
    }
}

/// Connects stored photons to the pixels of an engine's frame.
pub struct LayerConnection<'a> {
    scene: &'a PreparedScene,
    frame: &'a LayerFrame,
    camera: PinholeCamera,
    /// exposure / pixel area (light tracing's scale times π: no BRDF).
    scale: f32,
}

impl<'a> LayerConnection<'a> {
    /// The connections of `scene`'s photons to `frame` (which fits the scene).
    pub fn new(scene: &'a PreparedScene, frame: &'a LayerFrame) -> Self {
        let r = &scene.scene.render;
        let camera = PinholeCamera::new(&scene.scene.camera, r.width, r.height);
        LayerConnection { scene, frame, camera, scale: importance_scale(r.exposure, &camera) * PI }
    }

    /// What `photon` adds to the irradiance of the pixel that sees where it
    /// landed, or `None` when no pixel does (outside the frame, behind or
    /// in front of the engine's surface there, on its far side).
    pub fn splat(&self, photon: &Photon) -> Option<Splat> {
        if photon.on_rough_surface() {
            return None; // irradiance of diffuse surfaces only
        }
        let x = photon.pos();
        let seen = self.camera.project(x)?;
        let pixel = seen.y * self.camera.width + seen.x;
        let depth = self.frame.depth[pixel as usize];
        if !(depth.is_finite() && depth > 0.0) {
            return None;
        }
        // The surface the pixel's centre sees, and the photon's distance from its plane.
        let through =
            self.camera.corner + self.camera.right * (seen.x as f32 + 0.5) + self.camera.down * (seen.y as f32 + 0.5);
        let centre = self.camera.origin + through * depth;
        let normal = self.frame.normal[pixel as usize];
        let n = if (centre - self.camera.origin).dot(normal) < 0.0 { normal } else { -normal };
        if (x - centre).dot(n).abs() > LAYER_PLANE_REL * depth || photon.direction().dot(n) >= 0.0 {
            return None;
        }
        let v = x - self.camera.origin;
        let importance = -v.dot(n) / (seen.depth * seen.depth * seen.depth) * self.scale;
        let flux = self.scene.bands.rgb_of_flux(photon.band, photon.lambda_nm, photon.flux);
        Some(Splat { pixel, radiance: flux * importance * self.scene.white_balance })
    }
}

/// The scalar reference's layer of a pass: what each of `photons` adds to
/// `frame`'s irradiance, in their order.
pub fn layer_splats(scene: &PreparedScene, frame: &LayerFrame, photons: &[Photon]) -> Vec<Splat> {
    let connection = LayerConnection::new(scene, frame);
    photons.iter().filter_map(|p| connection.splat(p)).collect()
}
