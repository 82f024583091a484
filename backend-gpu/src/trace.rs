//! The photon pass on the device: twin of `prismatic_core::photons::trace`. Emissions
//! go in chunks (a chunk's scratch fits one binding and its dispatch the
//! workgroup limits); per chunk: emit + trace, prefix sum of the per-emission
//! counts, scatter into the canonical map after the chunks before it, and
//! a one-invocation pass that moves the map's cursor. Nothing is read back:
//! the cursor goes into the grid's params on the device, and the
//! per-workgroup tallies are added to the render's statistics there
//! (stats.wgsl), or read when a caller asks for a pass's photon map.

use crate::context::GpuContext;
use crate::layout::Tally;
use crate::photons::{PHOTON_BYTES, PhotonArray};
use crate::pipelines::{Pipelines, dispatch};
use crate::scan::Scan;
use crate::scene::SceneBuffers;
use crate::shaders::{MAX_WORKGROUPS, WORKGROUP_SIZE};
use prismatic_core::optics::surface::Surface;
use prismatic_core::photons::wavelengths::IndirectWavelengths;
use prismatic_core::{BackendError, PreparedScene, Progress, Stage, TraceStats};

/// Largest chunk of emissions per dispatch (keeps progress reports coming
/// and the scratch small).
pub const MAX_CHUNK: u32 = 1 << 20;

/// Scratch slots per emission: the most photons one emission stores.
pub fn slots_per_emission(scene: &PreparedScene) -> u32 {
    caustic_slots(scene).max(indirect_slots(scene))
}

/// The most photons a caustic emission stores: one per path a white photon
/// splits into (every band, or the hero wavelengths) where it splits (at
/// glass that splits photons or a coloured metal), else one; where a path
/// can store and go on (a blended metal) or be met on rough surfaces for
/// light tracing, two at every surface up to the depth limit, for the
/// white path before its split too.
fn caustic_slots(scene: &PreparedScene) -> u32 {
    let paths = caustic_paths(scene);
    let recorded = scene.plan.rough_records;
    let blended = |s: &Surface| matches!(s, Surface::Metal(m) if m.is_blended());
    let goes_on = scene.surfaces.iter().any(|s| blended(s) || (recorded && s.facets().is_some()));
    match goes_on {
        true => (paths + 1) * 2 * (scene.plan.max_depth + 1),
        false => paths,
    }
}

/// The paths a caustic emission can become: one per band or hero
/// wavelength where a white photon splits (at glass that splits photons
/// or a coloured metal), else one.
fn caustic_paths(scene: &PreparedScene) -> u32 {
    let splits = scene.surfaces.iter().any(|s| match s {
        Surface::Dielectric(g) => g.splits_photons,
        Surface::Metal(m) => m.is_chromatic(),
        _ => false,
    });
    if splits { scene.scene.render.wavelengths.paths(scene.bands.len()) } else { 1 }
}

/// The most photons an indirect emission stores: one per wavelength it
/// carries at every diffuse hit up to the depth limit (none without
/// indirect light).
fn indirect_slots(scene: &PreparedScene) -> u32 {
    match scene.indirect_photons() {
        0 => 0,
        _ => scene.plan.max_depth.max(1) * IndirectWavelengths::most(scene),
    }
}

/// Photons a pass of `scene` has room for: every emission filling its
/// slots, but a caustic emission whose paths can store and go on (blended
/// metals, rough surfaces met for light tracing) at most
/// [`CAUSTIC_ROOM`] per path (the grids are as large as the map, so room
/// for every slot of such a scene would cost every pass; a pass that
/// stores more is an error that says so, [`PhotonPass::stored`]).
pub fn map_bound(scene: &PreparedScene) -> u64 {
    let caustic = caustic_slots(scene).min(CAUSTIC_ROOM * caustic_paths(scene));
    u64::from(scene.caustic_photons()) * u64::from(caustic)
        + u64::from(scene.indirect_photons()) * u64::from(indirect_slots(scene))
}

/// The room in the map per path of a caustic emission where paths can
/// store and go on ([`map_bound`]): the path's last photon and three met
/// on rough surfaces (or stored on blended metals) on its way.
pub const CAUSTIC_ROOM: u32 = 4;

