//! Bind-group layouts and compute pipelines of every stage, compiled once
//! per backend and shared by its renders (the view pipeline once per
//! view-ray stack size, the texture copy once per texel format).

use crate::shaders::{self, MAX_WORKGROUPS, WINDOWS};
use std::collections::HashMap;
use std::sync::Mutex;

/// What a binding holds.
#[derive(Clone, Copy)]
enum Slot {
    Uniform,
    Read,
    ReadWrite,
    Texture(wgpu::TextureFormat),
    /// A depth texture read by texel (multisampled or not).
    Depth {
        multisampled: bool,
    },
    /// A float texture read by texel (not filtered; multisampled or not).
    Sampled {
        multisampled: bool,
    },
}

fn layout(device: &wgpu::Device, label: &str, slots: &[Slot]) -> wgpu::BindGroupLayout {
    let entries: Vec<wgpu::BindGroupLayoutEntry> = slots
        .iter()
        .enumerate()
        .map(|(i, slot)| wgpu::BindGroupLayoutEntry {
            binding: i as u32,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: match *slot {
                Slot::Uniform => wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                Slot::Read | Slot::ReadWrite => wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Storage { read_only: matches!(slot, Slot::Read) },
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                Slot::Texture(format) => wgpu::BindingType::StorageTexture {
                    access: wgpu::StorageTextureAccess::WriteOnly,
                    format,
                    view_dimension: wgpu::TextureViewDimension::D2,
                },
                Slot::Depth { multisampled } => wgpu::BindingType::Texture {
                    sample_type: wgpu::TextureSampleType::Depth,
                    view_dimension: wgpu::TextureViewDimension::D2,
                    multisampled,
                },
                Slot::Sampled { multisampled } => wgpu::BindingType::Texture {
                    sample_type: wgpu::TextureSampleType::Float { filterable: false },
                    view_dimension: wgpu::TextureViewDimension::D2,
                    multisampled,
                },
            },
            count: None,
        })
        .collect();
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor { label: Some(label), entries: &entries })
}

/// Bind group 0 of every stage that reads the scene: the parameters and
/// the six scene buffers (`scene.wgsl`).
pub fn scene_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    use Slot::*;
    layout(device, "prismatic scene", &[Uniform, Read, Read, Read, Read, Read, Read])
}

fn with_windows(mut slots: Vec<Slot>, slot: Slot) -> Vec<Slot> {
    slots.extend((0..WINDOWS).map(|_| slot));
    slots
}

fn pipeline(
    device: &wgpu::Device,
    label: &str,
    source: &str,
    entry: &str,
    layouts: &[&wgpu::BindGroupLayout],
) -> wgpu::ComputePipeline {
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(label),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    let groups: Vec<Option<&wgpu::BindGroupLayout>> = layouts.iter().map(|l| Some(*l)).collect();
    let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(label),
        bind_group_layouts: &groups,
        immediate_size: 0,
    });
    device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some(label),
        layout: Some(&layout),
        module: &module,
        entry_point: Some(entry),
        compilation_options: Default::default(),
        cache: None,
    })
}

/// A texture copy's layout and pipeline.
pub type TextureCopy = (wgpu::BindGroupLayout, wgpu::ComputePipeline);

