//! A live render for engines: [`GpuSession`] keeps one scene's buffers, its
//! photon pass, grid, visible points and running sums on the device from
//! frame to frame, and each [`GpuSession::frame`] adds one progressive pass
//! (the estimator of `prismatic_core::progressive`: pilot-pass first radii,
//! radii shrinking with α, grid levels for small radii, the mean of the
//! passes) on the caller's queue without waiting for the device.
//! [`GpuSession::update`] diffs a changed scene against the current one and
//! invalidates only what the change touches ([`Change`]).

use crate::context::GpuContext;
use crate::layout::SessionParams;
use crate::levels::{self, GridLevels};
use crate::pipelines::{Pipelines, dispatch};
use crate::readback::PendingRead;
use crate::render::{PIXEL_BYTES, POINT_BYTES, pixel_buffer, pixel_chunks, pixels_per_chunk, read_image};
use crate::scene::{EncodedScene, SceneBuffers};
use crate::shaders::{WORKGROUP_SIZE, stack_size};
use crate::timing::{Stage, StageTimer, StageTimes};
use crate::trace::PhotonPass;
use crate::{GpuOptions, photons, render};
use prismatic_core::progressive::{GRID_LEVELS, photon_pass_scene, photons_per_path, pilot_scene};
use prismatic_core::scene::Scene;
use prismatic_core::{BackendError, Image, NoProgress, PreparedScene};

/// What a scene update invalidates, from least to most; each level redoes
/// what the levels below it redo.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord)]
pub enum Change {
    /// Nothing the image depends on (tone mapping, the pass count of an
    /// offline render).
    #[default]
    None,
    /// The photons alone: photon count, seed, radius, estimator, α,
    /// neighbours, projection maps. The passes start again (a new pilot
    /// pass, sums emptied); the view rays' image and visible points stay.
    Photons,
    /// What the view rays see: camera, objects, materials, lights (their
    /// direct light and shadows are the view pass's), bands, depth,
    /// wavelength sampling, exposure, ambient, background. The view rays
    /// are traced again, then as [`Change::Photons`].
    View,
    /// The image size: pixel and visible-point buffers are allocated
    /// again, then as [`Change::View`].
    Size,
}

impl Change {
    /// What going from scene `old` to scene `new` invalidates.
    pub fn between(old: &Scene, new: &Scene) -> Change {
        let (a, b) = (&old.render, &new.render);
        if (a.width, a.height) != (b.width, b.height) {
            Change::Size
        } else if old.camera != new.camera
            || old.objects != new.objects
            || old.materials != new.materials
            || old.lights != new.lights
            || a.bands != b.bands
            || a.max_depth != b.max_depth
            || a.wavelengths != b.wavelengths
            || a.exposure != b.exposure
            || a.ambient != b.ambient
            || a.background != b.background
        {
            Change::View
        } else if a.photons != b.photons
            || a.seed != b.seed
            || a.radius != b.radius
            || a.estimator != b.estimator
            || a.alpha != b.alpha
            || a.neighbours != b.neighbours
            || a.projection_maps != b.projection_maps
        {
            Change::Photons
        } else {
            Change::None
        }
    }
}

/// What one [`GpuSession::frame`] did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SessionFrame {
    /// Passes in the image now, this frame's included.
    pub passes: u32,
    /// White photons this frame emitted (its pass's, plus the pilot's after a change).
    pub photons: u64,
    /// What this frame redid before its pass (an update's change, or
    /// [`Change::Size`] when more visible-point slots were needed).
    pub redone: Change,
}

/// A pixel chunk's visible points, their first radii and running sums.
struct PointChunk {
    /// First pixel.
    offset: u64,
    /// Pixels.
    count: u64,
    /// `slots` visible points per pixel, slot-major.
    points: wgpu::Buffer,
    /// Per pixel: visible points it wanted.
    counts: wgpu::Buffer,
    /// Per slot: the first radius as a fraction of the scene's.
    ratio: wgpu::Buffer,
    /// Per pixel: Σ over passes of the caustic radiance.
    accum: wgpu::Buffer,
    /// Per pixel: the direct light (the view pass's pixels).
    base: wgpu::Buffer,
    /// View pass, gather, and session entries' bind groups.
    groups: Option<ChunkGroups>,
}

