//! A session's photon passes on the device, on the core's schedule
//! (`prismatic_core::plan::schedule`): the pilot pass that gives each visible
//! point its first radius (progressive radii only), and pass `k`: its
//! photons traced and gridded at every built level, gathered at the points
//! level by level (each level's gather dispatched over its own points, in
//! bucket segments on a software device), its photons light traced into
//! the pixels' sums (when the scene asks), added to the pixels' exact sums,
//! and its trace tallies added to the statistics.

use super::GpuSession;
use super::points::ChunkGroups;
use super::points::{LEVEL_ARGS_BYTES, LEVEL_HEADER_BYTES};
use crate::layout::{RunStats, SessionParams};
use crate::levels;
use crate::pipelines::{Pipelines, dispatch, dispatch_indirect};
use crate::shaders::WORKGROUP_SIZE;
use prismatic_core::model::scene::{Estimator, RadiusMode};
use prismatic_core::optics::surface::Surface;
use prismatic_core::photons::indirect::indirect_flux;
use prismatic_core::photons::trace::photon_flux;
use prismatic_core::photons::wavelengths::IndirectWavelengths;
use prismatic_core::plan::schedule::{GRID_LEVELS, PilotScale, pass_scene, pilot_scene};
use prismatic_core::{BackendError, NoProgress, PreparedScene, Progress, Stage};

/// Units a gather's largest possible term is worth at most: 2^30 of them
/// (an i64 sum holds 2^33 such terms; one term keeps 30 bits below it).
const TERM_BITS: i32 = 30;

impl GpuSession {
    /// Empties the pixels' sums, their first radii and the statistics of
    /// the passes (a change of the photons or more starts the passes
    /// again); with sampled view paths also the base, which holds pass 0's
    /// direct light, in its sums when pass 0 runs.
    pub(super) fn empty_sums(&mut self) -> Result<(), BackendError> {
        let none = RunStats { min_ratio: f32::INFINITY.to_bits(), ..RunStats::default() };
        self.ctx.write(&self.run_stats, 0, bytemuck::bytes_of(&none));
        let sampled = self.sampled();
        self.ctx.checked("emptying the sums", || {
            let mut encoder = self.ctx.device.create_command_encoder(&Default::default());
            for chunk in &self.points.chunks {
                encoder.clear_buffer(&chunk.sums, 0, None);
                encoder.clear_buffer(&chunk.pixel_ratios, 0, None);
                if sampled {
                    encoder.clear_buffer(&chunk.base, 0, None);
                }
            }
            self.ctx.submit(encoder);
        })
    }

    /// The pilot pass (progressive radii only): photons at 1/8 of a pass,
    /// gathered within the scene's radius; each point's first radius from
    /// what it found, and the grid levels those radii need marked (read
    /// back without waiting on a hardware GPU: its first pass may gather in
    /// coarser levels).
    pub(super) fn pilot(&mut self) -> Result<(), BackendError> {
        let Some(pilot) = pilot_scene(&self.scene).filter(|_| self.layer.is_none()) else { return Ok(()) };
        let scale = PilotScale::new(&self.scene, &pilot);
        let settings = SessionParams {
            pilot_scale: scale.scale,
            neighbours: scale.neighbours,
            inv_passes: 1.0,
            whole_radius: 1,
            sampled_view: u32::from(self.sampled()),
            ..SessionParams::default()
        };
        self.levels.forget(&self.ctx)?;
        self.trace_photons(&pilot, &mut NoProgress)?;
        self.stamp(Stage::Photons)?;
        self.grid_photons(&pilot)?;
        self.gather_chunks(Finish::FirstRadii, settings)?;
        self.stamp(Stage::Gather)?;
        self.levels.read_used(&self.ctx)?;
        if self.span != u32::MAX {
            // A device that gathers in segments waits for each pass's widest
            // buckets anyway: it waits for the mark too, so that the first
            // pass gathers in the levels its radii need.
            self.levels.wait_for_mark(&self.ctx)?;
            self.adopt_levels()?;
        }
        Ok(())
    }

