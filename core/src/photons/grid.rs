//! The uniform spatial hash grid over stored photons, used by the gather.
//!
//! Cells are cubes of edge 2r (r = gather radius), so a gather sphere
//! touches at most 2 cells per axis (8 in all). Cells hash into a table of
//! 2^k buckets (k from the photon count); the grid is built by counting sort:
//! count photons per bucket, prefix-sum the counts, scatter photon indices.
//! Different cells may share a bucket, so a query visits each distinct
//! bucket once and tests the distance of every candidate.

use crate::model::photon::Photon;
use alloc::vec;
use alloc::vec::Vec;
use glam::{IVec3, Vec3};

/// Largest bucket table (2^24 buckets, 64 MiB of offsets).
pub const MAX_TABLE_BITS: u32 = 24;

/// Spatial hash grid over a photon slice.
#[derive(Clone, Debug, PartialEq)]
pub struct PhotonGrid {
    /// Edge of a cell (twice the gather radius).
    pub cell_size: f32,
    /// Bucket mask (table size − 1).
    pub mask: u32,
    /// `cell_start[b]..cell_start[b + 1]` indexes `photon_index` for bucket b.
    pub cell_start: Vec<u32>,
    /// Photon indices sorted by bucket (stable: canonical order within a bucket).
    pub photon_index: Vec<u32>,
}

/// The integer cell of `p` (float → int casts saturate, so far-away points
/// land in the outermost cells instead of wrapping).
#[inline]
pub fn cell_of(p: Vec3, inv_cell: f32) -> IVec3 {
    IVec3::new(
        crate::util::math::floor(p.x * inv_cell) as i32,
        crate::util::math::floor(p.y * inv_cell) as i32,
        crate::util::math::floor(p.z * inv_cell) as i32,
    )
}

/// The bucket of cell `c` (Teschner et al. 2003 primes, wrapping u32 arithmetic
/// so that the WGSL twin gives the same bucket).
#[inline]
pub fn bucket_of(c: IVec3, mask: u32) -> u32 {
    ((c.x as u32).wrapping_mul(73_856_093)
        ^ (c.y as u32).wrapping_mul(19_349_663)
        ^ (c.z as u32).wrapping_mul(83_492_791))
        & mask
}

/// The bucket mask for a grid over `photons` photons.
#[inline]
pub fn bucket_mask(photons: usize) -> u32 {
    (photons.next_power_of_two().clamp(1, 1 << MAX_TABLE_BITS) - 1) as u32
}

/// The counting sort's first half: `start[b]..start[b + 1]` is where bucket
/// b's photons go, given each photon's bucket.
pub fn bucket_starts(bucket: &[u32], mask: u32) -> Vec<u32> {
    let buckets = mask as usize + 1;
    let mut start = vec![0u32; buckets + 1];
    for &b in bucket {
        start[b as usize + 1] += 1;
    }
    for i in 0..buckets {
        start[i + 1] += start[i];
    }
    start
}

impl PhotonGrid {
    /// Builds the grid for `photons` and gather radius `radius` (without
    /// those met on rough surfaces, which only a rough surface's visible
    /// points take: [`Photon::on_rough_surface`], [`PhotonGrid::build_rough`]).
    pub fn build(photons: &[Photon], radius: f32) -> Self {
        Self::build_where(photons, radius, |p| !p.on_rough_surface())
    }

    /// The grid of `photons` met on rough surfaces alone, for the gathers
    /// of visible points there ([`crate::photons::gather::gather_rough`]).
    pub fn build_rough(photons: &[Photon], radius: f32) -> Self {
        Self::build_where(photons, radius, Photon::on_rough_surface)
    }

    fn build_where(photons: &[Photon], radius: f32, gathered: impl Fn(&Photon) -> bool) -> Self {
        let cell_size = 2.0 * radius;
        let inv_cell = 1.0 / cell_size;
        let mask = bucket_mask(photons.iter().filter(|p| gathered(p)).count());
        let bucket: Vec<u32> =
            photons.iter().filter(|p| gathered(p)).map(|p| bucket_of(cell_of(p.pos(), inv_cell), mask)).collect();
        let cell_start = bucket_starts(&bucket, mask);
        let mut cursor = cell_start.clone();
        let mut photon_index = vec![0u32; bucket.len()];
        let indices = (0u32..).zip(photons).filter(|(_, p)| gathered(p)).map(|(i, _)| i);
        for (i, &b) in indices.zip(&bucket) {
            photon_index[cursor[b as usize] as usize] = i;
            cursor[b as usize] += 1;
        }
        PhotonGrid { cell_size, mask, cell_start, photon_index }
    }

    /// The distinct buckets a sphere of radius `r` around `p` can touch
    /// (at most 8), written to `out`; returns how many.
    #[inline]
    pub fn buckets_near(&self, p: Vec3, r: f32, out: &mut [u32; 8]) -> usize {
        let inv = 1.0 / self.cell_size;
        let lo = cell_of(p - Vec3::splat(r), inv);
        let hi = cell_of(p + Vec3::splat(r), inv);
        let mut n = 0;
        // r ≤ cell/2 ⇒ hi − lo ≤ 1 per axis; clamp to keep that for larger r.
        for z in lo.z..=hi.z.min(lo.z.saturating_add(1)) {
            for y in lo.y..=hi.y.min(lo.y.saturating_add(1)) {
                for x in lo.x..=hi.x.min(lo.x.saturating_add(1)) {
                    let b = bucket_of(IVec3::new(x, y, z), self.mask);
                    if !out[..n].contains(&b) {
                        out[n] = b;
                        n += 1;
                    }
                }
            }
        }
        n
    }

    /// Calls `visit` with the index of every photon in the buckets a sphere of
    /// radius `r ≤ cell_size / 2` around `p` touches (a superset of the
    /// photons within `r`).
    #[inline]
    pub fn for_each_candidate(&self, p: Vec3, r: f32, mut visit: impl FnMut(u32)) {
        let mut buckets = [0u32; 8];
        let n = self.buckets_near(p, r, &mut buckets);
        for &b in &buckets[..n] {
            let (s, e) = (self.cell_start[b as usize], self.cell_start[b as usize + 1]);
            for &i in &self.photon_index[s as usize..e as usize] {
                visit(i);
            }
        }
    }
}