struct ChunkGroups {
    view: wgpu::BindGroup,
    /// Per built grid level (by level), the gather's bindings.
    gather: Vec<Option<wgpu::BindGroup>>,
    session: wgpu::BindGroup,
}

impl ChunkGroups {
    /// The gather's bindings with level `level`'s grid.
    fn gather(&self, level: usize) -> &wgpu::BindGroup {
        self.gather[level].as_ref().expect("bound for every built level")
    }
}

impl PointChunk {
    fn groups(&self) -> &ChunkGroups {
        self.groups.as_ref().expect("bound when allocated")
    }
}

/// A scene rendered progressively on the device, one pass per frame.
pub struct GpuSession {
    ctx: GpuContext,
    pipelines: Pipelines,
    options: GpuOptions,
    /// Photons per bucket one gather dispatch reads (`u32::MAX` on hardware).
    span: u32,
    scene: PreparedScene,
    encoded: EncodedScene,
    buffers: SceneBuffers,
    photons: PhotonPass,
    levels: GridLevels,
    /// The image: row-major `vec4<f32>`, linear RGB, exposure applied.
    pixels: wgpu::Buffer,
    /// Visible-point slots per pixel.
    slots: u32,
    /// The most visible points a pixel wanted, where more than its slots.
    needed: wgpu::Buffer,
    chunks: Vec<PointChunk>,
    session_params: wgpu::Buffer,
    passes: u32,
    /// What the next frame must redo.
    stale: Change,
    /// Whether a view pass has told how many slots a pixel needs.
    slots_learnt: bool,
    /// The view pass's "points needed" on its way back.
    pending_slots: Option<PendingRead>,
    /// GPU stage times, where the device has timestamps.
    timer: Option<StageTimer>,
}

