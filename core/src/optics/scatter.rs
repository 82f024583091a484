//! Scattering, written once: the ray a path takes when it leaves a
//! dielectric surface (one branch chosen with its reflectance as
//! probability, or both branches with their weights; the reflectance is
//! Fresnel's, or a thin film's at the path's wavelength) or bounces off a
//! diffuse one (Lambert's law, indirect light's photons), and where a ray
//! leaving a surface starts, and a metal's reflection off one facet of
//! its GGX microsurface. A thin sheet (`thin`, glTF's thin-walled
//! transmission) reflects with [`sheet_reflectance`] and passes the rest
//! straight on: its two faces bend a ray back to where it was going, no
//! distance apart. Photons, the view rays and the sampled view paths all
//! scatter here; the CPU's packets and the WGSL twin mirror these functions.

use crate::geometry::primitive::{basis, cone_direction};
use crate::geometry::ray::Ray;
use crate::model::scene::ThinFilm;
use crate::optics::fresnel::{fresnel, interface, reflect, refract, sheet_reflectance};
use crate::optics::microfacet::Ggx;
use crate::util::math::sqrt;
use crate::util::tolerance;
use glam::Vec3;

/// The origin of a ray leaving surface point `p` (normal `n`, either side)
/// in direction `dir`: pushed off the surface to the side `dir` goes.
#[inline]
pub fn offset_origin(p: Vec3, n: Vec3, dir: Vec3) -> Vec3 {
    let eps = tolerance::surface_offset(p);
    if dir.dot(n) >= 0.0 { p + n * eps } else { p - n * eps }
}

/// What one path meets at a dielectric's surface: the relative index at
/// its wavelength, whether the glass is a thin sheet, and the surface's
/// film (if any) with the wavelength the path sees it at.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Face {
    /// The relative index of refraction (inside over outside).
    pub ior: f32,
    /// A thin sheet: rays pass straight on.
    pub thin: bool,
    /// A film on the surface, its index relative to the outside.
    pub film: Option<ThinFilm>,
    /// The wavelength the film is seen at (nm; unused without a film).
    pub lambda_nm: f32,
}

impl Face {
    /// Bare glass of index `ior` (a sheet: `thin`).
    pub fn bare(ior: f32, thin: bool) -> Self {
        Face { ior, thin, film: None, lambda_nm: 0.0 }
    }

    /// The reflectance of one interface from index `n1` into `n2` at
    /// incidence cosine `cos_i`: Fresnel's, or the film's Airy sum.
    #[inline]
    fn interface_reflectance(&self, cos_i: f32, n1: f32, n2: f32) -> f32 {
        match self.film {
            None => fresnel(cos_i, n1, n2),
            Some(film) => film.reflectance(cos_i, n1, n2, self.lambda_nm),
        }
    }

    /// The share of light reflected here for a ray at incidence cosine
    /// `cos_i` going from `n1` into `n2` (a sheet: both of its faces and
    /// what bounces between them, [`sheet_reflectance`]).
    #[inline]
    pub fn reflectance(&self, cos_i: f32, n1: f32, n2: f32) -> f32 {
        if self.thin {
            sheet_reflectance(self.interface_reflectance(cos_i, 1.0, self.ior))
        } else {
            self.interface_reflectance(cos_i, n1, n2)
        }
    }
}

/// The ray leaving a dielectric surface at `point` (outward normal
/// `outward`) for one arriving along `direction`: reflected with
/// probability equal to the reflectance (`u < R`, [`Face::reflectance`]),
/// refracted otherwise; total internal reflection always reflects. Photons
/// and sampled view paths choose their branch with it.
pub fn scatter_dielectric(direction: Vec3, point: Vec3, outward: Vec3, face: Face, u: f32) -> Ray {
    let (n, n1, n2) = interface(direction, outward, face.ior);
    let cos_i = -direction.dot(n);
    let d = if u < face.reflectance(cos_i, n1, n2) {
        reflect(direction, n)
    } else if face.thin {
        direction
    } else {
        refract(direction, n, n1, n2).unwrap_or_else(|| reflect(direction, n))
    };
    Ray { origin: offset_origin(point, n, d), direction: d }
}

