//! The scene's entities, mirrored into a prismatic scene: the components
//! an app puts on its entities, and the system that turns them (placed by
//! their global transforms) into a validated `PreparedScene` when they change.

use crate::{CausticScene, CausticSettings, CausticStats};
use bevy::ecs::system::SystemParam;
use bevy::prelude::*;
use prismatic_core::model::dispersion::Dispersion;
use prismatic_core::model::scene::{Camera, Checker, Light, Material, MaterialKind, Object, Scene, Shape};
use prismatic_core::{PreparedScene, Vec3 as CoreVec3};
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

/// The object is a smooth dispersive dielectric.
#[derive(Component, Clone, Debug, PartialEq)]
pub struct Glass {
    /// Its index of refraction n(λ).
    pub dispersion: Dispersion,
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

/// `shape` placed by `t`.
fn placed(shape: &Shape, t: &GlobalTransform) -> Shape {
    let point = |p: CoreVec3| core(t.transform_point(Vec3::new(p.x, p.y, p.z)));
    let vector = |v: CoreVec3| core(t.affine().transform_vector3(Vec3::new(v.x, v.y, v.z)));
    let normal = |n: CoreVec3| core(t.rotation() * Vec3::new(n.x, n.y, n.z));
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
        Shape::Mesh { positions, triangles, uvs } => Shape::Mesh {
            positions: positions.iter().copied().map(point).collect(),
            triangles: triangles.clone(),
            uvs: uvs.clone(),
        },
    }
}

/// The entities a scene is made of.
#[derive(SystemParam)]
pub(crate) struct SceneEntities<'w, 's> {
    cameras: Query<'w, 's, (&'static CausticCamera, &'static GlobalTransform)>,
    lights: Query<'w, 's, (&'static CausticLight, &'static GlobalTransform)>,
    objects: Query<
        'w,
        's,
        (&'static CausticShape, &'static GlobalTransform, Option<&'static Glass>, Option<&'static Receiver>),
    >,
}

/// The scene the entities make, or why it is not valid.
fn build_scene(settings: &CausticSettings, entities: &SceneEntities) -> Result<Scene, String> {
    let SceneEntities { cameras, lights, objects } = entities;
    let (camera, at) = cameras.iter().next().ok_or("no entity has a CausticCamera")?;
    let camera = Camera {
        position: core(at.translation()),
        look_at: core(at.translation() + at.forward().as_vec3()),
        up: core(at.up().as_vec3()),
        fov_deg: camera.fov_deg,
    };
    let lights = lights
        .iter()
        .map(|(light, at)| match *light {
            CausticLight::Spot { cone_deg, power } => Light::Spot {
                position: core(at.translation()),
                direction: core(at.forward().as_vec3()),
                cone_deg,
                power,
                spectrum: Default::default(),
            },
            CausticLight::Point { power } => {
                Light::Point { position: core(at.translation()), power, spectrum: Default::default() }
            }
        })
        .collect();
    let mut materials = Vec::new();
    let mut scene_objects = Vec::new();
    for (i, (shape, at, glass, receiver)) in objects.iter().enumerate() {
        let kind = match (glass, receiver) {
            (Some(g), None) => MaterialKind::Dielectric {
                dispersion: g.dispersion.clone(),
                outside: Dispersion::Constant(1.0),
                attenuation: None,
            },
            (None, Some(r)) => MaterialKind::Diffuse { albedo: r.albedo, checker: r.checker.clone(), texture: None },
            _ => return Err(format!("object {i} needs exactly one of Glass and Receiver")),
        };
        scene_objects.push(Object { shape: placed(&shape.0, at), material: materials.len() });
        materials.push(Material { name: format!("object{i}"), kind });
    }
    Ok(Scene { render: settings.0.clone(), camera, lights, materials, objects: scene_objects })
}

/// Mirrors the entities into [`CausticScene`] when the scene they make
/// differs from the last one; an invalid scene is reported in
/// [`CausticStats`] and the last valid one kept.
pub(crate) fn mirror_scene(
    mut commands: Commands,
    settings: Res<CausticSettings>,
    current: Option<Res<CausticScene>>,
    stats: Res<CausticStats>,
    mut last: Local<Option<Scene>>,
    entities: SceneEntities,
) {
    let scene = match build_scene(&settings, &entities) {
        Ok(scene) => scene,
        Err(e) => return stats.set(|s| s.error = Some(e)),
    };
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