fn storage(ctx: &GpuContext, label: &str, bytes: u64) -> wgpu::Buffer {
    ctx.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: bytes.max(4),
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

/// The photon pass's device buffers: the canonical map (room for every
/// photon the scene can store), one chunk's scratch, its scan and
/// compaction bindings, and the cursor and tallies. A session keeps them
/// from pass to pass, so a pass allocates nothing; a one-off trace makes
/// them for one.
pub struct PhotonPass {
    /// The map, in canonical order once a pass has run.
    pub photons: PhotonArray,
    /// Emissions per pass.
    total: u32,
    /// Scratch slots per emission.
    slots: u32,
    /// Emissions per chunk.
    chunk: u32,
    counts: wgpu::Buffer,
    offsets: wgpu::Buffer,
    /// One u32: photons stored so far (saturating at `u32::MAX`).
    cursor: wgpu::Buffer,
    tallies: wgpu::Buffer,
    /// The trace's and the compaction's bindings (they also hold the chunk's scratch).
    trace_group: wgpu::BindGroup,
    /// The scan of a whole chunk's `offsets` (a shorter last chunk's tail is zeroed).
    scan: Scan,
    compact_group: wgpu::BindGroup,
}

impl PhotonPass {
    /// Buffers for the photon passes of `scene` (its photon count, bands and
    /// wavelength sampling) with `window` photons per binding, bound to
    /// `scene_buffers`' params.
    pub fn new(
        ctx: &GpuContext,
        pipelines: &Pipelines,
        scene: &PreparedScene,
        scene_buffers: &SceneBuffers,
        window: u32,
    ) -> Result<Self, BackendError> {
        let total = scene.traced_photons();
        let slots = slots_per_emission(scene);
        let chunk = (window / slots).clamp(1, MAX_CHUNK).min(total.max(1));
        let capacity = map_bound(scene).min(u64::from(u32::MAX)) as u32;
        let photons = PhotonArray::new(ctx, "prismatic photon map", capacity, window)?;
        let groups = u64::from(chunk).div_ceil(u64::from(WORKGROUP_SIZE));
        let (scratch, counts, offsets, cursor, tallies) = ctx.checked("allocating the photon pass", || {
            (
                storage(ctx, "prismatic scratch", u64::from(chunk) * u64::from(slots) * PHOTON_BYTES),
                storage(ctx, "prismatic counts", u64::from(chunk) * 4),
                storage(ctx, "prismatic offsets", u64::from(chunk) * 4),
                storage(ctx, "prismatic cursor", 4),
                storage(ctx, "prismatic tallies", dispatched_groups(groups) * std::mem::size_of::<Tally>() as u64),
            )
        })?;
        let (trace_group, scan, compact_group) = ctx.checked("binding the photon pass", || {
            let trace_group = ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("prismatic trace"),
                layout: &pipelines.trace_layout,
                entries: &[
                    wgpu::BindGroupEntry { binding: 0, resource: scratch.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 1, resource: counts.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 2, resource: tallies.as_entire_binding() },
                ],
            });
            let scan = Scan::new(ctx, pipelines, &offsets, chunk);
            let mut entries = vec![
                wgpu::BindGroupEntry { binding: 0, resource: scene_buffers.params_buffer.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 1, resource: scratch.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 2, resource: counts.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 3, resource: offsets.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 4, resource: cursor.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 5, resource: scan.total().as_entire_binding() },
            ];
            entries.extend(photons.entries(6));
            let compact_group = ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("prismatic compact"),
                layout: &pipelines.compact_layout,
                entries: &entries,
            });
            (trace_group, scan, compact_group)
        })?;
        Ok(PhotonPass {
            photons,
            total,
            slots,
            chunk,
            counts,
            offsets,
            cursor,
            tallies,
            trace_group,
            scan,
            compact_group,
        })
    }

    /// Whether these buffers hold `scene`'s passes (same photons, same slots per emission).
    pub fn fits(&self, scene: &PreparedScene, window: u32) -> bool {
        let capacity = map_bound(scene).min(u64::from(u32::MAX)) as u32;
        (self.total, self.slots, self.photons.capacity, self.photons.window)
            == (scene.traced_photons(), slots_per_emission(scene), capacity, window)
    }

    /// Photons the map holds at most: every emission storing every slot.
    pub fn capacity(&self) -> u32 {
        self.photons.capacity
    }

    /// The device's count of stored photons (one u32), valid after [`PhotonPass::record`].
    pub fn cursor(&self) -> &wgpu::Buffer {
        &self.cursor
    }

    /// White photons a pass emits.
    pub fn emissions(&self) -> u32 {
        self.total
    }

    /// Submits a photon pass of the first `emissions` (at most
    /// [`PhotonPass::emissions`]) emissions of the seed in the params, in
    /// chunks, starting from an empty map; reads nothing back.
    pub fn record(
        &self,
        ctx: &GpuContext,
        pipelines: &Pipelines,
        scene_buffers: &mut SceneBuffers,
        emissions: u32,
        progress: &mut dyn Progress,
    ) -> Result<(), BackendError> {
        let (total, slots, chunk, window) = (emissions.min(self.total), self.slots, self.chunk, self.photons.window);
        let mut start = 0u32;
        while start < total {
            let len = chunk.min(total - start);
            let p = &mut scene_buffers.params;
            (p.chunk_start, p.chunk_len, p.slots, p.window, p.capacity) =
                (start, len, slots, window, self.photons.capacity);
            scene_buffers.write_params(ctx);
            ctx.checked("tracing photons", || {
                let mut encoder = ctx.device.create_command_encoder(&Default::default());
                if start == 0 {
                    encoder.clear_buffer(&self.cursor, 0, None);
                    encoder.clear_buffer(&self.tallies, 0, None);
                }
                dispatch(
                    &mut encoder,
                    &pipelines.trace,
                    &[&scene_buffers.bind_group, &self.trace_group],
                    u64::from(len),
                    WORKGROUP_SIZE,
                );
                encoder.copy_buffer_to_buffer(&self.counts, 0, &self.offsets, 0, u64::from(len) * 4);
                if len < chunk {
                    // The scan covers a whole chunk: a shorter chunk's tail adds nothing.
                    encoder.clear_buffer(&self.offsets, u64::from(len) * 4, None);
                }
                self.scan.record(pipelines, &mut encoder);
                let slots_total = u64::from(len) * u64::from(slots);
                dispatch(&mut encoder, &pipelines.compact, &[&self.compact_group], slots_total, WORKGROUP_SIZE);
                dispatch(&mut encoder, &pipelines.advance, &[&self.compact_group], 1, 1);
                ctx.submit(encoder);
            })?;
            start += len;
            progress.advance(Stage::Photons, u64::from(start), u64::from(total));
        }
        Ok(())
    }

    /// The per-workgroup tallies of the last pass.
    pub fn tallies(&self) -> &wgpu::Buffer {
        &self.tallies
    }

    /// What the last pass did (waits for the device and reads its tallies).
    pub fn stats(&self, ctx: &GpuContext) -> Result<TraceStats, BackendError> {
        read_stats(ctx, &self.tallies)
    }

    /// The last pass's photon map, in canonical order (waits for the device).
    pub fn read_map(&self, ctx: &GpuContext) -> Result<prismatic_core::PhotonMap, BackendError> {
        let stored = self.stored(ctx)?;
        Ok(prismatic_core::PhotonMap { photons: self.photons.read(ctx, stored)?, stats: self.stats(ctx)? })
    }

    /// Waits for the pass and reads its photon count; an error when the
    /// map overflowed.
    pub fn stored(&self, ctx: &GpuContext) -> Result<u32, BackendError> {
        let stored = u32::from_le_bytes(ctx.read(&self.cursor, 0, 4)?[..4].try_into().expect("4 bytes"));
        if stored > self.photons.capacity {
            return Err(BackendError::OutOfMemory(format!(
                "{stored} caustic photons do not fit the device's photon map ({} photons: {} bindings of at most {} \
                 photons); trace fewer photons, use --wavelengths random_band, or use --backend cpu",
                self.photons.capacity,
                crate::shaders::WINDOWS,
                self.photons.window
            )));
        }
        Ok(stored)
    }
}

