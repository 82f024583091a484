//! What a session reads back, only when asked (each waits for the device):
//! the image without caustics, the pixels' exact sums, the statistics.

use super::GpuSession;
use super::points::SUM_BYTES;
use crate::layout::RunStats;
use crate::pixels::read_pixels;
use prismatic_core::model::scene::RadiusMode;
use prismatic_core::render::accumulation::count_passes;
use prismatic_core::{BackendError, Image, RenderStats, TraceStats};

impl GpuSession {
    /// The view pass's pixels: direct light, ambient and background.
    pub(super) fn read_base(&self) -> Result<Image, BackendError> {
        let r = &self.scene.scene.render;
        let mut image = Image::new(r.width, r.height);
        for chunk in &self.points.chunks {
            let pixels = &mut image.pixels[chunk.offset as usize..(chunk.offset + chunk.count) as usize];
            read_pixels(&self.ctx, &chunk.base, 0, pixels)?;
        }
        Ok(image)
    }

    /// Every pixel's sums, in pixel order.
    pub(super) fn read_sums(&self) -> Result<Vec<[i64; 3]>, BackendError> {
        let mut sums = Vec::new();
        for chunk in &self.points.chunks {
            let bytes = self.ctx.read(&chunk.sums, 0, chunk.count * SUM_BYTES)?;
            let words: Vec<[u32; 2]> = bytemuck::pod_collect_to_vec(&bytes);
            sums.extend(words.chunks_exact(3).map(|p| [0, 1, 2].map(|c| i64_from_words(p[c]))));
        }
        Ok(sums)
    }

    /// The statistics: the passes' trace tallies, the visible points and
    /// their first radii (the device's), the bytes moved (the context's).
    pub(super) fn read_stats(&self) -> Result<RenderStats, BackendError> {
        let (mut points, mut cut) = (0, 0);
        for chunk in &self.points.chunks {
            let counts: Vec<u32> = bytemuck::pod_collect_to_vec(&self.ctx.read(&chunk.total, 0, 8)?);
            points += u64::from(counts[0]).min(chunk.capacity);
            cut += u64::from(counts[1]);
        }
        let bytes = self.ctx.read(&self.run_stats, 0, size_of::<RunStats>() as u64)?;
        let s: RunStats = bytemuck::pod_read_unaligned(&bytes);
        let [emitted, paths, segments, specular_paths, stored] = s.counts.map(|w| i64_from_words(w) as u64);
        let [flux_emitted, flux_stored, flux_escaped, flux_direct, flux_depth_limited, flux_absorbed] =
            s.flux.map(f64::from);
        let trace = TraceStats {
            emitted,
            paths,
            segments,
            specular_paths,
            stored,
            flux_emitted,
            flux_stored,
            flux_escaped,
            flux_direct,
            flux_depth_limited,
            flux_absorbed,
        };
        let r0 = self.scene.scene.render.radius;
        let first_radii = match self.scene.scene.render.radius_mode {
            _ if points == 0 => None,
            RadiusMode::Fixed => Some((r0, r0)),
            RadiusMode::Progressive => Some((f32::from_bits(s.min_ratio) * r0, f32::from_bits(s.max_ratio) * r0)),
        };
        let (uploaded, read_back) = self.ctx.traffic();
        Ok(RenderStats {
            passes: count_passes(&self.passes),
            trace,
            visible_points: points,
            first_radii,
            view_paths_cut: cut,
            uploaded,
            read_back,
        })
    }
}

/// An i64 from its WGSL words `[lo, hi]` (fixed.wgsl).
fn i64_from_words([lo, hi]: [u32; 2]) -> i64 {
    ((u64::from(hi) << 32) | u64::from(lo)) as i64
}