    /// Photon pass `k`, gathered at the points with their radii and added to
    /// the pixels' sums; `summed` passes are in the image with it.
    pub(super) fn pass(&mut self, k: u32, summed: u32, progress: &mut dyn Progress) -> Result<(), BackendError> {
        self.use_lights_of(k)?;
        let pass = pass_scene(&self.scene, k);
        let fixed = self.scene.scene.render.radius_mode == RadiusMode::Fixed;
        let settings = SessionParams {
            inv_passes: 1.0 / summed as f32,
            whole_radius: u32::from(fixed),
            ..SessionParams::default()
        };
        if self.sampled() {
            self.trace_view(k)?;
            self.stamp(Stage::View)?;
            self.add_view()?;
        }
        self.trace_photons(&pass, progress)?;
        self.fold_tallies()?;
        self.stamp(Stage::Photons)?;
        if self.layer.is_some() {
            // No visible points: the gather's steps only add the pass to the sums and show them.
            self.splat_into_layer()?;
        } else {
            self.grid_photons(&pass)?;
            self.splat_photons()?;
        }
        self.gather_chunks(Finish::Accumulate, settings)?;
        self.stamp(Stage::Gather)
    }

    /// Light tracing (when the scene asks for it): the pass's photons
    /// connected to the camera and added to the pixels' sums of each chunk,
    /// before the gather shows them.
    fn splat_photons(&mut self) -> Result<(), BackendError> {
        if !self.scene.scene.render.light_tracing {
            return Ok(());
        }
        self.splat_chunks("light tracing the pass", |p| &p.splat, |g| Some(&g.splat))
    }

    /// A caustic layer's pass: its photons added to the sums of the pixels
    /// of the engine's frame that see them.
    fn splat_into_layer(&mut self) -> Result<(), BackendError> {
        self.splat_chunks("splatting the pass into the layer", |p| &p.layer_splat, |g| g.layer.as_ref())
    }

    /// Each chunk's dispatch of `pipeline` over the slots of the pass's
    /// photon map, with the chunk's group 1 `group` (none: nothing to do).
    fn splat_chunks(
        &mut self,
        what: &str,
        pipeline: fn(&Pipelines) -> &wgpu::ComputePipeline,
        group: fn(&ChunkGroups) -> Option<&wgpu::BindGroup>,
    ) -> Result<(), BackendError> {
        if self.photons.capacity() == 0 {
            return Ok(());
        }
        for chunk in &self.points.chunks {
            let Some(chunk_group) = group(chunk.groups()) else { continue };
            let p = &mut self.buffers.params;
            (p.pixel_offset, p.pixel_count) = (chunk.offset as u32, chunk.count as u32);
            self.buffers.write_params(&self.ctx);
            self.ctx.checked(what, || {
                let mut encoder = self.ctx.device.create_command_encoder(&Default::default());
                let groups = [&self.buffers.bind_group, chunk_group];
                let slots = u64::from(self.photons.capacity());
                dispatch(&mut encoder, pipeline(&self.pipelines), &groups, slots, WORKGROUP_SIZE);
                self.ctx.submit(encoder);
            })?;
        }
        Ok(())
    }

    /// Traces `pass`'s photons (its seed and photon count) into the map.
    pub(super) fn trace_photons(
        &mut self,
        pass: &PreparedScene,
        progress: &mut dyn Progress,
    ) -> Result<(), BackendError> {
        let r = &pass.scene.render;
        let (sum_shift, flux_shift) = gather_shifts(pass);
        let p = &mut self.buffers.params;
        (p.seed, p.radius, p.sum_shift, p.flux_shift) = (r.seed, r.radius, sum_shift, flux_shift);
        (p.flux, p.caustic_photons, p.indirect_flux) = (photon_flux(pass), pass.caustic_photons(), indirect_flux(pass));
        if self.photons.capacity() > 0 {
            let emissions = pass.traced_photons().min(self.photons.emissions());
            self.photons.record(&self.ctx, &self.pipelines, &mut self.buffers, emissions, progress)?;
        }
        Ok(())
    }

    /// Adds the last photon pass's tallies to the statistics (on the device).
    fn fold_tallies(&mut self) -> Result<(), BackendError> {
        self.ctx.checked("adding up the statistics", || {
            let mut encoder = self.ctx.device.create_command_encoder(&Default::default());
            dispatch(&mut encoder, &self.pipelines.fold_tallies, &[&self.fold_group], 1, 1);
            self.ctx.submit(encoder);
        })
    }