/// Workgroups a dispatch of `groups` runs: x·y of its 2D grid (one tally each).
fn dispatched_groups(groups: u64) -> u64 {
    let max = u64::from(MAX_WORKGROUPS);
    groups.min(max) * groups.div_ceil(max)
}

/// Adds the workgroups' tallies of the last pass up in u64 and f64 (waits
/// for the device).
fn read_stats(ctx: &GpuContext, tallies: &wgpu::Buffer) -> Result<TraceStats, BackendError> {
    let bytes = ctx.read(tallies, 0, tallies.size())?;
    let mut s = TraceStats::default();
    for t in bytemuck::pod_collect_to_vec::<u8, Tally>(&bytes) {
        let [emitted, paths, segments, specular, stored] = t.counts.map(u64::from);
        s.emitted += emitted;
        s.paths += paths;
        s.segments += segments;
        s.specular_paths += specular;
        s.stored += stored;
        let [fe, fs, fx, fd, fl, fa] = t.flux.map(f64::from);
        s.flux_emitted += fe;
        s.flux_stored += fs;
        s.flux_escaped += fx;
        s.flux_direct += fd;
        s.flux_depth_limited += fl;
        s.flux_absorbed += fa;
    }
    Ok(s)
}

#[cfg(test)]
mod tests {
    use crate::scene::{EncodedScene, SceneBuffers};
    use bytemuck::{Pod, Zeroable};
    use glam::Vec3;
    use prismatic_conformance::scenes::lit_by_every_light_kind;
    use prismatic_core::PreparedScene;
    use prismatic_core::model::scene::PhotonSequence;
    use prismatic_core::photons::emit::emit;
    use wgpu::util::DeviceExt;

