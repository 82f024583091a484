//! Gather estimators: caustic irradiance at a surface point from the photons within a radius.
//!
//! Both return irradiance in linear RGB (W/m² scaled by the band weights);
//! the renderer turns it into radiance with the diffuse BRDF (albedo/π) and
//! adds it to the ray-traced direct light.
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
//! Only photons arriving at the front of the surface (`dot(dir, n) < 0` for
//! the normal facing the viewer) count, so light does not bleed through thin walls.

use crate::bands::{BandTable, MAX_BANDS};
use crate::grid::PhotonGrid;
use crate::photon::{Photon, WHITE_BAND};
use crate::scene::Estimator;
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
}

/// Caustic irradiance (linear RGB) at `q` from the photons of `grid`.
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
    let area = PI * f64::from(r2);
    let mut accepted = 0u32;
    let irradiance = match estimator {
        Estimator::Density => {
            let mut sum = DVec3::ZERO;
            grid.for_each_candidate(q.point, q.radius, |i| {
                let p = &photons[i as usize];
                if accepts(p, q, r2) {
                    sum += bands.rgb_of_flux(p.band, p.flux).as_dvec3();
                    accepted += 1;
                }
            });
            (sum / area).as_vec3()
        }
        Estimator::Paper => {
            // counts[i] = T_i for band i; counts[MAX_BANDS] = white photons.
            let mut counts = [0u32; MAX_BANDS + 1];
            let mut flux = 0.0f64;
            grid.for_each_candidate(q.point, q.radius, |i| {
                let p = &photons[i as usize];
                if accepts(p, q, r2) {
                    let slot = if p.band == WHITE_BAND { MAX_BANDS } else { usize::from(p.band) };
                    counts[slot] += 1;
                    flux += f64::from(p.flux);
                    accepted += 1;
                }
            });
            paper_hue(bands, &counts).as_vec3() * (flux / area) as f32
        }
    };
    (irradiance, accepted)
}

/// The paper's hue N·W/Total from integer band counts (`counts[MAX_BANDS]`
/// holds white photons); black when nothing was gathered.
pub fn paper_hue(bands: &BandTable, counts: &[u32; MAX_BANDS + 1]) -> DVec3 {
    let n = bands.len();
    let white = u64::from(counts[MAX_BANDS]);
    let total: u64 = counts[..n].iter().map(|&c| u64::from(c)).sum::<u64>() + white * n as u64;
    if total == 0 {
        return DVec3::ZERO;
    }
    let mut w = DVec3::splat(white as f64);
    for (band, &t) in bands.bands().iter().zip(&counts[..n]) {
        w += band.weight.as_dvec3() * f64::from(t);
    }
    w * (n as f64 / total as f64)
}

#[inline]
fn accepts(p: &Photon, q: &GatherQuery, r2: f32) -> bool {
    (p.pos() - q.point).length_squared() <= r2 && p.direction().dot(q.normal) < 0.0
}