/// Every layout and pipeline of the backend.
pub struct Pipelines {
    /// Group 0 of trace and view: params and the scene's six buffers.
    pub scene_layout: wgpu::BindGroupLayout,
    /// Group 1 of trace: scratch photons, counts, tallies.
    pub trace_layout: wgpu::BindGroupLayout,
    /// Compaction: params, scratch, counts, offsets, cursor, chunk total, map windows.
    pub compact_layout: wgpu::BindGroupLayout,
    /// Prefix sum: its params, data, block sums.
    pub scan_layout: wgpu::BindGroupLayout,
    /// Grid: params, cells, cursor, map windows, sorted windows, widest bucket.
    pub grid_layout: wgpu::BindGroupLayout,
    /// Group 1 of the view: pixels, visible points, points appended.
    pub view_layout: wgpu::BindGroupLayout,
    /// Group 0 of a session's passes: params, bands, cells, points appended, visible points, pixels, sorted windows.
    pub gather_layout: wgpu::BindGroupLayout,
    /// Group 1 of a session's passes: sums, base pixels, session params, levels used, statistics, level lists.
    pub session_layout: wgpu::BindGroupLayout,
    /// The gathers' dispatch arguments: points per level, the arguments.
    pub level_dispatch_layout: wgpu::BindGroupLayout,
    /// The tally fold: tallies, statistics.
    pub stats_layout: wgpu::BindGroupLayout,
    /// Group 1 of light tracing: the pixels' sums, the stored count, map windows.
    pub splat_layout: wgpu::BindGroupLayout,
    /// Group 1 of the caustic layer: light tracing's, then the engine's frame.
    pub layer_layout: wgpu::BindGroupLayout,
    /// An engine's frame from its textures: parameters, depth, normals, the
    /// frame; single-sampled textures, then multisampled ones.
    pub frame_layouts: [wgpu::BindGroupLayout; 2],
    /// A layer's history: parameters, image, history, previous and current frames.
    pub history_layout: wgpu::BindGroupLayout,
    /// Emit + trace.
    pub trace: wgpu::ComputePipeline,
    /// Compaction scatter.
    pub compact: wgpu::ComputePipeline,
    /// Cursor advance after a chunk.
    pub advance: wgpu::ComputePipeline,
    /// Per-block scan.
    pub scan_blocks: wgpu::ComputePipeline,
    /// Block offsets added back.
    pub scan_add: wgpu::ComputePipeline,
    /// Photons per bucket.
    pub grid_count: wgpu::ComputePipeline,
    /// Photons into bucket order.
    pub grid_scatter: wgpu::ComputePipeline,
    /// The widest bucket's size.
    pub grid_widest: wgpu::ComputePipeline,
    /// session.wgsl `list_points`: the points listed by grid level.
    pub list_points: wgpu::ComputePipeline,
    /// level_dispatch.wgsl: the indirect arguments of each level's gather.
    pub level_dispatches: wgpu::ComputePipeline,
    /// session.wgsl `first_radius`: first radii from the pilot's gather.
    pub first_radius: wgpu::ComputePipeline,
    /// session.wgsl `begin_pass`: sums emptied, this pass's radii.
    pub begin_pass: wgpu::ComputePipeline,
    /// session.wgsl `gather_level`: a pass's gather at one grid level's points on diffuse surfaces.
    pub gather_level: wgpu::ComputePipeline,
    /// session.wgsl `gather_rough_level`: the same at its points on rough metal and glass.
    pub gather_rough_level: wgpu::ComputePipeline,
    /// session.wgsl `accumulate`: the pass added to the pixels' sums.
    pub accumulate: wgpu::ComputePipeline,
    /// session.wgsl `show`: the pixels' base plus mean caustic.
    pub show: wgpu::ComputePipeline,
    /// session.wgsl `add_view`: a sampled pass's own view added to the pixels' sums.
    pub add_view: wgpu::ComputePipeline,
    /// stats.wgsl `fold_tallies`: a pass's tallies added to the statistics.
    pub fold_tallies: wgpu::ComputePipeline,
    /// splat.wgsl `splat`: light tracing, the photons added to the pixels' sums.
    pub splat: wgpu::ComputePipeline,
    /// layer.wgsl `layer_splat`: the photons added to the sums of an engine's frame.
    pub layer_splat: wgpu::ComputePipeline,
    /// frame.wgsl `frame_from_textures`: an engine's depth and normal
    /// textures into the layer's frame; single-sampled, then multisampled.
    pub frame_from_textures: [wgpu::ComputePipeline; 2],
    /// history.wgsl `blend_history`: a layer's frame folded into each pixel's running mean.
    pub blend_history: wgpu::ComputePipeline,
    view: Mutex<HashMap<u32, wgpu::ComputePipeline>>,
    texture: Mutex<HashMap<wgpu::TextureFormat, TextureCopy>>,
}

