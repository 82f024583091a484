//! Scattering, written once: the ray a path takes when it leaves a
//! dielectric surface (one branch chosen with its reflectance as
//! probability, or both branches with their weights; the reflectance is
//! Fresnel's, or a thin film's at the path's wavelength) or bounces off a
//! diffuse one (Lambert's law, indirect light's photons), and where a ray
//! leaving a surface starts, and a metal's reflection off one facet of
//! its GGX microsurface. A thin sheet (`thin`, glTF's thin-walled
//! transmission) reflects with [`sheet_reflectance`] and passes the rest
//! straight on: its two faces bend a ray back to where it was going, no
//! distance apart. Rough glass does all of this about one facet normal
//! drawn from its GGX microsurface ([`scatter_rough_dielectric`]; a rough
//! sheet passes light on as its reflection mirrored through the surface).
//! Photons, the view rays and the sampled view paths all scatter here; the
//! CPU's packets and the WGSL twin mirror these functions.

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

/// A ray leaving rough glass off one facet ([`scatter_rough_dielectric`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GlassBounce {
    /// The reflected or transmitted ray.
    pub ray: Ray,
    /// G2/G1: the share of such rays the microsurface lets out unshadowed.
    pub unshadowed: f32,
    /// The ray passed through the surface (refracted, or crossed a sheet).
    pub crossed: bool,
    /// The branch number rescaled within the branch it chose: uniform on
    /// [0, 1) and independent of the choice, so a photon spends it on its
    /// survival (`leftover < unshadowed`) without a number of its own.
    pub leftover: f32,
}

/// Where a ray meets one facet of rough glass: the normal facing it, the
/// facet's Fresnel reflectance, the ray reflected off the facet and the
/// one passed through it (`None` under total internal reflection).
struct Facet {
    n: Vec3,
    reflectance: f32,
    reflected: Vec3,
    through: Option<Vec3>,
}

impl Facet {
    /// The facet a ray along `direction` meets on the glass `face` (outward
    /// normal `outward`), drawn from the visible normals of `ggx` by the
    /// two numbers `u1`, `u2`.
    fn draw(direction: Vec3, outward: Vec3, face: Face, ggx: Ggx, (u1, u2): (f32, f32)) -> Facet {
        let (n, n1, n2) = interface(direction, outward, face.ior);
        let (t, b) = basis(n);
        let wo = Vec3::new(-direction.dot(t), -direction.dot(b), -direction.dot(n));
        let ml = ggx.sample_visible_normal(wo, u1, u2);
        let m = (t * ml.x + b * ml.y + n * ml.z).normalize();
        let reflectance = face.reflectance((-direction.dot(m)).clamp(0.0, 1.0), n1, n2);
        let reflected = reflect(direction, m);
        let through = match face.thin {
            // A sheet's two faces: the facet's reflection mirrored through
            // the surface (straight on when the facet is the normal).
            true => Some(reflected - n * (2.0 * reflected.dot(n))),
            false => refract(direction, m, n1, n2),
        };
        Facet { n, reflectance, reflected, through }
    }

    /// G2/G1 of a ray leaving along `d` (its side checked: a reflection
    /// stays on the incoming side, a transmission crosses), else `None`:
    /// the microsurface sends it the wrong way and the path ends there
    /// (the light single scattering drops).
    fn unshadowed(&self, ggx: Ggx, direction: Vec3, d: Vec3, crossed: bool) -> Option<f32> {
        let (cos_o, cos_i) = (-direction.dot(self.n), d.dot(self.n));
        if cos_o <= 0.0 || cos_i == 0.0 || (cos_i < 0.0) != crossed {
            return None;
        }
        // G2/G1 = (1 + Λo)/(1 + Λo + Λi); Λ reads a direction's cosine only.
        let (lo, li) = (ggx.lambda(Vec3::Z * cos_o), ggx.lambda(Vec3::Z * cos_i));
        Some((1.0 + lo) / (1.0 + lo + li))
    }
}

/// The ray arriving along `direction` at rough glass (`face`, outward
/// normal `outward`, its facets' normals `ggx`) at `point`: a facet normal
/// drawn from those `direction` sees (Heitz 2018, from the two numbers `facet`), then
/// Fresnel's choice at that facet (`u < R`: reflected off it, else
/// refracted through it at the path's own index, Walter et al. 2007).
/// `None` where the ray would leave on the wrong side of the surface: the
/// path ends there. Its weight is G2/G1 ([`GlassBounce::unshadowed`]).
pub fn scatter_rough_dielectric(
    direction: Vec3,
    (point, outward): (Vec3, Vec3),
    face: Face,
    ggx: Ggx,
    facet: (f32, f32),
    u: f32,
) -> Option<GlassBounce> {
    let f = Facet::draw(direction, outward, face, ggx, facet);
    let r = f.reflectance;
    let (d, crossed, leftover) = match f.through {
        Some(d) if u >= r => (d, true, (u - r) / (1.0 - r)),
        _ => (f.reflected, false, u / r),
    };
    let unshadowed = f.unshadowed(ggx, direction, d, crossed)?;
    let ray = Ray { origin: offset_origin(point, f.n, d), direction: d };
    Some(GlassBounce { ray, unshadowed, crossed, leftover: leftover.min(ONE_BELOW) })
}

/// The largest f32 below 1.
const ONE_BELOW: f32 = 1.0 - f32::EPSILON / 2.0;

/// Both branches at rough glass off one facet, for a path that follows
/// both: each ray with its weight (Fresnel's share at the facet times
/// G2/G1), `None` where the branch leaves on the wrong side or the ray is
/// totally internally reflected.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoughBranches {
    /// The ray reflected off the facet, and its weight R G2/G1.
    pub reflected: Option<(Ray, f32)>,
    /// The ray passed through it, and its weight (1 − R) G2/G1.
    pub crossed: Option<(Ray, f32)>,
}

/// [`RoughBranches`] of a ray arriving along `direction` at rough glass
/// (`face`, outward normal `outward`, facets `ggx`) at `point`, off the
/// facet the numbers `facet` draw ([`scatter_rough_dielectric`]'s facet).
pub fn split_rough_dielectric(
    direction: Vec3,
    (point, outward): (Vec3, Vec3),
    face: Face,
    ggx: Ggx,
    facet: (f32, f32),
) -> RoughBranches {
    let f = Facet::draw(direction, outward, face, ggx, facet);
    let branch = |d: Vec3, crossed: bool, share: f32| {
        let unshadowed = f.unshadowed(ggx, direction, d, crossed)?;
        Some((Ray { origin: offset_origin(point, f.n, d), direction: d }, share * unshadowed))
    };
    let r = if f.through.is_some() { f.reflectance } else { 1.0 };
    RoughBranches {
        reflected: branch(f.reflected, false, r),
        crossed: f.through.and_then(|d| branch(d, true, 1.0 - r)),
    }
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
