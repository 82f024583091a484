//! The scene's entities, mirrored into a prismatic scene: the components
//! an app puts on its entities, and the system that turns them (placed by
//! their global transforms) into a validated `PreparedScene` when they
//! change. Objects are prismatic shapes ([`CausticShape`]) or Bevy's own
//! meshes (`Mesh3d`): a [`Glass`] mesh, or a mesh drawn with a
//! [`CausticMaterial`] (a diffuse receiver of its base colour, or a metal
//! of that colour and its roughness where it is metallic, with its maps:
//! [`crate::standard`]).

use crate::images::AppImages;
use crate::layer::{CausticLayer, CausticLayerView, CausticMaterial};
use crate::standard::{drawn, glass_normal_map};
use crate::{CausticScene, CausticSettings, CausticStats};
use bevy::camera::{Camera as BevyCamera, Projection};
use bevy::ecs::system::SystemParam;
use bevy::math::Affine2;
use bevy::mesh::{Indices, VertexAttributeValues};
use bevy::prelude::*;
use prismatic_core::model::dispersion::Dispersion;
use prismatic_core::model::scene::{
    Camera, Checker, Light, Material, MaterialKind, Object, RenderSettings, Scene, Shape, ThinFilm,
};
use prismatic_core::{PreparedScene, Vec3 as CoreVec3};
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
/// welded where they repeat along UV seams; where Bevy draws it with a
/// `StandardMaterial` that has a normal map, a water surface's ripples,
/// the glass's normals tilt by that map).
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
/// positions or no longer has its data in the main world. With
/// `uv_transform` (its material reads textures), its `UV_0` through that
/// transform and its tangents come too, and welding keeps their seams;
/// the shape has no texture coordinates when the mesh has none.
fn mesh_shape(mesh: &Mesh, t: &GlobalTransform, uv_transform: Option<Affine2>) -> Option<Shape> {
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
    let uvs = match (uv_transform, mesh.try_attribute_option(Mesh::ATTRIBUTE_UV_0)) {
        (Some(to_texture), Ok(Some(VertexAttributeValues::Float32x2(uv)))) if uv.len() == positions.len() => {
            Some(uv.iter().map(|&uv| to_texture.transform_point2(Vec2::from_array(uv)).to_array()).collect::<Vec<_>>())
        }
        _ => None,
    };
    let tangents = match mesh.try_attribute_option(Mesh::ATTRIBUTE_TANGENT) {
        Ok(Some(VertexAttributeValues::Float32x4(k))) if uvs.is_some() && k.len() == positions.len() => Some(k),
        _ => None,
    };
    let normal_to_world = normal_to_world(t);
    // Tangents turn as directions; a mirroring transform turns their handedness.
    let handedness = t.affine().matrix3.determinant().signum();
    let tangent_to_world = |k: &[f32; 4]| {
        let along = core(t.affine().transform_vector3(Vec3::new(k[0], k[1], k[2])));
        glam::Vec4::new(along.x, along.y, along.z, k[3] * handedness)
    };
    let (mut welded, mut welded_normals, mut index_of) = (Vec::new(), Vec::new(), HashMap::new());
    let (mut welded_uvs, mut welded_tangents) = (Vec::new(), Vec::new());
    let remap: Vec<u32> = positions
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let normal = normals.map_or([0.0; 3], |n| n[i]);
            let uv = uvs.as_ref().map(|uv| uv[i]);
            let tangent = tangents.map(|k| &k[i]);
            let key = (
                p.map(f32::to_bits),
                normal.map(f32::to_bits),
                uv.map(|uv| uv.map(f32::to_bits)),
                tangent.map(|k| k.map(f32::to_bits)),
            );
            *index_of.entry(key).or_insert_with(|| {
                welded.push(core(t.transform_point(Vec3::from_array(*p))));
                welded_normals.push(normal_to_world(normal));
                welded_uvs.extend(uv.map(glam::Vec2::from_array));
                welded_tangents.extend(tangent.map(tangent_to_world));
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
    Some(Shape::Mesh {
        positions: welded,
        triangles,
        uvs: welded_uvs,
        normals: welded_normals,
        tangents: welded_tangents,
    })
}

/// A [`Glass`] mesh, and the material Bevy draws it with, if any.
type GlassMesh =
    (&'static Glass, &'static Mesh3d, &'static GlobalTransform, Option<&'static MeshMaterial3d<StandardMaterial>>);

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
    glass_meshes: Query<'w, 's, GlassMesh, Without<CausticShape>>,
    receiver_meshes: Query<'w, 's, ReceiverMesh, (Without<CausticShape>, Without<Glass>)>,
    meshes: Res<'w, Assets<Mesh>>,
    materials: Res<'w, Assets<CausticMaterial>>,
    standard_materials: Option<Res<'w, Assets<StandardMaterial>>>,
    images: AppImages<'w, 's>,
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

/// The scene the entities make, the layer's view (if any) and what of the
/// app's materials it leaves out, or why it is not valid.
fn build_scene(
    settings: &CausticSettings,
    entities: &mut SceneEntities,
) -> Result<(Scene, Option<CausticLayerView>, Vec<String>), String> {
    let SceneView { camera, size: (width, height), layer } = scene_view(settings, entities)?;
    let SceneEntities {
        lights,
        objects,
        glass_meshes,
        receiver_meshes,
        meshes,
        materials,
        standard_materials,
        images,
        ..
    } = entities;
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
        scene_materials.push(Material {
            name: format!("object{i}"),
            kind,
            normal_map: None,
            roughness_map: None,
            film_map: None,
            specular_map: None,
        });
    }
    let mesh = |handle: &Mesh3d, at, what: &str, uv_transform| {
        meshes
            .get(&handle.0)
            .and_then(|m| mesh_shape(m, at, uv_transform))
            .ok_or(format!("{what}'s mesh has no positions here"))
    };
    let mut left_out = Vec::new();
    for (i, (glass, handle, at, drawn_with)) in glass_meshes.iter().enumerate() {
        let name = format!("glass mesh {i}");
        let drawn_with = drawn_with.zip(standard_materials.as_ref()).and_then(|(m, all)| all.get(&m.0));
        let normal_map = drawn_with.and_then(|m| glass_normal_map(m, &name, images, &mut left_out));
        let shape = mesh(handle, at, "a Glass mesh", normal_map.as_ref().map(|(_, to_texture)| *to_texture))?;
        let normal_map = match (&shape, normal_map) {
            (Shape::Mesh { uvs, .. }, Some(_)) if uvs.is_empty() => {
                left_out.push(format!("{name}: its normal map (its mesh has no UV_0)"));
                None
            }
            (_, map) => map.map(|(map, _)| map),
        };
        let kind = MaterialKind::Dielectric {
            dispersion: glass.dispersion.clone(),
            outside: Dispersion::Constant(1.0),
            attenuation: None,
            thin: false,
            film: glass.film,
            roughness: glass.roughness,
        };
        scene_objects.push(Object { shape, material: scene_materials.len() });
        scene_materials.push(Material { normal_map, ..Material::new(name, kind) });
    }
    for (i, (material, handle, at)) in receiver_meshes.iter().enumerate() {
        let Some(m) = materials.get(&material.0) else { continue };
        let name = format!("receiver mesh {i}");
        let drawn = drawn(&m.base, name.clone(), images, &mut left_out);
        let shape = mesh(handle, at, "a CausticMaterial mesh", drawn.uv_transform)?;
        let material = match &shape {
            Shape::Mesh { uvs, .. } if uvs.is_empty() && drawn.uv_transform.is_some() => {
                left_out.push(format!("{name}: its textures (its mesh has no UV_0)"));
                drawn.untextured()
            }
            _ => drawn.material,
        };
        scene_objects.push(Object { shape, material: scene_materials.len() });
        scene_materials.push(material);
    }
    // A layer's irradiance is in Bevy's photometric units; an image's pixels in the settings' exposure.
    let exposure = layer.map_or(settings.0.exposure, |l| l.lux_per_watt);
    let render = RenderSettings { width, height, exposure, ..settings.0.clone() };
    Ok((Scene { render, camera, lights, materials: scene_materials, objects: scene_objects }, layer, left_out))
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
    mut entities: SceneEntities,
) {
    entities.images.refresh();
    let (scene, layer, left_out) = match build_scene(&settings, &mut entities) {
        Ok(built) => built,
        Err(e) => return stats.set(|s| s.error = Some(e)),
    };
    stats.set(|s| s.left_out = left_out);
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

#[cfg(test)]
mod tests {
    use super::*;
    use bevy::asset::RenderAssetUsages;
    use bevy::ecs::message::Messages;
    use bevy::ecs::system::RunSystemOnce;
    use bevy::render::render_resource::{Extent3d, TextureDimension, TextureFormat};
    use prismatic_core::model::metalness::{Metalness, SpecularLayer};

    /// A 2×1 image of these texels.
    fn image(format: TextureFormat, texels: [[u8; 4]; 2]) -> Image {
        let size = Extent3d { width: 2, height: 1, depth_or_array_layers: 1 };
        Image::new(size, TextureDimension::D2, texels.concat(), format, RenderAssetUsages::MAIN_WORLD)
    }

    /// The scene a camera, a light and one 2×2 floor drawn with `material`
    /// make (the floor's mesh without texture coordinates where `uvs` is
    /// false), and what it leaves out.
    fn mirrored(material: impl FnOnce(&mut Assets<Image>) -> StandardMaterial, uvs: bool) -> (Scene, Vec<String>) {
        built(&mut world_of(material, uvs))
    }

    /// The world of [`mirrored`]'s scene.
    fn world_of(material: impl FnOnce(&mut Assets<Image>) -> StandardMaterial, uvs: bool) -> World {
        let mut world = World::new();
        world.insert_resource(CausticSettings::default());
        world.init_resource::<Messages<AssetEvent<Image>>>();
        world.init_resource::<Assets<Mesh>>();
        world.init_resource::<Assets<CausticMaterial>>();
        let mut images = Assets::<Image>::default();
        let base = material(&mut images);
        world.insert_resource(images);
        let mut floor = Mesh::from(Plane3d::default().mesh().size(2.0, 2.0));
        if !uvs {
            floor.remove_attribute(Mesh::ATTRIBUTE_UV_0);
        }
        let mesh = Mesh3d(world.resource_mut::<Assets<Mesh>>().add(floor));
        let material = MeshMaterial3d(
            world.resource_mut::<Assets<CausticMaterial>>().add(CausticMaterial { base, extension: default() }),
        );
        world.spawn((CausticCamera { fov_deg: 40.0 }, GlobalTransform::from_xyz(0.0, 2.0, 4.0)));
        world.spawn((CausticLight::Point { power: 10.0 }, GlobalTransform::from_xyz(0.0, 3.0, 0.0)));
        world.spawn((mesh, material, GlobalTransform::IDENTITY));
        world
    }

    /// The scene `world`'s entities make, and what it leaves out.
    fn built(world: &mut World) -> (Scene, Vec<String>) {
        let built = world
            .run_system_once(|settings: Res<CausticSettings>, mut entities: SceneEntities| {
                build_scene(&settings, &mut entities)
            })
            .unwrap()
            .unwrap();
        (built.0, built.2)
    }

    /// Texels packed as prismatic's textures hold them.
    fn packed(texels: &[[u8; 4]]) -> Vec<u32> {
        texels.iter().map(|&[r, g, b, _]| u32::from(r) | u32::from(g) << 8 | u32::from(b) << 16).collect()
    }

    fn uvs_of(scene: &Scene) -> &[glam::Vec2] {
        match &scene.objects[0].shape {
            Shape::Mesh { uvs, .. } => uvs,
            other => panic!("not a mesh: {other:?}"),
        }
    }

    /// The specular layer of Bevy's default reflectance (0.5): F0 0.04, F90 1.
    fn default_layer() -> SpecularLayer {
        SpecularLayer { f0: prismatic_core::Vec3::splat(0.16 * 0.25), f90: 1.0, ior: 1.5 }
    }

    #[test]
    fn reflectance_sets_the_specular_layer_and_zero_leaves_a_bare_diffuse_surface() {
        let (scene, _) = mirrored(|_| StandardMaterial { reflectance: 1.0, ..default() }, true);
        let MaterialKind::Metal { metalness, .. } = scene.materials[0].kind else { panic!("a layered base") };
        assert_eq!(metalness.layer.map(|l| (l.f0.x, l.f90)), Some((0.16, 1.0)), "F0 0.16 reflectance²");
        let (scene, _) = mirrored(|_| StandardMaterial { reflectance: 0.0, ..default() }, true);
        assert!(matches!(scene.materials[0].kind, MaterialKind::Diffuse { .. }), "{:?}", scene.materials[0].kind);
    }

    #[test]
    fn a_receiver_reads_its_base_colour_texture_through_its_uv_transform() {
        let texels = [[200, 100, 50, 255], [0, 0, 0, 255]];
        let (scene, left_out) = mirrored(
            |images| StandardMaterial {
                base_color_texture: Some(images.add(image(TextureFormat::Rgba8UnormSrgb, texels))),
                uv_transform: Affine2::from_scale(Vec2::splat(2.0)),
                metallic: 0.0,
                ..default()
            },
            true,
        );
        assert!(left_out.is_empty(), "{left_out:?}");
        // A non-metal: its diffuse base (the texture) under its specular layer.
        let MaterialKind::Metal { texture: Some(texture), metalness, .. } = &scene.materials[0].kind else {
            panic!("{:?}", scene.materials[0].kind)
        };
        assert_eq!(*metalness, Metalness::layered(default_layer()));
        assert_eq!(&*texture.texels, &packed(&texels));
        let largest = uvs_of(&scene).iter().fold(0.0f32, |m, uv| m.max(uv.max_element()));
        assert_eq!(largest, 2.0, "the plane's UV_0 spans 0..1, its transform doubles it");
        PreparedScene::new(scene).expect("a valid scene");
    }

    #[test]
    fn a_metallic_map_makes_a_rough_metal_coloured_by_its_base_colour_texture() {
        let (roughness, normals) =
            ([[0, 128, 255, 255], [0, 64, 255, 255]], [[128, 128, 255, 255], [128, 200, 255, 255]]);
        let (scene, left_out) = mirrored(
            |images| StandardMaterial {
                metallic: 1.0,
                perceptual_roughness: 0.8,
                metallic_roughness_texture: Some(images.add(image(TextureFormat::Rgba8Unorm, roughness))),
                normal_map_texture: Some(images.add(image(TextureFormat::Rgba8Unorm, normals))),
                flip_normal_map_y: true,
                base_color_texture: Some(images.add(image(TextureFormat::Rgba8UnormSrgb, [[200, 150, 60, 255]; 2]))),
                ..default()
            },
            true,
        );
        let material = &scene.materials[0];
        let MaterialKind::Metal { roughness: 0.8, texture: Some(colour), .. } = &material.kind else {
            panic!("a rough metal with its base colour texture: {:?}", material.kind)
        };
        assert_eq!(&*colour.texels, &packed(&[[200, 150, 60, 255]; 2]));
        assert_eq!(&*material.roughness_map.as_ref().unwrap().texels, &packed(&roughness));
        let flipped = [[128, 127, 255, 255], [128, 55, 255, 255]];
        assert_eq!(&*material.normal_map.as_ref().unwrap().texture.texels, &packed(&flipped));
        assert!(left_out.is_empty(), "{left_out:?}");
        assert!(!uvs_of(&scene).is_empty());
        PreparedScene::new(scene).expect("a valid scene");

        // Half its texels metallic: a metal blended texel by texel by its map's blue, nothing left out.
        let (scene, left_out) = mirrored(
            |images| StandardMaterial {
                metallic: 1.0,
                metallic_roughness_texture: Some(
                    images.add(image(TextureFormat::Rgba8Unorm, [[0, 255, 255, 255], [0, 255, 0, 255]])),
                ),
                ..default()
            },
            true,
        );
        let MaterialKind::Metal { metalness, .. } = scene.materials[0].kind else { panic!("a metal") };
        assert_eq!(metalness, Metalness { mapped: true, layer: Some(default_layer()), ..Metalness::WHOLE });
        assert!(left_out.is_empty(), "{left_out:?}");
        PreparedScene::new(scene).expect("a valid scene");
    }

    #[test]
    fn textures_on_a_mesh_without_uvs_or_still_loading_are_left_out() {
        let (scene, left_out) = mirrored(
            |images| StandardMaterial {
                base_color_texture: Some(images.add(image(TextureFormat::Rgba8UnormSrgb, [[9; 4]; 2]))),
                metallic: 0.0,
                ..default()
            },
            false,
        );
        assert!(matches!(scene.materials[0].kind, MaterialKind::Metal { texture: None, .. }));
        assert_eq!(left_out, ["receiver mesh 0: its textures (its mesh has no UV_0)"]);
        PreparedScene::new(scene).expect("a valid scene");
        // An image not loaded yet: drawn without it until it is, nothing said.
        let (scene, left_out) = mirrored(
            |_| StandardMaterial { base_color_texture: Some(Handle::default()), metallic: 0.0, ..default() },
            true,
        );
        assert!(matches!(scene.materials[0].kind, MaterialKind::Metal { texture: None, .. }));
        assert!(left_out.is_empty() && uvs_of(&scene).is_empty(), "{left_out:?}");
    }

    #[test]
    fn a_glass_mesh_takes_the_normal_map_bevy_draws_it_with() {
        let ripples = [[128, 128, 255, 255], [200, 128, 230, 255]];
        let mut world = world_of(|_| StandardMaterial::default(), true);
        world.init_resource::<Assets<StandardMaterial>>();
        let map = world.resource_mut::<Assets<Image>>().add(image(TextureFormat::Rgba8Unorm, ripples));
        let water = StandardMaterial {
            normal_map_texture: Some(map),
            uv_transform: Affine2::from_translation(Vec2::new(0.25, 0.0)),
            ..default()
        };
        let water = MeshMaterial3d(world.resource_mut::<Assets<StandardMaterial>>().add(water));
        let cube = Mesh3d(world.resource_mut::<Assets<Mesh>>().add(Cuboid::new(1.0, 1.0, 1.0)));
        let glass = Glass { dispersion: Dispersion::Paper, film: None, roughness: 0.0 };
        world.spawn((glass, cube, water, GlobalTransform::from_xyz(0.0, 1.0, 0.0)));
        let (scene, left_out) = built(&mut world);
        assert!(left_out.is_empty(), "{left_out:?}");
        let glass = scene.objects.iter().find(|o| scene.materials[o.material].name == "glass mesh 0").unwrap();
        let map = scene.materials[glass.material].normal_map.as_ref().expect("the water's normal map");
        assert_eq!(&*map.texture.texels, &packed(&ripples));
        let Shape::Mesh { uvs, .. } = &glass.shape else { panic!("not a mesh") };
        // The cube's UV_0 spans 0..1 on each face; the material moves it by 0.25 along u.
        let (lo, hi) = uvs.iter().fold((f32::MAX, f32::MIN), |(lo, hi), uv| (lo.min(uv.x), hi.max(uv.x)));
        assert_eq!((lo, hi), (0.25, 1.25));
        PreparedScene::new(scene).expect("a valid scene: the glass is closed across its faces' seams");
    }
}
