//! One photon path in flight and what every photon does on its way: the
//! steps at mirrors, metals and glass (depth limit, absorption in coloured
//! glass, reflection, a metal's facet and Fresnel, or a dielectric's
//! Fresnel choice), shared by caustic and indirect light's
//! photons, and what a path stores.

use crate::geometry::primitive::Ray;
use crate::model::bands::BandTable;
use crate::model::light_range::range_window;
use crate::model::photon::{Photon, TraceStats, oct_pack};
use crate::optics::fresnel::reflect;
use crate::optics::scatter::{offset_origin, scatter_dielectric, scatter_metal, scatter_rough_dielectric};
use crate::optics::surface::{DielectricOptics, Surface};
use crate::plan::prepared::{Hit, PreparedScene};
use crate::util::rng::{dim, random_f32};
use glam::Vec3;

/// One photon path in flight: where it goes, its flux, band and wavelength, and
/// how many surfaces it has met after leaving its light (`bounces`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Path {
    pub(crate) ray: Ray,
    pub(crate) flux: f32,
    pub(crate) band: u16,
    /// The wavelength a continuous-spectrum photon is traced at.
    pub(crate) lambda_nm: Option<f32>,
    pub(crate) bounces: u32,
}

impl Path {
    /// Windows the flux of a path on its first segment by its light's
    /// `range` at its first hit, `t` from the light
    /// ([`crate::model::light_range`]); what the window takes counts as
    /// escaped. False when nothing is left.
    pub(crate) fn reach(&mut self, range: Option<f32>, t: f32, stats: &mut TraceStats) -> bool {
        if self.bounces > 0 || range.is_none() {
            return true;
        }
        let kept = self.flux * range_window(t, range);
        stats.flux_escaped += f64::from(self.flux - kept);
        self.flux = kept;
        kept > 0.0
    }

    /// The photon this path stores where it meets a diffuse surface at `point`.
    pub(crate) fn photon(&self, scene: &PreparedScene, point: Vec3, index: u32) -> Photon {
        Photon {
            position: point.to_array(),
            flux: self.flux,
            direction_oct: oct_pack(self.ray.direction),
            lambda_nm: stored_wavelength(&scene.bands, self.band, self.lambda_nm),
            emission: index,
            band: self.band,
            bounces: self.bounces as u16,
        }
    }
}

/// Whether path `p`, which has reached the blended metal at `hit` and been
/// stored there as on a diffuse surface, goes on as its specular part:
/// with the probability [`crate::model::metalness::Metalness::specular_share`] there
/// ([`dim::metal_part`]; [`crate::optics::metal`]). Always at a whole
/// metal, mirror or glass.
pub(crate) fn goes_on_as_metal(scene: &PreparedScene, index: u32, p: &Path, hit: &Hit) -> bool {
    match &scene.surfaces[hit.object] {
        Surface::Metal(metal) if metal.is_blended() => {
            let u = random_f32(scene.scene.render.seed, index, dim::metal_part(p.band, p.bounces));
            u < scene.metalness_at(metal, hit).specular_share()
        }
        _ => true,
    }
}

/// What became of a path at a mirror, metal or glass ([`cross_specular`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Crossing {
    /// It goes on, its ray the new one.
    On,
    /// It ended there, its flux tallied.
    Ended,
    /// A blended metal's specular layer passed it to the diffuse base
    /// below (nothing tallied), leaving the uniform number for the base's
    /// own choice.
    ToBase(f32),
}

/// Whether path `p` goes on at the mirror or glass it has reached at `hit`:
/// not past the depth limit, not absorbed on the segment inside coloured
/// glass that ends here ([`absorbed`]). An ended path's flux is tallied.
pub(crate) fn arrives_at_specular(
    scene: &PreparedScene,
    index: u32,
    p: &Path,
    hit: &Hit,
    stats: &mut TraceStats,
) -> bool {
    if p.bounces >= scene.plan.max_depth {
        stats.flux_depth_limited += f64::from(p.flux);
        return false;
    }
    if let Surface::Dielectric(glass) = &scene.surfaces[hit.object]
        && absorbed(glass, p.ray.direction, hit.normal, hit.t, p.band, || {
            random_f32(scene.scene.render.seed, index, dim::absorb(p.band, p.bounces))
        })
    {
        stats.flux_absorbed += f64::from(p.flux);
        return false;
    }
    true
}

