//! What denoisers and compositors take besides the image (OpenImageDenoise's
//! auxiliary images, a compositor's depth): per pixel, through its centre,
//! the albedo and the (shading) normal at the first non-specular hit, and
//! the depth of the first hit. Through smooth glass both branches count
//! with their Fresnel weights, as OIDN's documentation asks; mirrors are
//! followed.

use crate::geometry::camera::PinholeCamera;
use crate::geometry::primitive::Ray;
use crate::model::image::Image;
use crate::model::photon::WHITE_BAND;
use crate::optics::fresnel::reflect;
use crate::optics::scatter::{offset_origin, split_dielectric};
use crate::optics::surface::Surface;
use crate::plan::prepared::PreparedScene;
use crate::util::tolerance::MIN_VIEW_WEIGHT;
use alloc::vec;
use alloc::vec::Vec;
use glam::Vec3;

/// A render's auxiliary images.
#[derive(Clone, Debug, PartialEq)]
pub struct Features {
    /// The albedo of the first non-specular surface (a ray that leaves the
    /// scene: what it sees there, clamped to 1), in [0, 1].
    pub albedo: Image,
    /// The world-space unit normal there, facing the camera (0 for the sky).
    pub normal: Image,
    /// The distance along the pixel's centre ray to the first surface it
    /// meets (∞ where it meets none).
    pub depth: Vec<f32>,
}

/// The features of `scene`'s pixels.
pub fn features(scene: &PreparedScene) -> Features {
    let r = &scene.scene.render;
    let camera = PinholeCamera::new(&scene.scene.camera, r.width, r.height);
    let mut out = Features {
        albedo: Image::new(r.width, r.height),
        normal: Image::new(r.width, r.height),
        depth: vec![f32::INFINITY; r.width as usize * r.height as usize],
    };
    for y in 0..r.height {
        for x in 0..r.width {
            let i = (y * r.width + x) as usize;
            let ray = camera.ray(x, y);
            if let Some(hit) = scene.intersect(&ray, f32::INFINITY) {
                out.depth[i] = hit.t;
            }
            let (albedo, normal) = first_diffuse(scene, &ray, 1.0, 0);
            out.albedo.pixels[i] = albedo;
            out.normal.pixels[i] = normal;
        }
    }
    out
}

/// The albedo and normal that `ray` finds at its first non-specular hit,
/// times `weight` (its share of the pixel), at specular depth `depth`.
fn first_diffuse(scene: &PreparedScene, ray: &Ray, weight: f32, depth: u32) -> (Vec3, Vec3) {
    let Some(hit) = scene.intersect(ray, f32::INFINITY) else {
        return (scene.background(ray.direction).clamp(Vec3::ZERO, Vec3::ONE) * weight, Vec3::ZERO);
    };
    // Mirrors, metals and glass scatter about the shading normal, and it
    // is the normal a denoiser takes (smooth across a mesh's triangles).
    let normal = scene.scattering_normal(&hit, ray.direction);
    let side = if ray.direction.dot(hit.normal) < 0.0 { 1.0 } else { -1.0 };
    let facing = normal * side;
    if depth >= scene.plan.max_depth.max(1) {
        return (Vec3::ZERO, facing * weight);
    }
    match &scene.surfaces[hit.object] {
        Surface::Diffuse { .. } => {
            let albedo = scene.albedo_at(hit.object, hit.triangle, hit.point, hit.normal * side);
            (albedo * weight, facing * weight)
        }
        // A rough or blended metal is a surface of its own to a denoiser: its colour is F0.
        Surface::Metal(metal) if metal.is_blended() || scene.facets(&hit).is_some() => {
            (scene.metal_at(metal, &hit).f0 * weight, facing * weight)
        }
        Surface::Mirror | Surface::Metal(_) => {
            let d = reflect(ray.direction, normal);
            first_diffuse(scene, &Ray { origin: offset_origin(hit.point, normal, d), direction: d }, weight, depth + 1)
        }
        Surface::Dielectric(glass) => {
            let face = scene.face(glass, &hit, WHITE_BAND, None);
            let split = split_dielectric(ray.direction, hit.point, normal, face);
            let (r, t) = (split.reflectance, 1.0 - split.reflectance);
            let mut sum = (Vec3::ZERO, Vec3::ZERO);
            for (branch, share) in [(Some(split.reflected), r), (split.refracted, t)] {
                if let Some(b) = branch.filter(|_| share * weight > MIN_VIEW_WEIGHT) {
                    let (a, n) = first_diffuse(scene, &b, weight * share, depth + 1);
                    sum = (sum.0 + a, sum.1 + n);
                }
            }
            sum
        }
    }
}
