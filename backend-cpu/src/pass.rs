//! The CPU backend's gather of a pass: the reference's `gather_pass` with
//! packet grids, rebuilt in place from pass to pass, scheduled over small
//! chunks of visible points (not image tiles), so the threads share a
//! caustic that covers a few rows evenly.

use crate::grid::CpuGrid;
use glam::Vec3;
use prismatic_core::PhotonMap;
use prismatic_core::photons::gather::{GatherQuery, gather_rough};
use prismatic_core::photons::grid::PhotonGrid;
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
    /// The core's grids of the photons met on rough surfaces, at the
    /// levels of the points there (the reference's, built whole on one
    /// thread each pass; the gathers there run in parallel).
    rough: [Option<PhotonGrid>; GRID_LEVELS],
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
        let mut rough = [false; GRID_LEVELS];
        points.iter().zip(levels).filter(|(p, _)| p.rough.is_some()).for_each(|(_, &l)| rough[usize::from(l)] = true);
        for (l, (grid, &needed)) in self.rough.iter_mut().zip(&rough).enumerate() {
            *grid = needed.then(|| PhotonGrid::build_rough(&map.photons, level_radius(r_pass, l)));
        }
        for l in (0..GRID_LEVELS).filter(|&l| used[l]) {
            let radius = level_radius(r_pass, l);
            let queries = (points, radii, levels)
                .into_par_iter()
                .filter(|&(p, _, &level)| usize::from(level) == l && p.rough.is_none())
                .map(|(p, &r, _)| (p.point, r));
            match &mut self.levels[l] {
                Some(grid) => grid.rebuild_near(&map.photons, radius, queries),
                empty => *empty = Some(CpuGrid::build_near(&map.photons, radius, queries)),
            }
        }
    }

    /// Gathers the last build's photons (`map`'s) at `points` (those it
    /// was built for), each within its radius: per point the caustic
    /// irradiance (a rough point's: π times its radiance,
    /// `gather_rough`) and the photons accepted.
    pub fn gather(
        &self,
        scene: &PreparedScene,
        map: &PhotonMap,
        points: &[VisiblePoint],
        radii: &[f32],
    ) -> (Vec<Vec3>, Vec<u32>) {
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
                            let q = GatherQuery { point: p.point, normal: p.normal, radius: r, albedo: p.albedo };
                            if let Some(at) = &p.rough {
                                let grid = self.rough[usize::from(level)].as_ref().expect("level built");
                                return gather_rough(scene, (grid, &map.photons), &q, at);
                            }
                            let grid = grids[usize::from(level)].as_ref().expect("level built");
                            grid.gather_counted(&scene.bands, settings.estimator, &q)
                        })
                        .collect()
                })
                .collect();
        chunks.into_iter().flatten().unzip()
    }
}
