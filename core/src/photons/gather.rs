//! Gather estimators: caustic irradiance at a surface point from the photons within a radius.
//!
//! Both return reflected irradiance in linear RGB (W/m² scaled by the band
//! weights, each photon times what the surface reflects of it,
//! [`BandTable::reflectance`]: its reflectance spectrum at the photon's
//! wavelength, or its RGB albedo); the renderer turns it into radiance with
//! the diffuse BRDF's 1/π and adds it to the ray-traced direct light.
//!
//! - `paper` (Gwak & Ryou): with T_i the number of band-i photons in the
//!   disc and Total = Σ T_i, the hue is W/Total with W = Σ C_i T_i. A white
//!   (unsplit) photon counts once in every band. Because the weights of N
//!   bands sum to white, W/Total of balanced white light is (1,1,1)/N; we
//!   scale the hue by N so that white is (1,1,1), and take the strength from
//!   the photon flux density Σ Φ / (π r²). Counts are integers.
//! - `density`: Σ N·C_i·Φ / (π r²) over the photons (each band photon
//!   carries 1/N of the white flux, see [`BandTable::rgb_of_flux`]).
//!
//! A photon traced at its own wavelength takes its colour from it instead
//! of from C_i when the table says so ([`BandTable::colour_by_wavelength`]).
//!
//! A gather is two steps, each with a twin in every backend: the photons
//! found add to a point's [`GatherSums`] ([`GatherSums::add`]), and
//! [`finish`] turns the sums into irradiance (WGSL `finish_estimate`).
//!
//! Only photons arriving at the front of the surface (`dot(dir, n) < 0` for
//! the normal facing the viewer) count, so light does not bleed through thin walls.
//!
//! A visible point on rough metal or glass takes the photons met on rough
//! surfaces instead, from either side, each weighed by π times the
//! surface's BSDF toward the viewer ([`gather_rough`]).

use crate::model::bands::BandTable;
use crate::model::photon::{Photon, WHITE_BAND};
use crate::model::scene::Estimator;
use crate::photons::grid::PhotonGrid;
use crate::photons::reflects::RoughSurface;
use crate::plan::prepared::{Hit, PreparedScene};
use core::f64::consts::PI;
use glam::{DVec3, Vec3};

/// A gather query: where, which side, how far.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GatherQuery {
    /// Surface point.
    pub point: Vec3,
    /// Unit normal facing the viewer.
    pub normal: Vec3,
    /// Gather radius.
    pub radius: f32,
    /// The surface's RGB albedo (`Vec3::ONE` for the irradiance itself).
    pub albedo: Vec3,
}

/// What a gather adds up at a point, in f64 and integers (neither stalls
/// at 2^24 photons).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct GatherSums {
    /// `density`: Σ N·C_i·Φ; `paper`: W = Σ C_i T_i (a white photon adds
    /// (1, 1, 1)); by wavelength, the colour of λ for N·C_i.
    pub sums: DVec3,
    /// `paper`: Total = Σ T_i, a white photon counting N.
    pub total: u64,
    /// Σ Φ of the photons found.
    pub flux: f64,
    /// Photons found (a white photon counts once).
    pub found: u32,
}

impl GatherSums {
    /// Adds a photon of `band` at `lambda_nm` carrying `flux` that the
    /// gather accepted, reflected by a surface of RGB albedo `albedo`.
    #[inline]
    pub fn add(&mut self, estimator: Estimator, bands: &BandTable, band: u16, lambda_nm: f32, flux: f32, albedo: Vec3) {
        self.add_reflected(estimator, bands, (band, lambda_nm, flux), bands.reflectance(albedo, band, lambda_nm));
    }

    /// Adds a photon of `band` at `lambda_nm` carrying `flux` that the
    /// gather accepted, of which the surface sends `reflected` on (per RGB
    /// channel).
    #[inline]
    pub fn add_reflected(
        &mut self,
        estimator: Estimator,
        bands: &BandTable,
        (band, lambda_nm, flux): (u16, f32, f32),
        reflected: Vec3,
    ) {
        self.found += 1;
        self.flux += f64::from(flux);
        match estimator {
            Estimator::Density => self.sums += (bands.rgb_of_flux(band, lambda_nm, flux) * reflected).as_dvec3(),
            Estimator::Paper if band == WHITE_BAND => {
                self.sums += reflected.as_dvec3();
                self.total += bands.len() as u64;
            }
            Estimator::Paper => {
                self.sums += (bands.hue(band, lambda_nm) * reflected).as_dvec3();
                self.total += 1;
            }
        }
    }
}