/// Takes path `p` (one that does not split here) across the mirror, metal
/// or glass at `hit`: reflected; off a metal's facet ([`scatter_metal`],
/// its two numbers [`dim::bounce`]'s) with the facet's Fresnel at the
/// path's wavelength times the unshadowed share as its survival
/// probability ([`dim::scatter`]; Russian roulette, so survivors keep their
/// flux; on a blended metal the specular part's, [`crate::optics::metal::MetalOptics::specular_reflectance`],
/// and what its layer's facet passes reaches the base: [`Crossing::ToBase`]
/// with the probability [`crate::optics::metal::MetalOptics::layer_passes`]);
/// or Fresnel's choice between reflection and refraction at the
/// path's own index ([`dim::scatter`]), about the normal or, on rough
/// glass, about a facet's ([`scatter_rough_dielectric`], its numbers
/// [`dim::bounce`]'s), surviving with the unshadowed share (the branch
/// number's leftover). [`Crossing::Ended`] when the path ended here:
/// absorbed by a metal, by rough glass's microsurface or by a tinted sheet
/// ([`absorbed_crossing`]), its flux tallied. A white
/// path meets only grey metals: at a coloured one a white photon splits
/// or takes one band first, and indirect light's goes on as one of its
/// wavelengths. The bounce is the caller's to count.
pub(crate) fn cross_specular(
    scene: &PreparedScene,
    index: u32,
    p: &mut Path,
    hit: &Hit,
    stats: &mut TraceStats,
) -> Crossing {
    let seed = scene.scene.render.seed;
    let normal = scene.scattering_normal(hit, p.ray.direction);
    let on = |goes_on: bool| if goes_on { Crossing::On } else { Crossing::Ended };
    match &scene.surfaces[hit.object] {
        Surface::Mirror => {
            let d = reflect(p.ray.direction, normal);
            p.ray = Ray { origin: offset_origin(hit.point, normal, d), direction: d };
            Crossing::On
        }
        Surface::Metal(metal) => {
            let metal = scene.metal_at(metal, hit);
            let ggx = metal.ggx;
            let (u1, u2) = match ggx {
                Some(_) => {
                    let [d1, d2] = dim::bounce(p.band, p.bounces);
                    (random_f32(seed, index, d1), random_f32(seed, index, d2))
                }
                None => (0.0, 0.0),
            };
            let lambda_nm = stored_wavelength(&scene.bands, p.band, p.lambda_nm);
            let u = random_f32(seed, index, dim::scatter(p.band, p.bounces));
            if let Some(b) = scatter_metal(p.ray.direction, hit.point, normal, ggx, u1, u2) {
                let reflects = b.unshadowed * metal.specular_reflectance(b.cos_facet, p.band, lambda_nm, &scene.bands);
                if u < reflects {
                    p.ray = b.ray;
                    return Crossing::On;
                }
                let passes = metal.layer_passes(b.cos_facet, p.band, lambda_nm, &scene.bands);
                if u < reflects + passes {
                    return Crossing::ToBase((u - reflects) / passes);
                }
            }
            stats.flux_absorbed += f64::from(p.flux);
            Crossing::Ended
        }
        Surface::Dielectric(glass) => {
            let u = random_f32(seed, index, dim::scatter(p.band, p.bounces));
            let face = scene.face(glass, hit, p.band, p.lambda_nm);
            let before = p.ray.direction;
            let crossed = match scene.facets(hit) {
                None => {
                    p.ray = scatter_dielectric(before, hit.point, normal, face, u);
                    p.ray.direction == before
                }
                Some(ggx) => {
                    let [d1, d2] = dim::bounce(p.band, p.bounces);
                    let facet = (random_f32(seed, index, d1), random_f32(seed, index, d2));
                    let bounce = scatter_rough_dielectric(before, (hit.point, normal), face, ggx, facet, u);
                    match bounce.filter(|b| b.leftover < b.unshadowed) {
                        Some(b) => {
                            p.ray = b.ray;
                            b.crossed
                        }
                        None => {
                            stats.flux_absorbed += f64::from(p.flux);
                            return Crossing::Ended;
                        }
                    }
                }
            };
            let absorbed =
                absorbed_crossing(glass, crossed, p.band, || random_f32(seed, index, dim::absorb(p.band, p.bounces)));
            if absorbed {
                stats.flux_absorbed += f64::from(p.flux);
            }
            on(!absorbed)
        }
        Surface::Diffuse { .. } => unreachable!("a diffuse surface is not crossed"),
    }
}

/// The wavelength a photon of `band` traced at `lambda_nm` (`None`: the
/// band's own) stores: the one it was traced at, 0 for white light.
#[inline]
pub fn stored_wavelength(bands: &BandTable, band: u16, lambda_nm: Option<f32>) -> f32 {
    match bands.bands().get(usize::from(band)) {
        Some(b) => lambda_nm.unwrap_or(b.lambda_nm),
        None => 0.0,
    }
}

/// Whether coloured `glass` absorbs the photon path of `band` on a segment
/// of length `t` along `dir` that ends on it (outward `normal` there). Only
/// a segment that ran inside (it meets the glass from within) can be
/// absorbed, with probability 1 − e^(−σt) against the uniform number `u`
/// ([`dim::absorb`]): Russian roulette, so survivors keep their flux and
/// both estimators (counts and flux) stay unbiased.
pub fn absorbed(glass: &DielectricOptics, dir: Vec3, normal: Vec3, t: f32, band: u16, u: impl FnOnce() -> f32) -> bool {
    let Some(absorption) = glass.absorption.as_ref().filter(|_| !glass.thin) else { return false };
    dir.dot(normal) > 0.0 && u() >= absorption.transmittance(band, t)
}

/// Whether a tinted thin sheet absorbs the photon path of `band` that
/// `crossed` it (a polished sheet's crossing leaves along the direction it
/// came): with probability 1 − its crossing's transmittance
/// ([`DielectricOptics::sheet_crossing`]) against the uniform number `u`
/// ([`dim::absorb`], unused at a sheet by [`absorbed`]), as Russian roulette.
pub fn absorbed_crossing(glass: &DielectricOptics, crossed: bool, band: u16, u: impl FnOnce() -> f32) -> bool {
    glass.thin && glass.absorption.is_some() && crossed && u() >= glass.sheet_crossing(band)
}
