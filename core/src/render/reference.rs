//! The scalar reference backend, single-threaded: the definition of right.
//! Its kernels are the core's view pass ([`crate::render::view`]), photon tracer
//! ([`crate::photons::trace`]), [`gather_pass`] and light tracing
//! ([`crate::photons::light_tracing`]), driven by [`HostRender`].

use crate::model::photon::PhotonMap;
use crate::photons::gather::{GatherQuery, gather_counted, gather_rough};
use crate::photons::grid::PhotonGrid;
use crate::plan::prepared::PreparedScene;
use crate::plan::schedule::{GRID_LEVELS, level_of, level_radius, levels_used};
use crate::render::host::{HostKernels, HostRender, PassGather};
use crate::render::protocol::{Backend, BackendError, Render};
use crate::render::visible::{VisiblePoint, VisiblePoints};
use crate::util::progress::{NoProgress, Progress};
use alloc::boxed::Box;
use alloc::vec::Vec;

/// The scalar reference: renders are [`HostRender`]s over [`ScalarKernels`].
#[derive(Clone, Copy, Debug, Default)]
pub struct ReferenceBackend;

impl Backend for ReferenceBackend {
    fn name(&self) -> &'static str {
        "reference"
    }

    fn prepare(&mut self, scene: &PreparedScene) -> Result<Box<dyn Render>, BackendError> {
        Ok(Box::new(HostRender::new(ScalarKernels, scene)))
    }
}

/// The reference's kernels: one ray, one photon, one point at a time.
#[derive(Clone, Copy, Debug, Default)]
pub struct ScalarKernels;

impl HostKernels for ScalarKernels {
    fn name(&self) -> &'static str {
        "reference"
    }

    fn visible_points(&mut self, scene: &PreparedScene, pass: u32, progress: &mut dyn Progress) -> VisiblePoints {
        crate::render::view::visible_points(scene, pass, progress)
    }

    fn trace(&mut self, scene: &PreparedScene, progress: &mut dyn Progress) -> PhotonMap {
        crate::photons::trace::trace_photons(scene, progress)
    }

    fn pass(&mut self, scene: &PreparedScene, points: &[VisiblePoint], radii: &[f32]) -> PassGather {
        let map = crate::photons::trace::trace_photons(scene, &mut NoProgress);
        let splats = crate::photons::light_tracing::splat_photons(scene, &map.photons);
        PassGather { splats, ..gather_pass(scene, &map, points, radii) }
    }
}

/// The scalar reference of a pass's gather: `map`'s photons at `points`,
/// each with its own radius (`radii`, at most the scene's radius, which is
/// the pass's), from grids of [`GRID_LEVELS`] cell sizes.
pub fn gather_pass(scene: &PreparedScene, map: &PhotonMap, points: &[VisiblePoint], radii: &[f32]) -> PassGather {
    let r_pass = scene.scene.render.radius;
    let used = levels_used(radii, r_pass);
    let grids: Vec<Option<PhotonGrid>> =
        (0..GRID_LEVELS).map(|l| used[l].then(|| PhotonGrid::build(&map.photons, level_radius(r_pass, l)))).collect();
    // The photons met on rough surfaces, at the levels where rough points gather.
    let rough_radii: Vec<f32> = points.iter().zip(radii).filter(|(p, _)| p.rough.is_some()).map(|(_, &r)| r).collect();
    let rough_used = levels_used(&rough_radii, r_pass);
    let rough_grids: Vec<Option<PhotonGrid>> = (0..GRID_LEVELS)
        .map(|l| rough_used[l].then(|| PhotonGrid::build_rough(&map.photons, level_radius(r_pass, l))))
        .collect();
    let settings = &scene.scene.render;
    let (irradiance, photons) = points
        .iter()
        .zip(radii)
        .map(|(p, &r)| {
            let level = level_of(r, r_pass);
            let q = GatherQuery { point: p.point, normal: p.normal, radius: r, albedo: p.albedo };
            match &p.rough {
                Some(at) => {
                    let grid = rough_grids[level].as_ref().expect("level built");
                    gather_rough(scene, (grid, &map.photons), &q, at)
                }
                None => {
                    let grid = grids[level].as_ref().expect("level built");
                    gather_counted(grid, &map.photons, &scene.bands, settings.estimator, &q)
                }
            }
        })
        .unzip();
    PassGather { irradiance, photons, splats: Vec::new(), stats: map.stats }
}
