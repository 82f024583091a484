//! The CPU backend's gather of a pass: the reference's `gather_pass` with
//! packet grids, rebuilt in place from pass to pass, scheduled over small
//! chunks of visible points (not image tiles), so the threads share a
//! caustic that covers a few rows evenly.

use crate::grid::CpuGrid;
use glam::Vec3;
use prismatic_core::PhotonMap;
use prismatic_core::photons::gather::GatherQuery;
use prismatic_core::plan::prepared::PreparedScene;
use prismatic_core::plan::schedule::{GRID_LEVELS, level_of, level_radius};
use prismatic_core::render::visible::VisiblePoint;
use rayon::prelude::*;

/// Visible points per work item: a caustic's dense points spread over
/// many items, each small enough to balance two cores.
pub const POINT_CHUNK: usize = 256;

/// The grid levels of a pass, kept from pass to pass for their memory,
/// and each visible point's level.
#[derive(Default)]
pub struct PassGrids {
    levels: [Option<CpuGrid>; GRID_LEVELS],
    /// Each point's grid level in the last build.
    point_levels: Vec<u8>,
}

impl PassGrids {
    /// Builds the grid levels that gathers at `points` within `radii` (at
    /// most the pass radius, `scene`'s) need over `map`, each level holding
    /// only the photons near its own points.
    pub fn rebuild(&mut self, scene: &PreparedScene, map: &PhotonMap, points: &[VisiblePoint], radii: &[f32]) {
        let r_pass = scene.scene.render.radius;
        self.point_levels.clear();
        self.point_levels.par_extend(radii.par_iter().map(|&r| level_of(r, r_pass) as u8));
        let mut used = [false; GRID_LEVELS];
        self.point_levels.iter().for_each(|&l| used[usize::from(l)] = true);
        let levels = &self.point_levels;
        for l in (0..GRID_LEVELS).filter(|&l| used[l]) {
            let radius = level_radius(r_pass, l);
            let queries = (points, radii, levels)
                .into_par_iter()
                .filter(|&(_, _, &level)| usize::from(level) == l)
                .map(|(p, &r, _)| (p.point, r));
            match &mut self.levels[l] {
                Some(grid) => grid.rebuild_near(&map.photons, radius, queries),
                empty => *empty = Some(CpuGrid::build_near(&map.photons, radius, queries)),
            }
        }
    }

    /// Gathers the last build's photons at `points` (those it was built
    /// for), each within its radius: per point the caustic irradiance and
    /// the photons accepted.
    pub fn gather(&self, scene: &PreparedScene, points: &[VisiblePoint], radii: &[f32]) -> (Vec<Vec3>, Vec<u32>) {
        let settings = &scene.scene.render;
        let grids = &self.levels;
        let chunks: Vec<Vec<_>> =
            (points.par_chunks(POINT_CHUNK), radii.par_chunks(POINT_CHUNK), self.point_levels.par_chunks(POINT_CHUNK))
                .into_par_iter()
                .map(|(points, radii, levels)| {
                    points
                        .iter()
                        .zip(radii)
                        .zip(levels)
                        .map(|((p, &r), &level)| {
                            let grid = grids[usize::from(level)].as_ref().expect("level built");
                            let q = GatherQuery { point: p.point, normal: p.normal, radius: r, albedo: p.albedo };
                            grid.gather_counted(&scene.bands, settings.estimator, &q)
                        })
                        .collect()
                })
                .collect();
        chunks.into_iter().flatten().unzip()
    }
}
