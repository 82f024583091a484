//! The scene's entities, mirrored into a prismatic scene: the components
//! an app puts on its entities, and the system that turns them (placed by
//! their global transforms) into a validated `PreparedScene` when they
//! change. Objects are prismatic shapes ([`CausticShape`]) or Bevy's own
//! meshes (`Mesh3d`): a [`Glass`] mesh, or a mesh drawn with a
//! [`CausticMaterial`] (a diffuse receiver of its base colour, or a metal
//! of that colour and its roughness where its `metallic` is 0.5 or more).

use crate::layer::{CausticLayer, CausticLayerView, CausticMaterial};
use crate::{CausticScene, CausticSettings, CausticStats};
use bevy::camera::{Camera as BevyCamera, Projection};
use bevy::ecs::system::SystemParam;
use bevy::mesh::{Indices, VertexAttributeValues};
use bevy::prelude::*;
use prismatic_core::model::dispersion::Dispersion;
use prismatic_core::model::scene::{
    Camera, Checker, Light, Material, MaterialKind, Object, RenderSettings, Scene, Shape, ThinFilm,
};
use prismatic_core::{MetalColor, PreparedScene, Vec3 as CoreVec3};
use std::collections::HashMap;
use std::sync::Arc;

/// The view prismatic renders: the entity's position, looking along its
/// forward axis (−Z) with its up axis (+Y).
#[derive(Component, Clone, Copy, Debug, PartialEq)]
pub struct CausticCamera {
    /// Vertical field of view in degrees.
    pub fov_deg: f32,
}

/// A light that casts caustics, at the entity's position.
#[derive(Component, Clone, Copy, Debug, PartialEq)]
pub enum CausticLight {
    /// The paper's spot light, along the entity's forward axis (−Z).
    Spot {
        /// Half-angle of the cone in degrees.
        cone_deg: f32,
        /// Flux in W.
        power: f32,
    },
    /// A point light.
    Point {
        /// Flux in W.
        power: f32,
    },
}

/// An object's geometry in the entity's local space (prismatic's shapes;
/// the entity's transform places it; scales should be uniform).
#[derive(Component, Clone, Debug, PartialEq)]
pub struct CausticShape(pub Shape);

/// The object is a smooth dispersive dielectric: its [`CausticShape`], or
/// else its `Mesh3d` (Bevy's mesh with its vertex normals, its vertices
/// welded where they repeat along UV seams).
#[derive(Component, Clone, Debug, PartialEq)]
pub struct Glass {
    /// Its index of refraction n(λ).
    pub dispersion: Dispersion,
    /// A thin film on its surface (a coated lens, a soap film): reflects
    /// in the film's colours. `None`: bare glass.
    pub film: Option<ThinFilm>,
    /// glTF's perceptual roughness, 0 (polished) to 1: frosted glass
    /// spreads its caustic into a glow.
    pub roughness: f32,
}

/// The object is a diffuse surface that catches caustics.
#[derive(Component, Clone, Debug, PartialEq)]
pub struct Receiver {
    /// Albedo per linear RGB channel.
    pub albedo: CoreVec3,
    /// An optional checker texture.
    pub checker: Option<Checker>,
}

fn core(v: Vec3) -> CoreVec3 {
    CoreVec3::new(v.x, v.y, v.z)
}

/// Turns a unit normal by `t` as normals turn: by the inverse transpose,
/// which keeps them normal across a non-uniform scale (zero stays zero).
fn normal_to_world(t: &GlobalTransform) -> impl Fn([f32; 3]) -> CoreVec3 {
    let to_world = t.affine().matrix3.inverse().transpose();
    move |n| core((to_world * Vec3A::from_array(n)).normalize_or_zero().into())
}

