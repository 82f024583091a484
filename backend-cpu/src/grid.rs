//! The hash grid of the CPU backend and its gather: the core's `PhotonGrid`
//! and `gather_counted`, with the photons copied into bucket order as structure-of-
//! arrays records, so that a query tests eight photons at a time against
//! the radius and the surface side.

use crate::simd::{Vec3x8, lt};
use glam::{IVec3, Vec3};
use prismatic_core::model::bands::BandTable;
use prismatic_core::model::photon::Photon;
use prismatic_core::model::scene::Estimator;
use prismatic_core::photons::gather::{GatherQuery, GatherSums, finish};
use prismatic_core::photons::grid::{bucket_mask, bucket_of, cell_of};
use rayon::prelude::*;
use std::sync::atomic::{AtomicU64, Ordering};
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
    lambda: Vec<f32>,
    band: Vec<u16>,
    /// Scratch: each photon's bucket (kept for the next rebuild).
    bucket: Vec<u32>,
    /// Scratch of `rebuild_near`: one bit a bucket, set where a query may
    /// look (empty: every bucket).
    near: Vec<u64>,
}

/// A build task sorts at least this many photons (fewer photons: one task).
const SORT_TASK: usize = 1 << 15;

/// One build task's share of the grid's arrays: the records of a range of
/// buckets, which a counting sort places next to each other.
struct RecordSlices<'a> {
    pos: [&'a mut [f32]; 3],
    dir: [&'a mut [f32]; 3],
    flux: &'a mut [f32],
    lambda: &'a mut [f32],
    band: &'a mut [u16],
}

impl CpuGrid {
    /// Builds the grid over all `photons`.
    pub fn build(photons: &[Photon], radius: f32) -> Self {
        let mut grid = Self::empty();
        grid.rebuild(photons, radius);
        grid
    }

    /// Builds the grid for gathers at `queries` only (see [`CpuGrid::rebuild_near`]).
    pub fn build_near(photons: &[Photon], radius: f32, queries: impl ParallelIterator<Item = (Vec3, f32)>) -> Self {
        let mut grid = Self::empty();
        grid.rebuild_near(photons, radius, queries);
        grid
    }

    fn empty() -> Self {
        CpuGrid {
            cell_size: 0.0,
            mask: 0,
            cell_start: Vec::new(),
            pos: Default::default(),
            dir: Default::default(),
            flux: Vec::new(),
            lambda: Vec::new(),
            band: Vec::new(),
            bucket: Vec::new(),
            near: Vec::new(),
        }
    }

    /// Rebuilds the grid over `photons` in the memory of the last build (a
    /// progressive render's passes allocate nothing after the first).
    pub fn rebuild(&mut self, photons: &[Photon], radius: f32) {
        self.near.clear();
        self.sort(photons, radius);
    }

    /// Rebuilds the grid over those of `photons` that gathers at `queries`
    /// (point, radius ≤ `radius`) can find: the photons in the buckets of
    /// the cells the queries' spheres touch. A gather anywhere else misses
    /// photons. Progressive passes sort only the photons near each grid
    /// level's own points (a dense caustic's few points skip the floor).
    pub fn rebuild_near(
        &mut self,
        photons: &[Photon],
        radius: f32,
        queries: impl ParallelIterator<Item = (Vec3, f32)>,
    ) {
        let mask = bucket_mask(photons.len());
        let inv = 1.0 / (2.0 * radius);
        let near: Vec<AtomicU64> = (0..(mask as usize + 1).div_ceil(64)).map(|_| AtomicU64::new(0)).collect();
        queries.for_each(|(p, r)| {
            let (lo, hi) = (cell_of(p - Vec3::splat(r), inv), cell_of(p + Vec3::splat(r), inv));
            for z in lo.z..=hi.z.min(lo.z.saturating_add(1)) {
                for y in lo.y..=hi.y.min(lo.y.saturating_add(1)) {
                    for x in lo.x..=hi.x.min(lo.x.saturating_add(1)) {
                        let b = bucket_of(IVec3::new(x, y, z), mask) as usize;
                        let (word, bit) = (&near[b / 64], 1 << (b % 64));
                        // Neighbouring queries mark the same buckets: read first.
                        if word.load(Ordering::Relaxed) & bit == 0 {
                            word.fetch_or(bit, Ordering::Relaxed);
                        }
                    }
                }
            }
        });
        self.near.clear();
        self.near.extend(near.into_iter().map(AtomicU64::into_inner));
        self.sort(photons, radius);
    }

    /// The counting sort of `photons` into buckets (those `near` allows),
    /// run as tasks over ranges of buckets: each task counts and places the
    /// photons of its buckets, scanning every photon in order, so the
    /// layout is the serial sort's whatever the thread count.
    fn sort(&mut self, photons: &[Photon], radius: f32) {
        let n = photons.len();
        self.cell_size = 2.0 * radius;
        let inv_cell = 1.0 / self.cell_size;
        self.mask = bucket_mask(n);
        let buckets = self.mask as usize + 1;
        let mask = self.mask;
        self.bucket.clear();
        let near = &self.near;
        self.bucket.par_extend(photons.par_iter().map(|p| {
            let b = bucket_of(cell_of(p.pos(), inv_cell), mask);
            // Buckets no query looks in, and photons met on rough surfaces
            // (no gather takes them): past the table, so never counted.
            let looked_in = near.is_empty() || near[b as usize / 64] & (1 << (b % 64)) != 0;
            if looked_in && !p.on_rough_surface() { b } else { u32::MAX }
        }));
        let tasks = rayon::current_num_threads().min(n / SORT_TASK).max(1);
        // Buckets split evenly (the hash spreads photons evenly over them).
        let first: Vec<usize> = (0..=tasks).map(|t| t * buckets / tasks).collect();
        let bucket = &self.bucket;

        // Count: task t fills start[first[t] + 1..=first[t + 1]] with its
        // buckets' counts, then the prefix sums join the tasks' ranges.
        self.cell_start.clear();
        self.cell_start.resize(buckets + 1, 0);
        let (_, counts) = self.cell_start.split_at_mut(1);
        let mut count_slices = split_at(counts, &first[1..]);
        count_slices.par_iter_mut().enumerate().for_each(|(t, count)| {
            let lo = first[t];
            for &b in bucket {
                if let Some(c) = (b as usize).checked_sub(lo).and_then(|i| count.get_mut(i)) {
                    *c += 1;
                }
            }
        });
        for i in 0..buckets {
            self.cell_start[i + 1] += self.cell_start[i];
        }

        // Scatter: task t writes the records of its buckets, one slice of
        // each array (the padding's 8 records go with the last task).
        let padded = self.cell_start[buckets] as usize + 8;
        for v in self.pos.iter_mut().chain(&mut self.dir).chain([&mut self.flux, &mut self.lambda]) {
            v.truncate(padded);
            v.resize(padded, 0.0);
        }
        self.band.truncate(padded);
        self.band.resize(padded, 0);
        let ends: Vec<usize> = first[1..].iter().map(|&b| self.cell_start[b] as usize).collect();
        let [px, py, pz] = &mut self.pos;
        let [dx, dy, dz] = &mut self.dir;
        let mut slices: Vec<RecordSlices> = split_at(px, &ends)
            .into_iter()
            .zip(split_at(py, &ends))
            .zip(split_at(pz, &ends))
            .zip(split_at(dx, &ends).into_iter().zip(split_at(dy, &ends)).zip(split_at(dz, &ends)))
            .zip(split_at(&mut self.flux, &ends).into_iter().zip(split_at(&mut self.band, &ends)))
            .zip(split_at(&mut self.lambda, &ends))
            .map(|(((((x, y), z), ((u, v), w)), (flux, band)), lambda)| RecordSlices {
                pos: [x, y, z],
                dir: [u, v, w],
                flux,
                lambda,
                band,
            })
            .collect();
        let cell_start = &self.cell_start;
        slices.par_iter_mut().enumerate().for_each(|(t, out)| {
            let (lo, hi) = (first[t], first[t + 1]);
            let base = cell_start[lo];
            let mut cursor: Vec<u32> = cell_start[lo..hi].iter().map(|&s| s - base).collect();
            for (p, &b) in photons.iter().zip(bucket) {
                let Some(slot) = (b as usize).checked_sub(lo).and_then(|i| cursor.get_mut(i)) else { continue };
                let i = *slot as usize;
                *slot += 1;
                let d = p.direction();
                for k in 0..3 {
                    out.pos[k][i] = p.position[k];
                    out.dir[k][i] = d[k];
                }
                out.flux[i] = p.flux;
                out.lambda[i] = p.lambda_nm;
                out.band[i] = p.band;
            }
        });
    }

    /// Number of photons in the grid.
    pub fn len(&self) -> usize {
        self.flux.len() - 8
    }

    /// True when the grid holds no photons.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Caustic irradiance at `q`, reflected by `q.albedo`, and how many
    /// photons it accepted (the core's `gather_counted`, same estimators).
    pub fn gather_counted(&self, bands: &BandTable, estimator: Estimator, q: &GatherQuery) -> (Vec3, u32) {
        let r2 = q.radius * q.radius;
        let inv = 1.0 / self.cell_size;
        let lo = cell_of(q.point - Vec3::splat(q.radius), inv);
        let hi = cell_of(q.point + Vec3::splat(q.radius), inv);
        let (qp, qn, r2x8) = (Vec3x8::splat(q.point), Vec3x8::splat(q.normal), f32x8::splat(r2));
        let lane_index = f32x8::new([0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0]);
        let mut seen = [0u32; 8];
        let mut n_seen = 0;
        let mut sums = GatherSums::default();
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
                        for lane in (0..8).filter(|l| accepted & (1 << l) != 0) {
                            let k = i + lane;
                            sums.add(estimator, bands, self.band[k], self.lambda[k], self.flux[k], q.albedo);
                        }
                        i += 8;
                    }
                }
            }
        }
        (finish(estimator, bands.len(), &sums, q.radius), sums.found)
    }
}

