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
//! its BSDF toward the eye, in place of ρ (`CameraConnection::reflects`:
//! a metal's GGX reflection, rough glass's reflection or transmission).
//! The view's paths behind a rough surface the camera sees then leave the
//! hidden lights' highlights out ([`traces_behind_rough`]): this
//! partition is by the light, the lights rays meet staying the view's.

use crate::geometry::camera::PinholeCamera;
use crate::geometry::ray::Ray;
use crate::model::photon::{Photon, WHITE_BAND};
use crate::optics::fresnel::interface;
use crate::optics::rough_glass::rough_glass_bsdf;
use crate::optics::surface::Surface;
use crate::plan::prepared::{Hit, PreparedScene};
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
        let reflects = self.reflects(photon, ray.direction, &hit, n);
        if reflects == Vec3::ZERO {
            return None;
        }
        let importance = -v.dot(n) / (seen.depth * seen.depth * seen.depth) * self.scale;
        let flux = self.scene.bands.rgb_of_flux(photon.band, photon.lambda_nm, photon.flux);
        let radiance = flux * reflects * importance * self.scene.white_balance;
        Some(Splat { pixel: seen.y * self.camera.width + seen.x, radiance })
    }

    /// π times the BSDF, per RGB channel, by which the surface at `hit`
    /// (seen along `toward`, `n` its normal facing the eye) sends
    /// `photon`'s light toward the eye. A photon stored on a diffuse
    /// surface: its albedo, where it lit the side the eye sees (a blended
    /// metal's diffuse part: times its share toward the eye, (1 − m)(1 −
    /// max F_layer), [`crate::model::metalness::Metalness::diffuse_share`]).
    /// One met on a rough surface ([`Photon::on_rough_surface`]): π times
    /// a rough metal's (a blended metal's specular part's) BRDF, or rough
    /// glass's BSDF on either side (what crosses a tinted sheet keeps its
    /// colour; what leaves solid glass, [`radiance_across`]), as the
    /// view's highlights take them.
    fn reflects(&self, photon: &Photon, toward: Vec3, hit: &Hit, n: Vec3) -> Vec3 {
        let scene = self.scene;
        let (band, lambda_nm) = (photon.band, photon.lambda_nm);
        let (wo, wi) = (-toward, -photon.direction());
        let surface = &scene.surfaces[hit.object];
        if !photon.on_rough_surface() {
            let share = match surface {
                Surface::Diffuse { .. } => 1.0,
                Surface::Metal(metal) if metal.is_blended() => {
                    let toward_eye = toward.dot(scene.scattering_normal(hit, toward)).abs();
                    let m = scene.metalness_at(metal, hit);
                    scene.diffuse_share_at(metal, hit, m, toward_eye, band, lambda_nm)
                }
                _ => 0.0,
            };
            if share == 0.0 || wi.dot(n) <= 0.0 {
                return Vec3::ZERO; // none, or it lit the other side
            }
            let albedo = scene.albedo_at(hit.object, hit.triangle, hit.point, n);
            return scene.bands.reflectance(albedo, band, lambda_nm) * share;
        }
        let normal = scene.scattering_normal(hit, toward);
        match surface {
            Surface::Metal(metal) => {
                let facing = if toward.dot(normal) < 0.0 { normal } else { -normal };
                PI * scene.metal_at(metal, hit).reflection(wo, wi, facing, band, lambda_nm, &scene.bands)
            }
            Surface::Dielectric(glass) => {
                let Some(ggx) = scene.facets(hit) else { return Vec3::ZERO };
                let own = band != WHITE_BAND && scene.scene.render.wavelengths.continuous();
                let face = scene.face(glass, hit, band, own.then_some(lambda_nm));
                let f = PI * rough_glass_bsdf(wo, wi, normal, face, ggx);
                match wi.dot(normal) * wo.dot(normal) < 0.0 {
                    true if glass.thin => glass.sheet_crossing_rgb(band) * f,
                    true => Vec3::splat(f * radiance_across(toward, normal, face.ior)),
                    false => Vec3::splat(f),
                }
            }
            _ => Vec3::ZERO,
        }
    }
}

/// What radiance keeps of itself crossing glass of relative index `ior`
/// (outward normal `outward`) toward an eye that looks along `toward`:
/// (n_eye/n_photon)², radiance over n² being what a ray keeps. The
/// renderer's glass carries radiance across unscaled (rough glass's BTDF
/// leaves out this factor, [`crate::optics::microfacet::Ggx::transmission`]),
/// which a path that enters and leaves glass needs none of; but a photon's
/// flux inside glass is the physical one, so its light leaving toward the
/// eye takes it.
fn radiance_across(toward: Vec3, outward: Vec3, ior: f32) -> f32 {
    let (_, n_eye, n_photon) = interface(toward, outward, ior);
    let ratio = n_eye / n_photon;
    ratio * ratio
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