impl Pipelines {
    /// Compiles every stage's pipeline.
    pub fn new(device: &wgpu::Device) -> Self {
        use Slot::*;
        let scene_layout = scene_layout(device);
        let trace_layout = layout(device, "prismatic trace", &[ReadWrite, ReadWrite, ReadWrite]);
        let compact_layout = layout(
            device,
            "prismatic compact",
            &with_windows(vec![Uniform, Read, Read, Read, ReadWrite, Read], ReadWrite),
        );
        let scan_layout = layout(device, "prismatic scan", &[Uniform, ReadWrite, ReadWrite]);
        let grid_layout = layout(
            device,
            "prismatic grid",
            &[with_windows(with_windows(vec![Uniform, ReadWrite, ReadWrite], Read), ReadWrite), vec![ReadWrite]]
                .concat(),
        );
        let view_layout = layout(device, "prismatic view", &[ReadWrite, ReadWrite, ReadWrite, Read]);
        let gather_layout = layout(
            device,
            "prismatic gather",
            &[with_windows(vec![Uniform, Read, Read, Read, ReadWrite, ReadWrite], Read), vec![Read; 4]].concat(),
        );
        let session_layout = layout(
            device,
            "prismatic session",
            &[ReadWrite, Read, Uniform, ReadWrite, ReadWrite, ReadWrite, ReadWrite],
        );
        let level_dispatch_layout = layout(device, "prismatic level dispatches", &[Read, ReadWrite]);
        let stats_layout = layout(device, "prismatic statistics", &[Read, ReadWrite]);
        let splat_layout = layout(device, "prismatic light tracing", &with_windows(vec![ReadWrite, Read], Read));
        let layer_layout = layout(
            device,
            "prismatic caustic layer",
            &[with_windows(vec![ReadWrite, Read], Read), vec![Read]].concat(),
        );
        let frame_layouts = [false, true].map(|multisampled| {
            let textures = [Depth { multisampled }, Sampled { multisampled }];
            layout(device, "prismatic engine frame", &[&[Uniform][..], &textures, &[ReadWrite]].concat())
        });
        let history_layout = layout(device, "prismatic layer history", &[Uniform, ReadWrite, ReadWrite, Read, Read]);
        let session_src = shaders::session();
        let session =
            |label: &str, entry: &str| pipeline(device, label, &session_src, entry, &[&gather_layout, &session_layout]);
        let trace_src = shaders::trace();
        let compact_src = shaders::compact();
        let scan_src = shaders::scan();
        let grid_src = shaders::grid();
        Pipelines {
            trace: pipeline(device, "prismatic trace", &trace_src, "main", &[&scene_layout, &trace_layout]),
            compact: pipeline(device, "prismatic compact", &compact_src, "scatter", &[&compact_layout]),
            advance: pipeline(device, "prismatic advance", &compact_src, "advance", &[&compact_layout]),
            scan_blocks: pipeline(device, "prismatic scan", &scan_src, "scan_blocks", &[&scan_layout]),
            scan_add: pipeline(device, "prismatic scan add", &scan_src, "add_sums", &[&scan_layout]),
            grid_count: pipeline(device, "prismatic grid count", &grid_src, "count", &[&grid_layout]),
            grid_scatter: pipeline(device, "prismatic grid scatter", &grid_src, "scatter", &[&grid_layout]),
            grid_widest: pipeline(device, "prismatic grid widest", &grid_src, "widest", &[&grid_layout]),
            first_radius: session("prismatic first radius", "first_radius"),
            begin_pass: session("prismatic begin pass", "begin_pass"),
            list_points: session("prismatic list points", "list_points"),
            level_dispatches: pipeline(
                device,
                "prismatic level dispatches",
                &shaders::level_dispatch(),
                "level_dispatches",
                &[&level_dispatch_layout],
            ),
            gather_level: session("prismatic gather level", "gather_level"),
            gather_rough_level: session("prismatic rough gather level", "gather_rough_level"),
            accumulate: session("prismatic accumulate", "accumulate"),
            show: session("prismatic show", "show"),
            add_view: session("prismatic add view", "add_view"),
            fold_tallies: pipeline(
                device,
                "prismatic fold tallies",
                &shaders::stats(),
                "fold_tallies",
                &[&stats_layout],
            ),
            splat: pipeline(
                device,
                "prismatic light tracing",
                &shaders::splat(),
                "splat",
                &[&scene_layout, &splat_layout],
            ),
            layer_splat: pipeline(
                device,
                "prismatic caustic layer",
                &shaders::layer(),
                "layer_splat",
                &[&scene_layout, &layer_layout],
            ),
            frame_from_textures: [false, true].map(|multisampled| {
                let layout = &frame_layouts[usize::from(multisampled)];
                let source = shaders::frame(multisampled);
                pipeline(device, "prismatic engine frame", &source, "frame_from_textures", &[layout])
            }),
            blend_history: pipeline(
                device,
                "prismatic layer history",
                &shaders::history(),
                "blend_history",
                &[&history_layout],
            ),
            scene_layout,
            trace_layout,
            compact_layout,
            scan_layout,
            grid_layout,
            view_layout,
            gather_layout,
            session_layout,
            level_dispatch_layout,
            stats_layout,
            splat_layout,
            layer_layout,
            frame_layouts,
            history_layout,
            view: Mutex::new(HashMap::new()),
            texture: Mutex::new(HashMap::new()),
        }
    }