impl GpuSession {
    /// A session on `ctx` (an engine's device, or one of the backend's)
    /// for `scene`. Compiles the pipelines and allocates every buffer; the
    /// first [`GpuSession::frame`] traces the visible points and waits for
    /// the device once, to learn how many points a pixel needs.
    pub fn new(ctx: GpuContext, scene: &PreparedScene, options: GpuOptions) -> Result<Self, BackendError> {
        let pipelines = Pipelines::new(&ctx.device);
        let software = ctx.device.adapter_info().device_type == wgpu::DeviceType::Cpu;
        let span = options.gather_span.unwrap_or(if software { render::SOFTWARE_GATHER_SPAN } else { u32::MAX });
        let encoded = EncodedScene::new(scene);
        let buffers = ctx
            .checked("uploading the scene", || SceneBuffers::upload(&ctx.device, &pipelines.scene_layout, &encoded))?;
        let window = window(&ctx, options);
        let photons = photon_pass(&ctx, &pipelines, scene, &buffers, window)?;
        let levels = GridLevels::new(&ctx, &pipelines, &buffers, &photons)?;
        let small = |label: &str, size: usize, usage: wgpu::BufferUsages| {
            ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: size.max(16) as u64,
                usage,
                mapped_at_creation: false,
            })
        };
        let (needed, session_params) = ctx.checked("allocating the session", || {
            let copy = wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST;
            (
                small("prismatic points needed", 4, wgpu::BufferUsages::STORAGE | copy),
                small(
                    "prismatic session params",
                    size_of::<SessionParams>(),
                    wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                ),
            )
        })?;
        let pixels = pixel_buffer(&ctx, scene.scene.render.width, scene.scene.render.height)?;
        let timer = StageTimer::new(&ctx)?;
        Ok(GpuSession {
            ctx,
            pipelines,
            options,
            span,
            scene: scene.clone(),
            encoded,
            buffers,
            photons,
            levels,
            pixels,
            slots: render::FIRST_POINTS_PER_PIXEL,
            needed,
            chunks: Vec::new(),
            session_params,
            passes: 0,
            stale: Change::Size,
            slots_learnt: false,
            pending_slots: None,
            timer,
        })
    }

    /// The device and queue.
    pub fn context(&self) -> &GpuContext {
        &self.ctx
    }

    /// The scene being rendered.
    pub fn scene(&self) -> &PreparedScene {
        &self.scene
    }

    /// Passes in the image so far.
    pub fn passes(&self) -> u32 {
        self.passes
    }

    /// The image's pixels: width × height row-major `vec4<f32>` (linear RGB,
    /// exposure applied, alpha 1), the mean of the passes so far.
    pub fn pixels(&self) -> &wgpu::Buffer {
        &self.pixels
    }

    /// Makes `scene` the session's scene. Uploads only the bytes of the
    /// scene's buffers that changed (reallocating a buffer only when it
    /// grows); the photon map and grid are reallocated only when the photon
    /// count, band split or photon window changes. Returns what the change
    /// invalidates; the next frame redoes it.
    pub fn update(&mut self, scene: &PreparedScene) -> Result<Change, BackendError> {
        let change = Change::between(&self.scene.scene, &scene.scene);
        if change == Change::None {
            self.scene = scene.clone();
            return Ok(change);
        }
        let encoded = EncodedScene::new(scene);
        let regrouped = self.ctx.checked("updating the scene", || {
            self.buffers.update(
                &self.ctx.device,
                &self.ctx.queue,
                &self.pipelines.scene_layout,
                &self.encoded,
                &encoded,
            )
        })?;
        self.encoded = encoded;
        let window = window(&self.ctx, self.options);
        let mut rebind = regrouped;
        if !self.photons.fits(scene, window) {
            self.photons = photon_pass(&self.ctx, &self.pipelines, scene, &self.buffers, window)?;
            self.levels.reallocate(&self.ctx, &self.pipelines, &self.buffers, &self.photons)?;
            rebind = true;
        }
        if change == Change::Size {
            let r = &scene.scene.render;
            self.pixels = pixel_buffer(&self.ctx, r.width, r.height)?;
        } else if rebind {
            // The chunks' bind groups hold the band table, grid and photons that moved.
            self.bind_chunks()?;
        }
        self.scene = scene.clone();
        self.stale = self.stale.max(change);
        Ok(change)
    }

    /// Submits one progressive pass (after redoing what an update or a
    /// slot shortage invalidated) and returns without waiting for the
    /// device. On a software device the gather goes in segments whose
    /// number comes from the grid, which it reads back (waits); a hardware
    /// GPU never waits.
    pub fn frame(&mut self) -> Result<SessionFrame, BackendError> {
        self.check_reads()?;
        let redone = std::mem::take(&mut self.stale);
        let mut photons = 0;
        if redone >= Change::Size {
            self.allocate_chunks()?;
        }
        if let Some(timer) = &mut self.timer {
            timer.begin(&self.ctx)?;
        }
        if redone >= Change::View {
            self.trace_view()?;
            self.stamp(Stage::View)?;
        }
        if redone >= Change::Photons {
            photons += self.pilot()?;
            self.passes = 0;
        }
        photons += self.pass()?;
        self.passes += 1;
        if let Some(timer) = &mut self.timer {
            timer.finish(&self.ctx)?;
        }
        Ok(SessionFrame { passes: self.passes, photons, redone })
    }

    /// The GPU time of each stage of the last frame whose timestamps have
    /// come back (read without waiting, usually a frame or two late);
    /// `None` before then, or when the device has no timestamp queries
    /// (an engine's device needs [`crate::timestamp_features`] for them).
    pub fn stage_times(&self) -> Option<StageTimes> {
        self.timer.as_ref().and_then(StageTimer::last)
    }

    /// Copies the image into `texture` (its size; `Rgba32Float`,
    /// `Rgba16Float` or `Rgba8Unorm`; `STORAGE_BINDING` usage) on the
    /// device; submitted, not waited for.
    pub fn copy_to_texture(&mut self, texture: &wgpu::Texture) -> Result<(), BackendError> {
        render::copy_to_texture(&self.ctx, &mut self.pipelines, &mut self.buffers, &self.pixels, texture)
    }

    /// Waits for the device and reads the image back (tests, screenshots).
    pub fn image(&self) -> Result<Image, BackendError> {
        let r = &self.scene.scene.render;
        read_image(&self.ctx, &self.pixels, r.width, r.height)
    }

    /// Visible-point slots per pixel now.
    pub fn points_per_pixel(&self) -> u32 {
        self.slots
    }

    /// The grid levels built now: bit l for level l (cells of the pass
    /// radius / 4^l); level 0 always, finer ones once the first radii ask.
    pub fn grid_levels(&self) -> u32 {
        self.levels.built()
    }

    /// Allocates the visible points' buffers for the current slots and
    /// binds every chunk.
    fn allocate_chunks(&mut self) -> Result<(), BackendError> {
        let r = &self.scene.scene.render;
        let total = u64::from(r.width) * u64::from(r.height);
        let chunk = pixels_per_chunk(&self.ctx.limits(), self.slots).min(total.max(1).next_multiple_of(16));
        let ctx = &self.ctx;
        let buffer = |label: &str, size: u64, usage: wgpu::BufferUsages| {
            ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: size.max(16),
                usage: wgpu::BufferUsages::STORAGE | usage,
                mapped_at_creation: false,
            })
        };
        let copy = wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC;
        self.chunks.clear();
        for (offset, count) in pixel_chunks(total, chunk) {
            let slots = count * u64::from(self.slots);
            let chunk = ctx.checked("allocating visible points", || PointChunk {
                offset,
                count,
                points: buffer("prismatic visible points", slots * POINT_BYTES, copy),
                counts: buffer("prismatic points per pixel", count * 4, copy),
                ratio: buffer("prismatic radius ratios", slots * 4, copy),
                accum: buffer("prismatic caustic sums", count * PIXEL_BYTES, copy),
                base: buffer("prismatic direct light", count * PIXEL_BYTES, copy),
                groups: None,
            })?;
            self.chunks.push(chunk);
        }
        self.bind_chunks()
    }

    /// Binds every chunk to the current pixels, scene, grid and photons
    /// (again after an update moved one of them; the points stay).
    fn bind_chunks(&mut self) -> Result<(), BackendError> {
        let (ctx, p) = (&self.ctx, &self.pipelines);
        for chunk in &mut self.chunks {
            let pixel_slice = wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                buffer: &self.pixels,
                offset: chunk.offset * PIXEL_BYTES,
                size: wgpu::BufferSize::new(chunk.count * PIXEL_BYTES),
            });
            let groups = ctx.checked("binding the session", || {
                let group = |label: &str, layout: &wgpu::BindGroupLayout, entries: &[wgpu::BindGroupEntry]| {
                    ctx.device.create_bind_group(&wgpu::BindGroupDescriptor { label: Some(label), layout, entries })
                };
                let view = group(
                    "prismatic session view",
                    &p.render_layout,
                    &[
                        wgpu::BindGroupEntry { binding: 0, resource: pixel_slice.clone() },
                        wgpu::BindGroupEntry { binding: 1, resource: chunk.points.as_entire_binding() },
                        wgpu::BindGroupEntry { binding: 2, resource: chunk.counts.as_entire_binding() },
                        wgpu::BindGroupEntry { binding: 3, resource: self.needed.as_entire_binding() },
                    ],
                );
                let mut gather: Vec<Option<wgpu::BindGroup>> = vec![None; GRID_LEVELS];
                for (level, grid) in self.levels.iter() {
                    let mut entries = vec![
                        wgpu::BindGroupEntry { binding: 0, resource: self.buffers.params_buffer.as_entire_binding() },
                        wgpu::BindGroupEntry { binding: 1, resource: self.buffers.bands().as_entire_binding() },
                        wgpu::BindGroupEntry { binding: 2, resource: grid.cells.as_entire_binding() },
                        wgpu::BindGroupEntry { binding: 3, resource: chunk.counts.as_entire_binding() },
                        wgpu::BindGroupEntry { binding: 4, resource: chunk.points.as_entire_binding() },
                        wgpu::BindGroupEntry { binding: 5, resource: pixel_slice.clone() },
                    ];
                    entries.extend(grid.sorted.entries(6));
                    gather[level] = Some(group("prismatic session gather", &p.gather_layout, &entries));
                }
                let session = group(
                    "prismatic session sums",
                    &p.session_layout,
                    &[
                        wgpu::BindGroupEntry { binding: 0, resource: chunk.ratio.as_entire_binding() },
                        wgpu::BindGroupEntry { binding: 1, resource: chunk.accum.as_entire_binding() },
                        wgpu::BindGroupEntry { binding: 2, resource: chunk.base.as_entire_binding() },
                        wgpu::BindGroupEntry { binding: 3, resource: self.session_params.as_entire_binding() },
                        wgpu::BindGroupEntry { binding: 4, resource: self.levels.used.as_entire_binding() },
                    ],
                );
                ChunkGroups { view, gather, session }
            })?;
            chunk.groups = Some(groups);
        }
        Ok(())
    }
}