    /// Grids the map at every built level for `pass`'s radius.
    fn grid_photons(&mut self, pass: &PreparedScene) -> Result<(), BackendError> {
        if self.photons.capacity() > 0 {
            // `rebuild` leaves the grid's mask and window in the params for the gather.
            let radius = pass.scene.render.radius;
            self.levels.rebuild(&self.ctx, &self.pipelines, &mut self.buffers, &self.photons, radius)?;
        }
        self.stamp(Stage::Grid)
    }

    /// Every chunk: the points' sums emptied, radii set and listed by grid
    /// level, the gather level by level (in segments on a software device),
    /// then `finish` (first radii or the pixels' sums) with the pass's
    /// `settings`.
    fn gather_chunks(&mut self, finish: Finish, settings: SessionParams) -> Result<(), BackendError> {
        let steps = self.gather_steps(settings.whole_radius != 0)?;
        let r_pass = self.buffers.params.radius;
        let rough = self.buffers.params.rough_gathers != 0;
        for chunk in &self.points.chunks {
            let points = chunk.capacity;
            let groups = chunk.groups();
            for (i, step) in steps.iter().enumerate() {
                let p = &mut self.buffers.params;
                (p.pixel_offset, p.pixel_count, p.point_capacity) =
                    (chunk.offset as u32, chunk.count as u32, chunk.capacity as u32);
                let mut session = SessionParams { built_levels: self.levels.built(), ..settings };
                if let Some(GatherStep { level, segment }) = *step {
                    p.inv_cell = levels::inv_cell(r_pass, level);
                    (p.gather_first, p.gather_span) = (segment.saturating_mul(self.span), self.span);
                    session.level = level as u32;
                }
                self.buffers.write_params(&self.ctx);
                self.ctx.write(&self.session_params, 0, bytemuck::bytes_of(&session));
                self.ctx.checked("gathering the pass", || {
                    let mut encoder = self.ctx.device.create_command_encoder(&Default::default());
                    let coarsest = [groups.gather(0), &groups.session];
                    if i == 0 {
                        encoder.clear_buffer(&chunk.level_lists, 0, Some(LEVEL_HEADER_BYTES));
                        dispatch(&mut encoder, &self.pipelines.begin_pass, &coarsest, points, WORKGROUP_SIZE);
                        dispatch(&mut encoder, &self.pipelines.list_points, &coarsest, points, WORKGROUP_SIZE);
                        let args = [&groups.level_dispatch];
                        let levels = GRID_LEVELS as u64;
                        dispatch(&mut encoder, &self.pipelines.level_dispatches, &args, levels, levels as u32);
                    }
                    if let Some(GatherStep { level, .. }) = *step {
                        let both = [groups.gather(level), &groups.session];
                        let offset = LEVEL_ARGS_BYTES * level as u64;
                        dispatch_indirect(&mut encoder, &self.pipelines.gather_level, &both, &chunk.level_args, offset);
                        if rough {
                            let rough_level = &self.pipelines.gather_rough_level;
                            dispatch_indirect(&mut encoder, rough_level, &both, &chunk.level_args, offset);
                        }
                    }
                    if i + 1 == steps.len() {
                        match finish {
                            Finish::FirstRadii => {
                                dispatch(&mut encoder, &self.pipelines.first_radius, &coarsest, points, WORKGROUP_SIZE);
                            }
                            Finish::Accumulate => {
                                dispatch(&mut encoder, &self.pipelines.accumulate, &coarsest, points, WORKGROUP_SIZE);
                                dispatch(&mut encoder, &self.pipelines.show, &coarsest, chunk.count, WORKGROUP_SIZE);
                            }
                        }
                    }
                    self.ctx.submit(encoder);
                })?;
            }
        }
        Ok(())
    }

    /// The gather dispatches of this pass, in order: each built level (when
    /// every radius is the pass radius: level 0 alone) in as many segments
    /// as its widest bucket needs on a software device (read back: a wait);
    /// one empty step when there are no photons (the sums are still set
    /// and finished).
    fn gather_steps(&self, whole_radius: bool) -> Result<Vec<Option<GatherStep>>, BackendError> {
        let mut steps = Vec::new();
        if self.photons.capacity() > 0 && self.layer.is_none() {
            for (level, grid) in self.levels.iter().take(if whole_radius { 1 } else { GRID_LEVELS }) {
                let segments = match self.span {
                    u32::MAX => 1,
                    span => grid.widest_bucket(&self.ctx, &self.pipelines)?.div_ceil(span).max(1),
                };
                steps.extend((0..segments).map(|segment| Some(GatherStep { level, segment })));
            }
        }
        if steps.is_empty() {
            steps.push(None);
        }
        Ok(steps)
    }
}