    /// `emit.wgsl`'s `emit` for photons 0..N, one per invocation.
    const ENTRY: &str = r#"
struct EmitOut {
    origin: vec3<f32>,
    light: u32,
    direction: vec3<f32>,
    weight: f32,
}

@group(1) @binding(0) var<storage, read_write> emitted: array<EmitOut>;

@compute @workgroup_size(64)
fn emit_twin(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= arrayLength(&emitted) {
        return;
    }
    let e = emit(params.seed, id.x);
    emitted[id.x] = EmitOut(e.origin, e.light, e.direction, e.weight);
}
"#;

    #[repr(C)]
    #[derive(Clone, Copy, Debug, Pod, Zeroable)]
    struct EmitOut {
        origin: [f32; 3],
        light: u32,
        direction: [f32; 3],
        weight: f32,
    }

    /// The WGSL's emission of photons 0..n of `scene`.
    fn wgsl_emit(ctx: &crate::GpuContext, scene: &PreparedScene, n: u32) -> Vec<EmitOut> {
        let device = &ctx.device;
        let scene_layout = crate::pipelines::scene_layout(device);
        let buffers = SceneBuffers::upload(ctx, &scene_layout, &EncodedScene::new(scene));
        let out_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("emit twin"),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::COMPUTE,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Storage { read_only: false },
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            }],
        });
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("emit twin"),
            source: wgpu::ShaderSource::Wgsl([crate::shaders::emission(), ENTRY.into()].concat().into()),
        });
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("emit twin"),
            bind_group_layouts: &[Some(&scene_layout), Some(&out_layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("emit twin"),
            layout: Some(&layout),
            module: &module,
            entry_point: Some("emit_twin"),
            compilation_options: Default::default(),
            cache: None,
        });
        let size = u64::from(n) * size_of::<EmitOut>() as u64;
        let output = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("emit twin answers"),
            contents: &vec![0u8; size as usize],
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        });
        let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("emit twin"),
            layout: &out_layout,
            entries: &[wgpu::BindGroupEntry { binding: 0, resource: output.as_entire_binding() }],
        });
        let mut encoder = device.create_command_encoder(&Default::default());
        {
            let mut pass = encoder.begin_compute_pass(&Default::default());
            pass.set_pipeline(&pipeline);
            pass.set_bind_group(0, Some(&buffers.bind_group), &[]);
            pass.set_bind_group(1, Some(&group), &[]);
            pass.dispatch_workgroups(n.div_ceil(64), 1, 1);
        }
        ctx.submit(encoder);
        bytemuck::pod_collect_to_vec(&ctx.read(&output, 0, size).unwrap())
    }

    /// `emit.wgsl` is the core's `emit`: for 4,096 photons from every light
    /// kind, with and without projection maps, Sobol and random numbers,
    /// the same light and weight, and origins and directions within a few
    /// ulps (the shader compiler may fuse multiply-adds).
    #[test]
    fn wgsl_emission_is_the_cores() {
        let Some(ctx) = crate::test_context("the WGSL emission twin") else { return };
        let n = 4096;
        for (projection_maps, sequence) in
            [(false, PhotonSequence::Sobol), (true, PhotonSequence::Sobol), (true, PhotonSequence::Random)]
        {
            let scene = lit_by_every_light_kind(projection_maps, sequence);
            let seed = EncodedScene::new(&scene).params.seed;
            for (i, got) in wgsl_emit(&ctx, &scene, n).iter().enumerate() {
                let want = emit(&scene, seed, i as u32);
                let scale = 1.0 + want.origin.abs().max_element();
                let close = (Vec3::from(got.origin) - want.origin).abs().max_element() <= 2e-6 * scale
                    && (Vec3::from(got.direction) - want.direction).abs().max_element() <= 2e-6
                    && (got.weight - want.weight).abs() <= 2e-6 * want.weight.abs().max(1.0);
                assert!(
                    got.light as usize == want.light && close,
                    "photon {i} (projection maps {projection_maps}, {sequence:?}): {got:?}, the core says {want:?}"
                );
            }
        }
    }
}