impl GpuSession {
    /// Traces the view rays of every chunk into its pixels (the direct
    /// light, kept as the base) and visible points. The first time, waits
    /// to learn whether every pixel's points had a slot and traces again
    /// with more when not; later, the check is read back a frame or more
    /// afterwards ([`GpuSession::check_reads`]).
    fn trace_view(&mut self) -> Result<(), BackendError> {
        loop {
            let view = self.pipelines.render(&self.ctx.device, stack_size(self.buffers.params.max_depth)).clone();
            let caustics = u32::from(self.photons.capacity() > 0);
            for (i, chunk) in self.chunks.iter().enumerate() {
                let p = &mut self.buffers.params;
                (p.pixel_offset, p.pixel_count, p.points_per_pixel, p.stored) =
                    (chunk.offset as u32, chunk.count as u32, self.slots, caustics);
                self.buffers.write_params(&self.ctx.queue);
                self.ctx.checked("tracing the view rays", || {
                    let mut encoder = self.ctx.device.create_command_encoder(&Default::default());
                    if i == 0 {
                        encoder.clear_buffer(&self.needed, 0, None);
                    }
                    let groups = [&self.buffers.bind_group, &chunk.groups().view];
                    dispatch(&mut encoder, &view, &groups, chunk.count, WORKGROUP_SIZE);
                    let bytes = chunk.count * PIXEL_BYTES;
                    encoder.copy_buffer_to_buffer(&self.pixels, chunk.offset * PIXEL_BYTES, &chunk.base, 0, bytes);
                    self.ctx.queue.submit([encoder.finish()]);
                })?;
            }
            self.pending_slots = Some(PendingRead::start(&self.ctx, &self.needed, "the visible-point count")?);
            if self.slots_learnt {
                return Ok(());
            }
            // The first view pass: wait for the answer, and trace again with enough slots.
            self.ctx.wait()?;
            self.slots_learnt = true;
            self.check_reads()?;
            if self.stale < Change::Size {
                return Ok(());
            }
            self.stale = Change::None;
            self.allocate_chunks()?;
        }
    }

