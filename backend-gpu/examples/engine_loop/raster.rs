//! The engine's side of a caustic layer, as a wgpu engine draws it: a depth
//! and normal prepass of its opaque triangles (reversed Z with an infinite
//! far plane and world-space normals stored as n · 0.5 + 0.5 in
//! `Rgb10a2Unorm`, as Bevy's prepass leaves them), and its floor. The
//! engine examples, the layer's tests and its frame times draw their
//! engine's frame with it.

use glam::{Mat4, Vec4};
use prismatic_core::Vec3;
use prismatic_core::model::scene::Camera;

/// The near plane of the engine's perspective.
pub const NEAR: f32 = 0.1;

/// The prepass's two targets.
pub struct Prepass {
    /// `Depth32Float`, reversed Z (1 at the near plane, 0 cleared).
    pub depth: wgpu::Texture,
    /// `Rgb10a2Unorm`, n · 0.5 + 0.5 (0 cleared).
    pub normal: wgpu::Texture,
}

const SHADER: &str = "
struct Vertex { @location(0) position: vec3<f32>, @location(1) normal: vec3<f32> }
struct Out { @builtin(position) clip: vec4<f32>, @location(0) normal: vec3<f32> }
@group(0) @binding(0) var<uniform> view_projection: mat4x4<f32>;
@vertex fn vertex(v: Vertex) -> Out {
    return Out(view_projection * vec4<f32>(v.position, 1.0), v.normal);
}
@fragment fn fragment(o: Out) -> @location(0) vec4<f32> {
    return vec4<f32>(normalize(o.normal) * 0.5 + vec3<f32>(0.5), 1.0);
}
";

/// Records the drawing of `triangles` (world space, one flat normal each)
/// as `camera` sees them at `width` × `height` pixels: the engine's depth
/// and normal prepass, its commands for the engine to submit.
pub fn prepass(
    device: &wgpu::Device,
    camera: &Camera,
    (width, height): (u32, u32),
    triangles: &[[Vec3; 3]],
) -> (Prepass, wgpu::CommandBuffer) {
    let target = |label, format| {
        device.create_texture(&wgpu::TextureDescriptor {
            label: Some(label),
            size: wgpu::Extent3d { width, height, depth_or_array_layers: 1 },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        })
    };
    let prepass = Prepass {
        depth: target("engine depth", wgpu::TextureFormat::Depth32Float),
        normal: target("engine normals", wgpu::TextureFormat::Rgb10a2Unorm),
    };
    let vertices: Vec<[f32; 6]> = triangles
        .iter()
        .flat_map(|t| {
            let n = (t[1] - t[0]).cross(t[2] - t[0]).normalize();
            t.map(|p| [p.x, p.y, p.z, n.x, n.y, n.z])
        })
        .collect();
    use wgpu::util::DeviceExt;
    let vertex_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("engine triangles"),
        contents: bytemuck::cast_slice(&vertices),
        usage: wgpu::BufferUsages::VERTEX,
    });
    let matrix = view_projection(camera, width, height).to_cols_array();
    let uniform = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("engine view projection"),
        contents: bytemuck::cast_slice(&matrix),
        usage: wgpu::BufferUsages::UNIFORM,
    });
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("engine prepass"),
        source: wgpu::ShaderSource::Wgsl(SHADER.into()),
    });
    let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("engine prepass"),
        layout: None,
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some("vertex"),
            compilation_options: Default::default(),
            buffers: &[Some(wgpu::VertexBufferLayout {
                array_stride: 24,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: &wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3],
            })],
        },
        primitive: wgpu::PrimitiveState::default(),
        depth_stencil: Some(wgpu::DepthStencilState {
            format: wgpu::TextureFormat::Depth32Float,
            depth_write_enabled: Some(true),
            depth_compare: Some(wgpu::CompareFunction::Greater),
            stencil: Default::default(),
            bias: Default::default(),
        }),
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module: &module,
            entry_point: Some("fragment"),
            compilation_options: Default::default(),
            targets: &[Some(wgpu::TextureFormat::Rgb10a2Unorm.into())],
        }),
        multiview_mask: None,
        cache: None,
    });
    let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("engine view projection"),
        layout: &pipeline.get_bind_group_layout(0),
        entries: &[wgpu::BindGroupEntry { binding: 0, resource: uniform.as_entire_binding() }],
    });
    let (depth_view, normal_view) = (view(&prepass.depth), view(&prepass.normal));
    let mut encoder = device.create_command_encoder(&Default::default());
    {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("engine prepass"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &normal_view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &depth_view,
                depth_ops: Some(wgpu::Operations { load: wgpu::LoadOp::Clear(0.0), store: wgpu::StoreOp::Store }),
                stencil_ops: None,
            }),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &bind_group, &[]);
        pass.set_vertex_buffer(0, vertex_buffer.slice(..));
        pass.draw(0..vertices.len() as u32, 0..1);
    }
    (prepass, encoder.finish())
}

/// A texture's whole view.
pub fn view(texture: &wgpu::Texture) -> wgpu::TextureView {
    texture.create_view(&Default::default())
}

/// The engine's view-projection of `camera`: a right-handed look-at and
/// the reversed-Z infinite perspective of the camera's vertical field of
/// view (glam's `look_at_rh` and `perspective_infinite_reverse_rh`, which
/// glam without `std` lacks).
pub fn view_projection(camera: &Camera, width: u32, height: u32) -> Mat4 {
    let f = 1.0 / (camera.fov_deg.to_radians() * 0.5).tan();
    let aspect = width as f32 / height as f32;
    let projection = Mat4::from_cols(
        Vec4::new(f / aspect, 0.0, 0.0, 0.0),
        Vec4::new(0.0, f, 0.0, 0.0),
        Vec4::new(0.0, 0.0, 0.0, -1.0),
        Vec4::new(0.0, 0.0, NEAR, 0.0),
    );
    let forward = (camera.look_at - camera.position).normalize();
    let side = forward.cross(camera.up).normalize();
    let up = side.cross(forward);
    let eye = camera.position;
    let view = Mat4::from_cols(
        Vec4::new(side.x, up.x, -forward.x, 0.0),
        Vec4::new(side.y, up.y, -forward.y, 0.0),
        Vec4::new(side.z, up.z, -forward.z, 0.0),
        Vec4::new(-side.dot(eye), -up.dot(eye), forward.dot(eye), 1.0),
    );
    projection * view
}

/// The engine's floor: a 60 × 60 quad at y = 0.
pub fn floor() -> [[Vec3; 3]; 2] {
    let v = Vec3::new;
    quad(v(-30.0, 0.0, -30.0), v(-30.0, 0.0, 30.0), v(30.0, 0.0, 30.0), v(30.0, 0.0, -30.0))
}

/// Two triangles of the quad with corners `a`, `b`, `c`, `d` in order.
pub fn quad(a: Vec3, b: Vec3, c: Vec3, d: Vec3) -> [[Vec3; 3]; 2] {
    [[a, b, c], [a, c, d]]
}