/// The estimator's last step: caustic irradiance from the sums of a
/// gather within `radius`, with `bands` bands. Black when nothing was found.
pub fn finish(estimator: Estimator, bands: usize, g: &GatherSums, radius: f32) -> Vec3 {
    let area = PI * f64::from(radius) * f64::from(radius);
    match estimator {
        Estimator::Density => (g.sums / area).as_vec3(),
        Estimator::Paper if g.total == 0 => Vec3::ZERO,
        Estimator::Paper => (g.sums * (bands as f64 / g.total as f64)).as_vec3() * (g.flux / area) as f32,
    }
}

/// Caustic irradiance (linear RGB) at `q` from the photons of `grid`, reflected by `q.albedo`.
pub fn gather(grid: &PhotonGrid, photons: &[Photon], bands: &BandTable, estimator: Estimator, q: &GatherQuery) -> Vec3 {
    gather_counted(grid, photons, bands, estimator, q).0
}

/// [`gather`], and how many photons it accepted.
pub fn gather_counted(
    grid: &PhotonGrid,
    photons: &[Photon],
    bands: &BandTable,
    estimator: Estimator,
    q: &GatherQuery,
) -> (Vec3, u32) {
    let r2 = q.radius * q.radius;
    let mut sums = GatherSums::default();
    grid.for_each_candidate(q.point, q.radius, |i| {
        let p = &photons[i as usize];
        if accepts(p, q, r2) {
            sums.add(estimator, bands, p.band, p.lambda_nm, p.flux, q.albedo);
        }
    });
    (finish(estimator, bands.len(), &sums, q.radius), sums.found)
}

/// Where a visible point on rough metal or glass is, for the BSDF its
/// gather weighs each photon by ([`RoughSurface::reflects`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoughPoint {
    /// The object.
    pub object: usize,
    /// Its mesh triangle (see [`crate::geometry::primitive::SurfaceHit::triangle`]).
    pub triangle: u32,
    /// The shading normal there, on either side.
    pub shading: Vec3,
    /// The direction of the view ray that met it.
    pub toward: Vec3,
}

/// Light reflected or passed toward the viewer (linear RGB, times π: the
/// diffuse gather's unit, see [`gather`]) at `q` on the rough surface `at`
/// ([`crate::optics::microfacet::Ggx::gathers`]), from the photons of
/// `grid` met on rough surfaces ([`Photon::on_rough_surface`]; the others
/// are a diffuse surface's), each weighed by π times the BSDF from its
/// direction toward the viewer, on either side ([`RoughSurface::reflects`]):
/// L = Σ f Φ / (π r²). And how many photons it accepted.
pub fn gather_rough(
    scene: &PreparedScene,
    (grid, photons): (&PhotonGrid, &[Photon]),
    q: &GatherQuery,
    at: &RoughPoint,
) -> (Vec3, u32) {
    let r2 = q.radius * q.radius;
    let bent = Hit { t: 0.0, point: q.point, normal: at.shading, object: at.object, triangle: at.triangle };
    let estimator = scene.scene.render.estimator;
    // The surface's maps read once for the point, not per photon.
    let surface = RoughSurface::at(scene, &bent);
    let mut sums = GatherSums::default();
    grid.for_each_candidate(q.point, q.radius, |i| {
        let p = &photons[i as usize];
        if p.on_rough_surface() && (p.pos() - q.point).length_squared() <= r2 {
            let reflected = surface.as_ref().map_or(Vec3::ZERO, |s| s.reflects(scene, p, at.toward, &bent));
            sums.add_reflected(estimator, &scene.bands, (p.band, p.lambda_nm, p.flux), reflected);
        }
    });
    (finish(estimator, scene.bands.len(), &sums, q.radius), sums.found)
}

#[inline]
fn accepts(p: &Photon, q: &GatherQuery, r2: f32) -> bool {
    (p.pos() - q.point).length_squared() <= r2 && p.direction().dot(q.normal) < 0.0
}