/// The powers of two that put a pass's gather sums in fixed point (colour
/// sums, flux sum): the largest term a photon can add is worth at most
/// 2^[`TERM_BITS`] units. A photon carries at most the white flux Φ (a
/// projection map's weights are below 1), or an indirect photon's when
/// that is larger (fewer indirect photons than caustic ones); the density estimator adds
/// Φ·max(1, N·max|C_i|) at most, the paper's max(1, max|C_i|) (C_i, or
/// the colour of a wavelength over N: [`BandTable::max_colour`]), each
/// times what the surface reflects of it, at most its largest albedo
/// channel when above 1, or where points on rough surfaces gather,
/// [`ROUGH_REFLECTS_BOUND`].
///
/// [`BandTable::max_colour`]: prismatic_core::BandTable::max_colour
pub fn gather_shifts(pass: &PreparedScene) -> (i32, i32) {
    let indirect = match pass.indirect_photons() {
        0 => 0.0,
        _ => indirect_flux(pass) * IndirectWavelengths::largest_share(pass),
    };
    let flux = photon_flux(pass).max(indirect);
    let reflects = if pass.plan.rough_gathers { ROUGH_REFLECTS_BOUND } else { 1.0 };
    let weight = pass.bands.max_colour().max(1.0) * max_albedo(pass).max(reflects);
    let term = match pass.scene.render.estimator {
        Estimator::Density => flux * (weight * pass.bands.len() as f32).max(1.0),
        Estimator::Paper => weight,
    };
    (TERM_BITS - exponent(term), TERM_BITS - exponent(flux))
}

/// What a gather's term takes room for of π times a rough surface's BSDF
/// (`prismatic_core::photons::reflects::rough_reflects`), which weighs the
/// photons a visible point there gathers: for facets rough enough to
/// gather (α ≥ 0.1, D at most 1/(πα²) ≈ 32) it stays below this where the
/// eye and the light are not near grazing (head on, π f is about 25 for a
/// metal, 180 through glass of index 1.5 and 900 of index 1.1); a term
/// past it is clamped to it (fixed.wgsl). Room for it costs the sums 12
/// of their bits, which a term's 2^18 units still hold to 4e-6.
const ROUGH_REFLECTS_BOUND: f32 = 4096.0;

/// The largest albedo channel of the scene's diffuse surfaces (a texture
/// scales its surface's albedo by at most 1).
fn max_albedo(scene: &PreparedScene) -> f32 {
    let channels = scene.surfaces.iter().filter_map(|s| match s {
        Surface::Diffuse { albedo, checker, .. } => {
            Some(albedo.max_element().max(checker.as_ref().map_or(0.0, |c| c.albedo.max_element())))
        }
        _ => None,
    });
    channels.fold(0.0, f32::max)
}

/// The e with 2^(e−1) ≤ x < 2^e for a positive normal `x` (0 for zero or
/// non-normal values: any shift serves sums of nothing).
fn exponent(x: f32) -> i32 {
    if !x.is_normal() {
        return 0;
    }
    ((x.to_bits() >> 23) & 0xff) as i32 - 126
}

/// One gather dispatch: a grid level's points, one segment of each bucket.
#[derive(Clone, Copy)]
struct GatherStep {
    level: usize,
    segment: u32,
}

/// What follows a chunk's gather.
#[derive(Clone, Copy)]
enum Finish {
    /// The pilot's: each point's first radius (per slot).
    FirstRadii,
    /// A pass's: the pixels' sums (per point), then their image (per pixel).
    Accumulate,
}

#[cfg(test)]
mod tests {
    use super::exponent;

    #[test]
    fn the_exponent_bounds_its_value() {
        for x in [1e-30f32, 3e-7, 0.1, 0.5, 1.0, 1.5, 2.0, 1000.0, 3e30] {
            let e = exponent(x);
            assert!(2f32.powi(e - 1) <= x && x < 2f32.powi(e), "{x}: {e}");
        }
        assert_eq!((exponent(0.0), exponent(f32::NAN)), (0, 0));
    }
}
