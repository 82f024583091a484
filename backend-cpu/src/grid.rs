//! The hash grid of the CPU backend and its gather: the core's `PhotonGrid`
//! and `gather`, with the photons copied into bucket order as structure-of-
//! arrays records, so that a query tests eight photons at a time against
//! the radius and the surface side.

use crate::simd::{Vec3x8, lt};
use glam::{DVec3, IVec3, Vec3};
use prismatic_core::bands::{BandTable, MAX_BANDS};
use prismatic_core::gather::{GatherQuery, paper_hue};
use prismatic_core::grid::{bucket_mask, bucket_of, bucket_starts, cell_of};
use prismatic_core::photon::{Photon, WHITE_BAND};
use prismatic_core::scene::Estimator;
use rayon::prelude::*;
use wide::f32x8;

/// Photons sorted into hash buckets (counting sort), as structure of arrays.
/// Each array has 8 entries of padding so that a cell's last packet can be
/// loaded whole (the padding lanes are masked off).
pub struct CpuGrid {
    cell_size: f32,
    mask: u32,
    cell_start: Vec<u32>,
    pos: [Vec<f32>; 3],
    dir: [Vec<f32>; 3],
    flux: Vec<f32>,
    band: Vec<u16>,
}

impl CpuGrid {
    /// Builds the grid: buckets in parallel, then count, prefix sum, scatter.
    pub fn build(photons: &[Photon], radius: f32) -> Self {
        let cell_size = 2.0 * radius;
        let inv_cell = 1.0 / cell_size;
        let mask = bucket_mask(photons.len());
        let bucket: Vec<u32> = photons.par_iter().map(|p| bucket_of(cell_of(p.pos(), inv_cell), mask)).collect();
        let cell_start = bucket_starts(&bucket, mask);
        let padded = photons.len() + 8;
        let mut grid = CpuGrid {
            cell_size,
            mask,
            pos: core::array::from_fn(|_| vec![0.0; padded]),
            dir: core::array::from_fn(|_| vec![0.0; padded]),
            flux: vec![0.0; padded],
            band: vec![0; padded],
            cell_start,
        };
        let mut cursor = grid.cell_start.clone();
        for (p, &b) in photons.iter().zip(&bucket) {
            let slot = &mut cursor[b as usize];
            let i = *slot as usize;
            *slot += 1;
            let d = p.direction();
            for k in 0..3 {
                grid.pos[k][i] = p.position[k];
                grid.dir[k][i] = d[k];
            }
            grid.flux[i] = p.flux;
            grid.band[i] = p.band;
        }
        grid
    }

    /// Number of photons in the grid.
    pub fn len(&self) -> usize {
        self.flux.len() - 8
    }

    /// True when the grid holds no photons.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
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
        self.gather_counted(bands, estimator, q, counts).0
    }

    /// [`CpuGrid::gather`], and how many photons it accepted (the core's `gather_counted`).
    pub fn gather_counted(
        &self,
        bands: &BandTable,
        estimator: Estimator,
        q: &GatherQuery,
        counts: &mut [u32; MAX_BANDS + 1],
    ) -> (Vec3, u32) {
        let r2 = q.radius * q.radius;
        let area = std::f64::consts::PI * f64::from(r2);
        let inv = 1.0 / self.cell_size;
        let lo = cell_of(q.point - Vec3::splat(q.radius), inv);
        let hi = cell_of(q.point + Vec3::splat(q.radius), inv);
        let (qp, qn, r2x8) = (Vec3x8::splat(q.point), Vec3x8::splat(q.normal), f32x8::splat(r2));
        let lane_index = f32x8::new([0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0]);
        let mut seen = [0u32; 8];
        let mut n_seen = 0;
        let mut density = DVec3::ZERO;
        let mut flux = 0.0f64;
        let mut found = 0u32;
        for z in lo.z..=hi.z.min(lo.z.saturating_add(1)) {
            for y in lo.y..=hi.y.min(lo.y.saturating_add(1)) {
                for x in lo.x..=hi.x.min(lo.x.saturating_add(1)) {
                    let b = bucket_of(IVec3::new(x, y, z), self.mask);
                    if seen[..n_seen].contains(&b) {
                        continue;
                    }
                    seen[n_seen] = b;
                    n_seen += 1;
                    let (start, end) = (self.cell_start[b as usize] as usize, self.cell_start[b as usize + 1] as usize);
                    let mut i = start;
                    while i < end {
                        let load = |v: &[f32]| f32x8::new(v[i..i + 8].try_into().expect("padded"));
                        let p = Vec3x8 { x: load(&self.pos[0]), y: load(&self.pos[1]), z: load(&self.pos[2]) };
                        let d = Vec3x8 { x: load(&self.dir[0]), y: load(&self.dir[1]), z: load(&self.dir[2]) };
                        // Same tests as the core: |p − q|² ≤ r² and dir · n < 0.
                        let inside = !(p - qp).length_squared().simd_gt(r2x8);
                        let front = lt(d.dot(qn), f32x8::ZERO);
                        let real = lt(lane_index, f32x8::splat((end - i) as f32));
                        let accepted = (inside & front & real).to_bitmask();
                        found += accepted.count_ones();
                        for lane in (0..8).filter(|l| accepted & (1 << l) != 0) {
                            let (band, f) = (self.band[i + lane], self.flux[i + lane]);
                            match estimator {
                                Estimator::Density => density += bands.rgb_of_flux(band, f).as_dvec3(),
                                Estimator::Paper => {
                                    counts[if band == WHITE_BAND { MAX_BANDS } else { usize::from(band) }] += 1;
                                    flux += f64::from(f);
                                }
                            }
                        }
                        i += 8;
                    }
                }
            }
        }
        let irradiance = match estimator {
            Estimator::Density => (density / area).as_vec3(),
            Estimator::Paper => {
                let hue = paper_hue(bands, counts);
                counts[..bands.len()].fill(0);
                counts[MAX_BANDS] = 0;
                hue.as_vec3() * (flux / area) as f32
            }
        };
        (irradiance, found)
    }
}