/// `shape` placed by `t`.
fn placed(shape: &Shape, t: &GlobalTransform) -> Shape {
    let point = |p: CoreVec3| core(t.transform_point(Vec3::new(p.x, p.y, p.z)));
    let vector = |v: CoreVec3| core(t.affine().transform_vector3(Vec3::new(v.x, v.y, v.z)));
    let to_world = normal_to_world(t);
    let normal = |n: CoreVec3| to_world(n.to_array());
    let scale = t.scale().max_element();
    match shape {
        Shape::Sphere { center, radius } => Shape::Sphere { center: point(*center), radius: radius * scale },
        Shape::Plane { point: p, normal: n } => Shape::Plane { point: point(*p), normal: normal(*n) },
        Shape::Disk { center, normal: n, radius, inner_radius } => Shape::Disk {
            center: point(*center),
            normal: normal(*n),
            radius: radius * scale,
            inner_radius: inner_radius * scale,
        },
        Shape::Prism { vertices, extrude } => Shape::Prism { vertices: vertices.map(point), extrude: vector(*extrude) },
        Shape::Mesh { positions, triangles, uvs, normals: n, tangents } => {
            // Tangents turn as directions; a mirroring transform turns their handedness.
            let handedness = t.affine().matrix3.determinant().signum();
            Shape::Mesh {
                positions: positions.iter().copied().map(point).collect(),
                triangles: triangles.clone(),
                uvs: uvs.clone(),
                normals: n.iter().copied().map(normal).collect(),
                tangents: tangents.iter().map(|k| vector(k.truncate()).extend(k.w * handedness)).collect(),
            }
        }
    }
}

/// `mesh`'s triangles placed by `t`, with its vertex normals where it has
/// them (turned by the inverse transpose), its vertices welded where
/// position and normal repeat (along UV seams); `None` when it has no
/// positions or no longer has its data in the main world.
fn mesh_shape(mesh: &Mesh, t: &GlobalTransform) -> Option<Shape> {
    let Ok(Some(VertexAttributeValues::Float32x3(positions))) = mesh.try_attribute_option(Mesh::ATTRIBUTE_POSITION)
    else {
        return None;
    };
    let indices: Vec<usize> = match mesh.try_indices_option() {
        Ok(Some(Indices::U16(i))) => i.iter().map(|&k| usize::from(k)).collect(),
        Ok(Some(Indices::U32(i))) => i.iter().map(|&k| k as usize).collect(),
        Ok(None) => (0..positions.len()).collect(),
        Err(_) => return None,
    };
    let normals = match mesh.try_attribute_option(Mesh::ATTRIBUTE_NORMAL) {
        Ok(Some(VertexAttributeValues::Float32x3(n))) if n.len() == positions.len() => Some(n),
        _ => None,
    };
    let normal_to_world = normal_to_world(t);
    let (mut welded, mut welded_normals, mut index_of) = (Vec::new(), Vec::new(), HashMap::new());
    let remap: Vec<u32> = positions
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let normal = normals.map_or([0.0; 3], |n| n[i]);
            *index_of.entry((p.map(f32::to_bits), normal.map(f32::to_bits))).or_insert_with(|| {
                welded.push(core(t.transform_point(Vec3::from_array(*p))));
                welded_normals.push(normal_to_world(normal));
                welded.len() as u32 - 1
            })
        })
        .collect();
    // Without normals, or with a zero one (which no surface has), the mesh is flat.
    if normals.is_none() || welded_normals.contains(&CoreVec3::ZERO) {
        welded_normals.clear();
    }
    let triangles = indices
        .chunks_exact(3)
        .filter_map(|c| {
            let tri = [remap[c[0]], remap[c[1]], remap[c[2]]];
            (tri[0] != tri[1] && tri[1] != tri[2] && tri[0] != tri[2]).then_some(tri)
        })
        .collect();
    Some(Shape::Mesh { positions: welded, triangles, uvs: Vec::new(), normals: welded_normals, tangents: Vec::new() })
}