/// `v` cut at each of `ends` but the last (the last slice runs to the end of
/// `v`: for the records, their padding).
fn split_at<'a, T>(v: &'a mut [T], ends: &[usize]) -> Vec<&'a mut [T]> {
    let mut slices = Vec::with_capacity(ends.len());
    let (mut rest, mut done) = (v, 0);
    for &end in &ends[..ends.len() - 1] {
        let (head, tail) = rest.split_at_mut(end - done);
        slices.push(head);
        (rest, done) = (tail, end);
    }
    slices.push(rest);
    slices
}

#[cfg(test)]
mod tests {
    use super::*;
    use prismatic_core::model::photon::oct_pack;

    /// The parallel scatter lays the records out as a serial counting sort
    /// does, whatever the thread count (the gathers' sums depend on it).
    #[test]
    fn the_layout_does_not_depend_on_the_thread_count() {
        let mut state = 0x2545_f491_u32;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 17;
            state ^= state << 5;
            state as f32 / u32::MAX as f32
        };
        let photons: Vec<Photon> = (0..5 * SORT_TASK as u32)
            .map(|i| Photon {
                position: [next() * 2.0 - 1.0, 0.0, next() * 2.0 - 1.0],
                flux: next(),
                direction_oct: oct_pack(Vec3::new(next() - 0.5, -1.0, next() - 0.5).normalize()),
                lambda_nm: 380.0 + 400.0 * next(),
                emission: i,
                band: (i % 7) as u16,
                bounces: 1,
            })
            .collect();
        let build = |threads| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            pool.install(|| CpuGrid::build(&photons, 0.01))
        };
        let same = |a: &CpuGrid, b: &CpuGrid, what: &str| {
            assert_eq!((a.cell_size, a.mask), (b.cell_size, b.mask), "{what}");
            assert_eq!(a.cell_start, b.cell_start, "{what}");
            let n = a.len();
            assert_eq!(n, b.len(), "{what}");
            for k in 0..3 {
                assert_eq!(a.pos[k][..n], b.pos[k][..n], "{what}");
                assert_eq!(a.dir[k][..n], b.dir[k][..n], "{what}");
            }
            assert_eq!((&a.flux[..n], &a.band[..n]), (&b.flux[..n], &b.band[..n]), "{what}");
            assert_eq!(a.lambda[..n], b.lambda[..n], "{what}");
        };
        let one = build(1);
        for threads in [2, 3, 8] {
            same(&one, &build(threads), &format!("{threads} threads"));
        }
        // A rebuild over a larger grid of another radius is a fresh build.
        let mut reused = CpuGrid::build(&[photons.clone(), photons.clone()].concat(), 0.05);
        reused.rebuild(&photons, 0.01);
        same(&one, &reused, "rebuilt");

        // A grid near a few queries holds fewer photons and gathers there
        // exactly what the whole grid gathers.
        let bands = BandTable::new(prismatic_core::BandSpec::Paper7);
        let queries: Vec<(Vec3, f32)> =
            (0..40).map(|i| (Vec3::new(next() - 0.5, 0.0, next() - 0.5), 0.008 + 0.002 * (i % 2) as f32)).collect();
        let near = CpuGrid::build_near(&photons, 0.01, queries.par_iter().copied());
        assert!(near.len() < photons.len() / 4, "{} of {}", near.len(), photons.len());
        for estimator in [Estimator::Density, Estimator::Paper] {
            for &(point, radius) in &queries {
                let q = GatherQuery { point, normal: Vec3::Y, radius, albedo: Vec3::ONE };
                let whole = one.gather_counted(&bands, estimator, &q);
                assert!(whole.1 > 0, "a query with no photons tests nothing");
                assert_eq!(near.gather_counted(&bands, estimator, &q), whole);
            }
        }
    }
}
