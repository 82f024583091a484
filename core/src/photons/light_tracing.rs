//! Light tracing: each caustic photon that lands where the camera sees a
//! diffuse surface directly is connected to the camera and adds its
//! reflected flux to the pixel it projects into (Veach's light tracing,
//! LuxCore's LIGHTCPU). Unbiased, with no radius: its error falls as 1/√N.
//!
//! A photon of flux Φ on a diffuse surface of albedo ρ seen from distance
//! d adds to pixel j (its mean radiance over the pixel's square of area A
//! on the image plane at distance 1)
//!
//! ```text
//! ΔL_j = Φ · ρ/π · cos θ_x / d² · 1 / (A · cos³ θ_c)
//!      = Φ · ρ/π · (−v·n) / (A · s³)
//! ```
//!
//! with v = x − eye, n the surface normal facing the eye, θ_x the angle
//! between them, θ_c the angle of v to the optical axis and s = d·cos θ_c
//! the point's depth along it (dω = dA cos θ_x / d² on the surface, and
//! dω = cos³ θ_c dA_image on the image plane). A band photon's flux counts
//! through its band's RGB weight, or the colour of its wavelength
//! ([`crate::model::bands::BandTable::rgb_of_flux`]), as in the density estimator. The camera's ray toward the photon must
//! reach it ([`CONNECTION_REL`]): the visibility test, and the hit gives
//! the surface's albedo and normal. On a blended metal the diffuse part
//! adds its share toward the eye of that, (1 − m)(1 − max F_layer)
//! ([`crate::model::metalness::Metalness::diffuse_share`]).
//!
//! Light tracing cannot connect through a mirror or glass to a pinhole, so
//! the caustics seen only that way are still gathered at visible points:
//! the view pass makes visible points only behind a specular bounce
//! ([`crate::render::view`]), and the paths are partitioned between the two
//! estimators by the camera side's specular depth: none counted twice.
//!
//! On rough metal and glass, light tracing brings what no view ray can: a
//! hidden light's ([`crate::model::scene::Light::is_hidden`]) caustic
//! photons are recorded where they meet such a surface
//! ([`crate::model::photon::ON_ROUGH_SURFACE`]) and weighted by π times
//! its BSDF toward the eye, in place of ρ ([`reflects`]:
//! a metal's GGX reflection, rough glass's reflection or transmission).
//! The view's paths behind a rough surface the camera sees then leave the
//! hidden lights' highlights out ([`traces_behind_rough`]): this
//! partition is by the light, the lights rays meet staying the view's.

use crate::geometry::camera::PinholeCamera;
use crate::geometry::ray::Ray;
use crate::model::photon::Photon;
use crate::photons::reflects::reflects;
use crate::plan::prepared::PreparedScene;
use crate::util::tolerance::CONNECTION_REL;
use alloc::vec::Vec;
use core::f32::consts::PI;
use glam::Vec3;

/// A photon's contribution to a pixel: radiance (linear RGB, exposure
/// applied) added to the pixel's mean for the pass.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Splat {
    /// The pixel, row-major (y · width + x).
    pub pixel: u32,
    /// What it adds to the pixel.
    pub radiance: Vec3,
}

/// Connects stored photons to the scene's camera.
pub struct CameraConnection<'a> {
    scene: &'a PreparedScene,
    camera: PinholeCamera,
    /// exposure / (π · pixel area).
    scale: f32,
}

impl<'a> CameraConnection<'a> {
    /// The connections of `scene`'s photons to its camera.
    pub fn new(scene: &'a PreparedScene) -> Self {
        let r = &scene.scene.render;
        let camera = PinholeCamera::new(&scene.scene.camera, r.width, r.height);
        CameraConnection { scene, camera, scale: importance_scale(r.exposure, &camera) }
    }

    /// What `photon` adds to the pixel that sees it, or `None` when no
    /// pixel sees it directly (outside the image, hidden) or the surface
    /// there sends none of its light toward the eye (its BSDF, see the
    /// module's notes on rough surfaces).
    pub fn splat(&self, photon: &Photon) -> Option<Splat> {
        let x = photon.pos();
        let seen = self.camera.project(x)?;
        let v = x - self.camera.origin;
        let d = v.length();
        let ray = Ray { origin: self.camera.origin, direction: v / d };
        let hit = self.scene.intersect(&ray, d * (1.0 + CONNECTION_REL))?;
        if hit.t < d * (1.0 - CONNECTION_REL) {
            return None;
        }
        let n = if ray.direction.dot(hit.normal) < 0.0 { hit.normal } else { -hit.normal };
        let reflects = reflects(self.scene, photon, ray.direction, &hit, n);
        if reflects == Vec3::ZERO {
            return None;
        }
        let importance = -v.dot(n) / (seen.depth * seen.depth * seen.depth) * self.scale;
        let flux = self.scene.bands.rgb_of_flux(photon.band, photon.lambda_nm, photon.flux);
        let radiance = flux * reflects * importance * self.scene.white_balance;
        Some(Splat { pixel: seen.y * self.camera.width + seen.x, radiance })
    }
}

/// Whether light tracing brings what a rough surface the camera sees
/// directly reflects or passes of the hidden lights' light
/// ([`crate::model::scene::Light::is_hidden`]) after mirrors, metals and
/// glass alone: the render light traces and traces caustic photons, which
/// are met on such surfaces ([`crate::model::photon::ON_ROUGH_SURFACE`];
/// a scene with no hidden light has no highlights to leave out).
/// Then the view's paths behind such a surface show no highlights of the
/// rough surfaces they meet ([`crate::render::view`]): that light is the
/// photons'.
pub fn traces_behind_rough(scene: &PreparedScene) -> bool {
    scene.scene.render.light_tracing && scene.caustic_photons() > 0
}

/// The factor every splat of `camera` shares: exposure / (π · pixel area)
/// (the BRDF's 1/π and the pixel's share of the image plane).
pub fn importance_scale(exposure: f32, camera: &PinholeCamera) -> f32 {
    exposure / (PI * camera.pixel_area())
}

/// The scalar reference's light tracing of a pass: what each of `photons`
/// adds, in their order (only when the scene asks for light tracing).
pub fn splat_photons(scene: &PreparedScene, photons: &[Photon]) -> Vec<Splat> {
    if !scene.scene.render.light_tracing {
        return Vec::new();
    }
    let connection = CameraConnection::new(scene);
    photons.iter().filter_map(|p| connection.splat(p)).collect()
}