/// A mesh drawn with a [`CausticMaterial`]: a diffuse receiver.
type ReceiverMesh = (&'static MeshMaterial3d<CausticMaterial>, &'static Mesh3d, &'static GlobalTransform);

/// The entities a scene is made of.
#[derive(SystemParam)]
pub(crate) struct SceneEntities<'w, 's> {
    cameras: Query<'w, 's, (&'static CausticCamera, &'static GlobalTransform)>,
    layer_cameras: Query<
        'w,
        's,
        (Entity, &'static CausticLayer, &'static BevyCamera, &'static Projection, &'static GlobalTransform),
    >,
    lights: Query<'w, 's, (&'static CausticLight, &'static GlobalTransform)>,
    objects: Query<
        'w,
        's,
        (&'static CausticShape, &'static GlobalTransform, Option<&'static Glass>, Option<&'static Receiver>),
    >,
    glass_meshes: Query<'w, 's, (&'static Glass, &'static Mesh3d, &'static GlobalTransform), Without<CausticShape>>,
    receiver_meshes: Query<'w, 's, ReceiverMesh, (Without<CausticShape>, Without<Glass>)>,
    meshes: Res<'w, Assets<Mesh>>,
    materials: Res<'w, Assets<CausticMaterial>>,
}

/// The scene's view: its camera, image size and, for a layer, Bevy's view.
struct SceneView {
    camera: Camera,
    size: (u32, u32),
    layer: Option<CausticLayerView>,
}

/// The scene's view: a [`CausticLayer`] camera's (its view, vertical field
/// of view, target size and near plane), else the [`CausticCamera`].
fn scene_view(settings: &CausticSettings, entities: &SceneEntities) -> Result<SceneView, String> {
    let view = |at: &GlobalTransform, fov_deg| Camera {
        position: core(at.translation()),
        look_at: core(at.translation() + at.forward().as_vec3()),
        up: core(at.up().as_vec3()),
        fov_deg,
    };
    if let Some((entity, layer, camera, projection, at)) = entities.layer_cameras.iter().next() {
        let Projection::Perspective(p) = projection else {
            return Err("the CausticLayer camera needs a perspective projection".into());
        };
        let size = camera.physical_target_size().ok_or("the CausticLayer camera's target has no size yet")?;
        let layer = CausticLayerView {
            camera: entity,
            near: p.near,
            history: layer.history,
            moving_history: layer.moving_history,
            lux_per_watt: layer.lux_per_watt,
        };
        return Ok(SceneView { camera: view(at, p.fov.to_degrees()), size: (size.x, size.y), layer: Some(layer) });
    }
    let (camera, at) = entities.cameras.iter().next().ok_or("no entity has a CausticCamera or a CausticLayer")?;
    Ok(SceneView { camera: view(at, camera.fov_deg), size: (settings.0.width, settings.0.height), layer: None })
}

/// The scene the entities make (and the layer's view, if any), or why it is not valid.
fn build_scene(
    settings: &CausticSettings,
    entities: &SceneEntities,
) -> Result<(Scene, Option<CausticLayerView>), String> {
    let SceneView { camera, size: (width, height), layer } = scene_view(settings, entities)?;
    let SceneEntities { lights, objects, glass_meshes, receiver_meshes, meshes, materials, .. } = entities;
    let lights = lights
        .iter()
        .map(|(light, at)| match *light {
            CausticLight::Spot { cone_deg, power } => Light::Spot {
                position: core(at.translation()),
                direction: core(at.forward().as_vec3()),
                cone_deg,
                inner_cone_deg: cone_deg,
                power,
                spectrum: Default::default(),
                range: None,
            },
            CausticLight::Point { power } => {
                Light::Point { position: core(at.translation()), power, spectrum: Default::default(), range: None }
            }
        })
        .collect();
    let mut scene_materials = Vec::new();
    let mut scene_objects = Vec::new();
    for (i, (shape, at, glass, receiver)) in objects.iter().enumerate() {
        let kind = match (glass, receiver) {
            (Some(g), None) => MaterialKind::Dielectric {
                dispersion: g.dispersion.clone(),
                outside: Dispersion::Constant(1.0),
                attenuation: None,
                thin: false,
                film: g.film,
                roughness: g.roughness,
            },
            (None, Some(r)) => MaterialKind::Diffuse {
                albedo: r.albedo,
                checker: r.checker.clone(),
                texture: None,
                emission: CoreVec3::ZERO,
            },
            _ => return Err(format!("object {i} needs exactly one of Glass and Receiver")),
        };
        scene_objects.push(Object { shape: placed(&shape.0, at), material: scene_materials.len() });
        scene_materials.push(Material { name: format!("object{i}"), kind, normal_map: None, roughness_map: None });
    }
    let mesh = |handle: &Mesh3d, at, what: &str| {
        meshes.get(&handle.0).and_then(|m| mesh_shape(m, at)).ok_or(format!("{what}'s mesh has no positions here"))
    };
    for (i, (glass, handle, at)) in glass_meshes.iter().enumerate() {
        let kind = MaterialKind::Dielectric {
            dispersion: glass.dispersion.clone(),
            outside: Dispersion::Constant(1.0),
            attenuation: None,
            thin: false,
            film: glass.film,
            roughness: glass.roughness,
        };
        scene_objects.push(Object { shape: mesh(handle, at, "a Glass mesh")?, material: scene_materials.len() });
        scene_materials.push(Material { name: format!("glass mesh {i}"), kind, normal_map: None, roughness_map: None });
    }
    for (i, (material, handle, at)) in receiver_meshes.iter().enumerate() {
        let Some(m) = materials.get(&material.0) else { continue };
        let c = m.base.base_color.to_linear();
        let color = CoreVec3::new(c.red, c.green, c.blue);
        // A metallic surface reflects the photons on, as glTF's metals do
        // (`gltf_scene`'s rule); any other is a receiver of its diffuse share.
        let kind = if m.base.metallic >= 0.5 {
            MaterialKind::Metal {
                color: MetalColor::Rgb(color.clamp(CoreVec3::ZERO, CoreVec3::ONE)),
                roughness: m.base.perceptual_roughness.clamp(0.0, 1.0),
            }
        } else {
            let albedo = color * (1.0 - m.base.metallic);
            MaterialKind::Diffuse { albedo, checker: None, texture: None, emission: CoreVec3::ZERO }
        };
        scene_objects
            .push(Object { shape: mesh(handle, at, "a CausticMaterial mesh")?, material: scene_materials.len() });
        scene_materials.push(Material {
            name: format!("receiver mesh {i}"),
            kind,
            normal_map: None,
            roughness_map: None,
        });
    }
    // A layer's irradiance is in Bevy's photometric units; an image's pixels in the settings' exposure.
    let exposure = layer.map_or(settings.0.exposure, |l| l.lux_per_watt);
    let render = RenderSettings { width, height, exposure, ..settings.0.clone() };
    Ok((Scene { render, camera, lights, materials: scene_materials, objects: scene_objects }, layer))
}

/// Mirrors the entities into [`CausticScene`] when the scene they make
/// differs from the last one; an invalid scene is reported in
/// [`CausticStats`] and the last valid one kept.
pub(crate) fn mirror_scene(
    mut commands: Commands,
    settings: Res<CausticSettings>,
    current: Option<Res<CausticScene>>,
    stats: Res<CausticStats>,
    current_layer: Option<Res<CausticLayerView>>,
    mut last: Local<Option<Scene>>,
    entities: SceneEntities,
) {
    let (scene, layer) = match build_scene(&settings, &entities) {
        Ok(built) => built,
        Err(e) => return stats.set(|s| s.error = Some(e)),
    };
    match layer {
        Some(layer) if current_layer.as_deref() != Some(&layer) => commands.insert_resource(layer),
        None if current_layer.is_some() => commands.remove_resource::<CausticLayerView>(),
        _ => {}
    }
    if last.as_ref() == Some(&scene) {
        return;
    }
    *last = Some(scene.clone());
    // From the last prepared scene: meshes that did not change keep their
    // hierarchies (shared, or refitted where their vertices moved).
    let prepared = match &current {
        Some(c) => c.scene.update(scene),
        None => PreparedScene::new(scene),
    };
    match prepared {
        Ok(prepared) => {
            let generation = current.map_or(1, |c| c.generation + 1);
            commands.insert_resource(CausticScene { scene: Arc::new(prepared), generation });
        }
        Err(e) => stats.set(|s| s.error = Some(format!("invalid scene: {e}"))),
    }
}