    /// Looks (without waiting) whether values read back have come: the
    /// last view pass's slot count (when some pixel wanted more slots than
    /// it had, the next frame allocates enough and traces the view again)
    /// and the grid levels the first radii need (built for the next pass).
    fn check_reads(&mut self) -> Result<(), BackendError> {
        let timing = self.timer.as_ref().is_some_and(StageTimer::reading);
        if self.pending_slots.is_none() && !self.levels.reading() && !timing {
            return Ok(());
        }
        self.ctx
            .device
            .poll(wgpu::PollType::Poll)
            .map_err(|e| BackendError::Device(format!("polling the GPU: {e}")))?;
        if let Some(needed) = self.pending_slots.as_ref().map(PendingRead::value).transpose()?.flatten() {
            self.pending_slots = None;
            if needed > self.slots {
                self.slots = needed.next_power_of_two();
                self.stale = Change::Size;
            }
        }
        if self.levels.adopt(&self.ctx, &self.pipelines, &self.buffers, &self.photons)? && !self.chunks.is_empty() {
            self.bind_chunks()?;
        }
        if let Some(timer) = &mut self.timer {
            timer.check()?;
        }
        Ok(())
    }

    /// Stamps the end of `stage` when timing.
    fn stamp(&mut self, stage: Stage) -> Result<(), BackendError> {
        match &mut self.timer {
            Some(timer) => timer.end(&self.ctx, stage),
            None => Ok(()),
        }
    }