    /// The view pipeline for a view-ray stack of `stack` entries.
    pub fn view(&self, device: &wgpu::Device, stack: u32) -> wgpu::ComputePipeline {
        let mut cache = self.view.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
        cache
            .entry(stack)
            .or_insert_with(|| {
                let layouts = [&self.scene_layout, &self.view_layout];
                pipeline(device, "prismatic view", &shaders::view(stack), "main", &layouts)
            })
            .clone()
    }

    /// The copy into a storage texture of `format`, with its layout; `None`
    /// for formats the copy does not write.
    pub fn texture_copy(&self, device: &wgpu::Device, format: wgpu::TextureFormat) -> Option<TextureCopy> {
        let name = match format {
            wgpu::TextureFormat::Rgba32Float => "rgba32float",
            wgpu::TextureFormat::Rgba16Float => "rgba16float",
            wgpu::TextureFormat::Rgba8Unorm => "rgba8unorm",
            _ => return None,
        };
        let mut cache = self.texture.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
        Some(
            cache
                .entry(format)
                .or_insert_with(|| {
                    use Slot::*;
                    let layout = layout(device, "prismatic to texture", &[Uniform, Read, Texture(format)]);
                    let p = pipeline(device, "prismatic to texture", &shaders::to_texture(name), "main", &[&layout]);
                    (layout, p)
                })
                .clone(),
        )
    }
}

/// Records one compute pass of `pipeline` over `invocations` invocations of
/// `group_size` (workgroups beyond the per-dimension limit wrap into y).
pub fn dispatch(
    encoder: &mut wgpu::CommandEncoder,
    pipeline: &wgpu::ComputePipeline,
    groups: &[&wgpu::BindGroup],
    invocations: u64,
    group_size: u32,
) {
    if invocations == 0 {
        return;
    }
    let workgroups = invocations.div_ceil(u64::from(group_size));
    let max = u64::from(MAX_WORKGROUPS);
    let (x, y) = (workgroups.min(max) as u32, workgroups.div_ceil(max) as u32);
    let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor { label: None, timestamp_writes: None });
    pass.set_pipeline(pipeline);
    for (i, g) in groups.iter().enumerate() {
        pass.set_bind_group(i as u32, Some(*g), &[]);
    }
    pass.dispatch_workgroups(x, y, 1);
}

/// Dispatches `pipeline` with the workgroup counts (x, y, z as u32) that
/// `args` holds at `offset`, written there by an earlier dispatch.
pub fn dispatch_indirect(
    encoder: &mut wgpu::CommandEncoder,
    pipeline: &wgpu::ComputePipeline,
    groups: &[&wgpu::BindGroup],
    args: &wgpu::Buffer,
    offset: u64,
) {
    let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor { label: None, timestamp_writes: None });
    pass.set_pipeline(pipeline);
    for (i, g) in groups.iter().enumerate() {
        pass.set_bind_group(i as u32, Some(*g), &[]);
    }
    pass.dispatch_workgroups_indirect(args, offset);
}
