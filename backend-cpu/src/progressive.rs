//! The CPU backend's progressive pass: the core's `gather_pass` with
//! packet grids, rebuilt in place from pass to pass, scheduled over small
//! chunks of visible points (not image tiles), so the threads share a
//! caustic that covers a few rows evenly.

use crate::grid::CpuGrid;
use prismatic_core::PhotonMap;
use prismatic_core::bands::MAX_BANDS;
use prismatic_core::gather::GatherQuery;
use prismatic_core::prepared::PreparedScene;
use prismatic_core::progressive::{GRID_LEVELS, PassGather, level_of, level_radius};
use prismatic_core::visible::VisiblePoint;
use rayon::prelude::*;

/// Visible points per work item: a caustic's dense points spread over
/// many items, each small enough to balance two cores.
pub const POINT_CHUNK: usize = 256;

/// The grid levels of a pass, kept from pass to pass for their memory.
#[derive(Default)]
pub struct PassGrids {
    levels: [Option<CpuGrid>; GRID_LEVELS],
}

/// Gathers `map` at `points`, each within its radius (`radii`), building
/// the grid levels it needs in `grids`.
pub fn gather_pass(
    scene: &PreparedScene,
    map: &PhotonMap,
    points: &[VisiblePoint],
    radii: &[f32],
    grids: &mut PassGrids,
) -> PassGather {
    let r_pass = scene.scene.render.radius;
    let levels: Vec<u8> = radii.par_iter().map(|&r| level_of(r, r_pass) as u8).collect();
    let mut used = [false; GRID_LEVELS];
    levels.iter().for_each(|&l| used[usize::from(l)] = true);
    // Each level holds only the photons near its own points.
    for l in (0..GRID_LEVELS).filter(|&l| used[l]) {
        let radius = level_radius(r_pass, l);
        let queries = (points, radii, &levels)
            .into_par_iter()
            .filter(|&(_, _, &level)| usize::from(level) == l)
            .map(|(p, &r, _)| (p.point, r));
        match &mut grids.levels[l] {
            Some(grid) => grid.rebuild_near(&map.photons, radius, queries),
            empty => *empty = Some(CpuGrid::build_near(&map.photons, radius, queries)),
        }
    }
    let grids = &grids.levels;
    let settings = &scene.scene.render;
    let chunks: Vec<Vec<_>> =
        (points.par_chunks(POINT_CHUNK), radii.par_chunks(POINT_CHUNK), levels.par_chunks(POINT_CHUNK))
            .into_par_iter()
            .map(|(points, radii, levels)| {
                let mut counts = Box::new([0u32; MAX_BANDS + 1]);
                points
                    .iter()
                    .zip(radii)
                    .zip(levels)
                    .map(|((p, &r), &level)| {
                        let grid = grids[usize::from(level)].as_ref().expect("level built");
                        let q = GatherQuery { point: p.point, normal: p.normal, radius: r };
                        grid.gather_counted(&scene.bands, settings.estimator, &q, &mut counts)
                    })
                    .collect()
            })
            .collect();
    let (irradiance, photons) = chunks.into_iter().flatten().unzip();
    PassGather { irradiance, photons, stats: map.stats }
}