    /// The pilot pass: photons at 1/8 of a pass, gathered within the
    /// scene's radius; each point's first radius from what it found.
    fn pilot(&mut self) -> Result<u64, BackendError> {
        let pilot = pilot_scene(&self.scene);
        let r = &self.scene.scene.render;
        let settings = SessionParams {
            pilot_scale: r.photons as f32 / pilot.scene.render.photons as f32,
            neighbours: (r.neighbours * photons_per_path(&self.scene)) as f32,
            inv_passes: 1.0,
            pilot: 1,
            ..SessionParams::default()
        };
        self.levels.forget(&self.ctx)?;
        let emitted = self.photon_pass(&pilot)?;
        self.gather_chunks(Finish::FirstRadii, false, settings)?;
        self.stamp(Stage::Gather)?;
        self.levels.read_used(&self.ctx)?;
        Ok(emitted)
    }

    /// Photon pass `self.passes`, gathered at the points with their shrunk
    /// radii and added to the pixels' sums.
    fn pass(&mut self) -> Result<u64, BackendError> {
        let k = self.passes;
        let pass = photon_pass_scene(&self.scene, self.scene.scene.render.alpha, k);
        let settings = SessionParams { inv_passes: 1.0 / (f64::from(k) + 1.0) as f32, ..SessionParams::default() };
        let emitted = self.photon_pass(&pass)?;
        self.gather_chunks(Finish::Accumulate, k == 0, settings)?;
        self.stamp(Stage::Gather)?;
        Ok(emitted)
    }

    /// Traces `pass`'s photons (its seed and photon count) and grids them
    /// at every built level for its radius.
    fn photon_pass(&mut self, pass: &PreparedScene) -> Result<u64, BackendError> {
        let r = &pass.scene.render;
        let p = &mut self.buffers.params;
        (p.seed, p.radius) = (r.seed, r.radius);
        let emissions = r.photons.min(self.photons.emissions());
        if self.photons.capacity() == 0 {
            return Ok(0);
        }
        self.photons.record(&self.ctx, &self.pipelines, &mut self.buffers, emissions, &mut NoProgress)?;
        self.stamp(Stage::Photons)?;
        // `rebuild` leaves the grid's mask and window in the params for the gather.
        self.levels.rebuild(&self.ctx, &self.pipelines, &mut self.buffers, &self.photons, r.radius)?;
        self.stamp(Stage::Grid)?;
        Ok(u64::from(emissions))
    }

