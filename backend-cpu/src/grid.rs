//! The hash grid of the CPU backend and its gather: the core's `PhotonGrid`
//! and `gather`, with the photons copied into bucket order as compact
//! gather records (position, flux, direction, band) so that a query reads
//! memory front to back.

use glam::{DVec3, Vec3};
use prismatic_core::bands::{BandTable, MAX_BANDS};
use prismatic_core::gather::{GatherQuery, paper_hue};
use prismatic_core::grid::{MAX_TABLE_BITS, bucket_of, cell_of};
use prismatic_core::photon::{Photon, WHITE_BAND};
use prismatic_core::scene::Estimator;
use rayon::prelude::*;

/// One photon as the gather reads it.
#[derive(Clone, Copy, Debug, Default)]
pub struct GatherRecord {
    /// Position.
    pub pos: Vec3,
    /// Flux.
    pub flux: f32,
    /// Unit direction of travel.
    pub dir: Vec3,
    /// Band, or `WHITE_BAND`.
    pub band: u16,
}

/// Photons sorted into hash buckets (counting sort).
pub struct CpuGrid {
    cell_size: f32,
    mask: u32,
    cell_start: Vec<u32>,
    records: Vec<GatherRecord>,
}

impl CpuGrid {
    /// Builds the grid: buckets in parallel, then count, prefix sum, scatter.
    pub fn build(photons: &[Photon], radius: f32) -> Self {
        let cell_size = 2.0 * radius;
        let inv_cell = 1.0 / cell_size;
        let buckets = photons.len().next_power_of_two().clamp(1, 1 << MAX_TABLE_BITS);
        let mask = (buckets - 1) as u32;
        let bucket: Vec<u32> = photons.par_iter().map(|p| bucket_of(cell_of(p.pos(), inv_cell), mask)).collect();
        let mut cell_start = vec![0u32; buckets + 1];
        for &b in &bucket {
            cell_start[b as usize + 1] += 1;
        }
        for i in 0..buckets {
            cell_start[i + 1] += cell_start[i];
        }
        let mut cursor = cell_start.clone();
        let mut records = vec![GatherRecord::default(); photons.len()];
        for (p, &b) in photons.iter().zip(&bucket) {
            let slot = &mut cursor[b as usize];
            records[*slot as usize] = GatherRecord { pos: p.pos(), flux: p.flux, dir: p.direction(), band: p.band };
            *slot += 1;
        }
        CpuGrid { cell_size, mask, cell_start, records }
    }

    /// Number of photons in the grid.
    pub fn len(&self) -> usize {
        self.records.len()
    }

    /// True when the grid holds no photons.
    pub fn is_empty(&self) -> bool {
        self.records.is_empty()
    }

    /// Caustic irradiance at `q` (the core's `gather`, same estimators).
    /// `counts` is scratch space of `MAX_BANDS + 1` integers, left zeroed.
    pub fn gather(
        &self,
        bands: &BandTable,
        estimator: Estimator,
        q: &GatherQuery,
        counts: &mut [u32; MAX_BANDS + 1],
    ) -> Vec3 {
        let r2 = q.radius * q.radius;
        let area = std::f64::consts::PI * f64::from(r2);
        let inv = 1.0 / self.cell_size;
        let lo = cell_of(q.point - Vec3::splat(q.radius), inv);
        let hi = cell_of(q.point + Vec3::splat(q.radius), inv);
        let mut seen = [0u32; 8];
        let mut n_seen = 0;
        let mut density = DVec3::ZERO;
        let mut flux = 0.0f64;
        for z in lo.z..=hi.z.min(lo.z.saturating_add(1)) {
            for y in lo.y..=hi.y.min(lo.y.saturating_add(1)) {
                for x in lo.x..=hi.x.min(lo.x.saturating_add(1)) {
                    let b = bucket_of(glam::IVec3::new(x, y, z), self.mask);
                    if seen[..n_seen].contains(&b) {
                        continue;
                    }
                    seen[n_seen] = b;
                    n_seen += 1;
                    let cell =
                        &self.records[self.cell_start[b as usize] as usize..self.cell_start[b as usize + 1] as usize];
                    for r in cell {
                        if (r.pos - q.point).length_squared() > r2 || r.dir.dot(q.normal) >= 0.0 {
                            continue;
                        }
                        match estimator {
                            Estimator::Density => density += bands.rgb_of_flux(r.band, r.flux).as_dvec3(),
                            Estimator::Paper => {
                                let slot = if r.band == WHITE_BAND { MAX_BANDS } else { usize::from(r.band) };
                                counts[slot] += 1;
                                flux += f64::from(r.flux);
                            }
                        }
                    }
                }
            }
        }
        match estimator {
            Estimator::Density => (density / area).as_vec3(),
            Estimator::Paper => {
                let hue = paper_hue(bands, counts);
                counts[..bands.len()].fill(0);
                counts[MAX_BANDS] = 0;
                hue.as_vec3() * (flux / area) as f32
            }
        }
    }
}
