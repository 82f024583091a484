//! What a surface sends toward an eye of a photon's light: π times its
//! BSDF from the photon's direction to the eye's, per RGB channel. Light
//! tracing weighs each photon it connects to the camera by it
//! ([`crate::photons::light_tracing`]), and a visible point on a rough
//! surface each photon it gathers ([`crate::photons::gather::gather_rough`]).

use crate::model::photon::{Photon, WHITE_BAND};
use crate::optics::fresnel::interface;
use crate::optics::metal::MetalOptics;
use crate::optics::microfacet::Ggx;
use crate::optics::rough_glass::rough_glass_bsdf;
use crate::optics::surface::{DielectricOptics, Surface};
use crate::plan::prepared::{Hit, PreparedScene};
use core::f32::consts::PI;
use glam::Vec3;

/// π times the BSDF, per RGB channel, by which the surface at `hit`
/// (seen along `toward`, `n` its normal facing the eye) sends `photon`'s
/// light toward the eye. A photon stored on a diffuse surface: its albedo,
/// where it lit the side the eye sees (a blended metal's diffuse part:
/// times its share toward the eye, (1 − m)(1 − max F_layer),
/// [`crate::model::metalness::Metalness::diffuse_share`]). One met on a
/// rough surface ([`Photon::on_rough_surface`]): [`rough_reflects`] about
/// the shading normal there.
pub fn reflects(scene: &PreparedScene, photon: &Photon, toward: Vec3, hit: &Hit, n: Vec3) -> Vec3 {
    let (band, lambda_nm) = (photon.band, photon.lambda_nm);
    if photon.on_rough_surface() {
        let bent = Hit { normal: scene.scattering_normal(hit, toward), ..*hit };
        return rough_reflects(scene, photon, toward, &bent);
    }
    let share = match &scene.surfaces[hit.object] {
        Surface::Diffuse { .. } => 1.0,
        Surface::Metal(metal) if metal.is_blended() => {
            let toward_eye = toward.dot(scene.scattering_normal(hit, toward)).abs();
            scene.diffuse_share_at(metal, hit, scene.metalness_at(metal, hit), toward_eye, band, lambda_nm)
        }
        _ => 0.0,
    };
    if share == 0.0 || photon.direction().dot(n) >= 0.0 {
        return Vec3::ZERO; // none, or it lit the other side
    }
    let albedo = scene.albedo_at(hit.object, hit.triangle, hit.point, n);
    scene.bands.reflectance(albedo, band, lambda_nm) * share
}

/// π times the BSDF by which the rough metal or glass at `bent` (its
/// normal the shading normal there) sends the light of `photon`, met
/// there, toward an eye that looks along `toward` ([`RoughSurface::reflects`]).
/// Zero on a polished point.
pub fn rough_reflects(scene: &PreparedScene, photon: &Photon, toward: Vec3, bent: &Hit) -> Vec3 {
    RoughSurface::at(scene, bent).map_or(Vec3::ZERO, |s| s.reflects(scene, photon, toward, bent))
}

/// Rough metal or glass at a point as its maps make it there, read once
/// for every photon a visible point there weighs.
pub enum RoughSurface<'a> {
    /// A metal's optics there ([`PreparedScene::metal_at`]).
    Metal(MetalOptics),
    /// Glass and its facets there.
    Glass(&'a DielectricOptics, Ggx),
}

impl<'a> RoughSurface<'a> {
    /// The rough metal or glass at `bent`, or `None` where it is neither
    /// (or glass polished there).
    pub fn at(scene: &'a PreparedScene, bent: &Hit) -> Option<Self> {
        match &scene.surfaces[bent.object] {
            Surface::Metal(metal) => Some(RoughSurface::Metal(scene.metal_at(metal, bent))),
            Surface::Dielectric(glass) => Some(RoughSurface::Glass(glass, scene.facets(bent)?)),
            _ => None,
        }
    }

    /// π times the BSDF by which this surface at `bent` (its normal the
    /// shading normal there) sends the light of `photon`, met there, toward
    /// an eye that looks along `toward`: a rough metal's (a blended metal's
    /// specular part's) GGX reflection with its Fresnel at the photon's
    /// wavelength, or rough glass's reflection or transmission on either
    /// side (what crosses a tinted sheet keeps its colour; what leaves
    /// solid glass takes (n_eye/n_photon)², `radiance_across`), as the
    /// view's highlights take them. Zero off a polished metal.
    pub fn reflects(&self, scene: &PreparedScene, photon: &Photon, toward: Vec3, bent: &Hit) -> Vec3 {
        let (band, lambda_nm) = (photon.band, photon.lambda_nm);
        let (wo, wi, normal) = (-toward, -photon.direction(), bent.normal);
        match self {
            RoughSurface::Metal(metal) => {
                let facing = if toward.dot(normal) < 0.0 { normal } else { -normal };
                PI * metal.reflection(wo, wi, facing, band, lambda_nm, &scene.bands)
            }
            RoughSurface::Glass(glass, ggx) => {
                let own = band != WHITE_BAND && scene.scene.render.wavelengths.continuous();
                let face = scene.face(glass, bent, band, own.then_some(lambda_nm));
                let f = PI * rough_glass_bsdf(wo, wi, normal, face, *ggx);
                match wi.dot(normal) * wo.dot(normal) < 0.0 {
                    true if glass.thin => glass.sheet_crossing_rgb(band) * f,
                    true => Vec3::splat(f * radiance_across(toward, normal, face.ior)),
                    false => Vec3::splat(f),
                }
            }
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