    /// Every chunk: sums emptied and radii set, the gather level by level
    /// (in segments on a software device), then `finish` (first radii or
    /// accumulation) with the pass's `settings`; `first_pass` empties the
    /// pixels' sums first.
    fn gather_chunks(&mut self, finish: Finish, first_pass: bool, settings: SessionParams) -> Result<(), BackendError> {
        let steps = self.gather_steps(settings.pilot != 0)?;
        let r_pass = self.buffers.params.radius;
        for chunk in &self.chunks {
            let slot_count = chunk.count * u64::from(self.slots);
            let groups = chunk.groups();
            for (i, step) in steps.iter().enumerate() {
                let p = &mut self.buffers.params;
                (p.pixel_offset, p.pixel_count, p.points_per_pixel) =
                    (chunk.offset as u32, chunk.count as u32, self.slots);
                let mut session = SessionParams { built_levels: self.levels.built(), ..settings };
                if let Some(GatherStep { level, segment }) = *step {
                    p.inv_cell = levels::inv_cell(r_pass, level);
                    (p.gather_first, p.gather_span) = (segment.saturating_mul(self.span), self.span);
                    session.level = level as u32;
                }
                self.buffers.write_params(&self.ctx.queue);
                self.ctx.queue.write_buffer(&self.session_params, 0, bytemuck::bytes_of(&session));
                self.ctx.checked("gathering the pass", || {
                    let mut encoder = self.ctx.device.create_command_encoder(&Default::default());
                    let coarsest = [groups.gather(0), &groups.session];
                    if i == 0 {
                        if first_pass {
                            encoder.clear_buffer(&chunk.accum, 0, None);
                        }
                        dispatch(&mut encoder, &self.pipelines.begin_pass, &coarsest, slot_count, WORKGROUP_SIZE);
                    }
                    if let Some(GatherStep { level, .. }) = *step {
                        let both = [groups.gather(level), &groups.session];
                        dispatch(&mut encoder, &self.pipelines.gather_level, &both, slot_count, WORKGROUP_SIZE);
                    }
                    if i + 1 == steps.len() {
                        let (pipeline, invocations) = match finish {
                            Finish::FirstRadii => (&self.pipelines.first_radius, slot_count),
                            Finish::Accumulate => (&self.pipelines.accumulate, chunk.count),
                        };
                        dispatch(&mut encoder, pipeline, &coarsest, invocations, WORKGROUP_SIZE);
                    }
                    self.ctx.queue.submit([encoder.finish()]);
                })?;
            }
        }
        Ok(())
    }

    /// The gather dispatches of this pass, in order: each built level (the
    /// pilot's radii are all the pass radius: level 0 alone) in as many
    /// segments as its widest bucket needs on a software device; one empty
    /// step when there are no photons (the sums are still set and finished).
    fn gather_steps(&self, pilot: bool) -> Result<Vec<Option<GatherStep>>, BackendError> {
        let mut steps = Vec::new();
        if self.photons.capacity() > 0 {
            for (level, grid) in self.levels.iter().take(if pilot { 1 } else { GRID_LEVELS }) {
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
    /// A pass's: the pixels' sums and image (per pixel).
    Accumulate,
}

/// Photons per storage binding for `options` on `ctx`'s device.
fn window(ctx: &GpuContext, options: GpuOptions) -> u32 {
    let device = photons::window_for(&ctx.limits());
    options.window_photons.map_or(device, |w| w.clamp(1, device))
}

/// A photon pass's buffers for `scene`; an error when its photons cannot
/// all be stored (a frame must never drop photons silently).
fn photon_pass(
    ctx: &GpuContext,
    pipelines: &Pipelines,
    scene: &PreparedScene,
    buffers: &SceneBuffers,
    window: u32,
) -> Result<PhotonPass, BackendError> {
    let pass = PhotonPass::new(ctx, pipelines, scene, buffers, window)?;
    let bound = u64::from(pass.emissions()) * u64::from(crate::trace::slots_per_emission(scene));
    if bound > u64::from(pass.capacity()) {
        return Err(BackendError::OutOfMemory(format!(
            "a pass of {} photons can store {bound} band photons; this device's photon map holds {}: trace fewer \
             photons per frame",
            pass.emissions(),
            pass.capacity()
        )));
    }
    Ok(pass)
}
