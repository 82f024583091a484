//! The CPU backend's progressive pass: the core's `gather_pass` with
//! packet grids, scheduled over small chunks of visible points (not image
//! tiles), so the threads share a caustic that covers a few rows evenly.

use crate::grid::CpuGrid;
use prismatic_core::PhotonMap;
use prismatic_core::bands::MAX_BANDS;
use prismatic_core::gather::GatherQuery;
use prismatic_core::prepared::PreparedScene;
use prismatic_core::progressive::{GRID_LEVELS, PassGather, level_of, level_radius, levels_used};
use prismatic_core::visible::VisiblePoint;
use rayon::prelude::*;

/// Visible points per work item: a caustic's dense points spread over
/// many items, each small enough to balance two cores.
pub const POINT_CHUNK: usize = 256;

/// Gathers `map` at `points`, each within its radius (`radii`).
pub fn gather_pass(scene: &PreparedScene, map: &PhotonMap, points: &[VisiblePoint], radii: &[f32]) -> PassGather {
    let r_pass = scene.scene.render.radius;
    let used = levels_used(radii, r_pass);
    // The levels are built side by side: most of a build (the scatter) is serial.
    let grids: Vec<Option<CpuGrid>> = (0..GRID_LEVELS)
        .into_par_iter()
        .map(|l| used[l].then(|| CpuGrid::build(&map.photons, level_radius(r_pass, l))))
        .collect();
    let settings = &scene.scene.render;
    let chunks: Vec<Vec<_>> = points
        .par_chunks(POINT_CHUNK)
        .zip(radii.par_chunks(POINT_CHUNK))
        .map(|(points, radii)| {
            let mut counts = Box::new([0u32; MAX_BANDS + 1]);
            points
                .iter()
                .zip(radii)
                .map(|(p, &r)| {
                    let grid = grids[level_of(r, r_pass)].as_ref().expect("level built");
                    let q = GatherQuery { point: p.point, normal: p.normal, radius: r };
                    grid.gather_counted(&scene.bands, settings.estimator, &q, &mut counts)
                })
                .collect()
        })
        .collect();
    let (irradiance, photons) = chunks.into_iter().flatten().unzip();
    PassGather { irradiance, photons, stats: map.stats }
}