/// The ray leaving a diffuse surface at `point` (normal `normal`, either
/// side) for one arriving along `direction`: Lambert's law, a
/// cosine-distributed direction about the normal on the side the ray came
/// from (polar cosine √(1 − `u1`), azimuth `u2` turns). Indirect light's
/// photons bounce with it.
pub fn scatter_diffuse(direction: Vec3, point: Vec3, normal: Vec3, u1: f32, u2: f32) -> Ray {
    let n = if direction.dot(normal) < 0.0 { normal } else { -normal };
    let d = cone_direction(n, sqrt(1.0 - u1), u2);
    Ray { origin: offset_origin(point, n, d), direction: d }
}

/// A ray reflected off a metal ([`scatter_metal`]): where it goes, the
/// cosine at the facet it reflected off (Fresnel's there), and the share
/// G2/G1 of such reflections the microsurface does not shadow (1 when
/// polished). A path's weight is that share times the facet's Fresnel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MetalBounce {
    /// The reflected ray.
    pub ray: Ray,
    /// The cosine between the incoming ray and the facet's normal.
    pub cos_facet: f32,
    /// G2/G1: the reflection's share that leaves unshadowed.
    pub unshadowed: f32,
}

/// The ray arriving along `direction` reflects off a metal at `point`
/// (normal `normal`, either side; the ray comes from the side it faces):
/// about the normal when polished (`ggx` `None`), else about a facet
/// normal drawn from the GGX normals that `direction` sees (Heitz 2018,
/// [`Ggx::sample_visible_normal`], from `u1`, `u2`). `None` where the
/// reflection would leave below the surface: the path ends there.
pub fn scatter_metal(
    direction: Vec3,
    point: Vec3,
    normal: Vec3,
    ggx: Option<Ggx>,
    u1: f32,
    u2: f32,
) -> Option<MetalBounce> {
    let n = if direction.dot(normal) < 0.0 { normal } else { -normal };
    let Some(ggx) = ggx else {
        let d = reflect(direction, n);
        let cos_facet = -direction.dot(n);
        return Some(MetalBounce {
            ray: Ray { origin: offset_origin(point, n, d), direction: d },
            cos_facet,
            unshadowed: 1.0,
        });
    };
    let (t, b) = basis(n);
    let wo = -direction;
    let local = Vec3::new(wo.dot(t), wo.dot(b), wo.dot(n));
    if local.z <= 0.0 {
        return None;
    }
    let (wi, unshadowed) = ggx.sample_reflection(local, u1, u2)?;
    let cos_facet = local.dot((local + wi).normalize());
    let d = (t * wi.x + b * wi.y + n * wi.z).normalize();
    Some(MetalBounce { ray: Ray { origin: offset_origin(point, n, d), direction: d }, cos_facet, unshadowed })
}

/// Both branches at a dielectric surface, for a path that follows both:
/// the reflected ray with its Fresnel reflectance R, and the refracted ray
/// (weight 1 − R) unless the ray is totally internally reflected.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DielectricBranches {
    /// The mirror-reflected ray.
    pub reflected: Ray,
    /// Fresnel reflectance R, the reflected ray's weight.
    pub reflectance: f32,
    /// The refracted ray; `None` under total internal reflection (then R = 1).
    pub refracted: Option<Ray>,
}

/// [`DielectricBranches`] of a ray arriving along `direction` at `point`
/// (outward normal `outward`) on the glass `face`.
pub fn split_dielectric(direction: Vec3, point: Vec3, outward: Vec3, face: Face) -> DielectricBranches {
    let (n, n1, n2) = interface(direction, outward, face.ior);
    let cos_i = -direction.dot(n);
    let reflectance = face.reflectance(cos_i, n1, n2);
    let d = reflect(direction, n);
    let reflected = Ray { origin: offset_origin(point, n, d), direction: d };
    let through = if face.thin { Some(direction) } else { refract(direction, n, n1, n2) };
    let refracted = through.map(|d| Ray { origin: offset_origin(point, n, d), direction: d });
    DielectricBranches { reflected, reflectance, refracted }
}
