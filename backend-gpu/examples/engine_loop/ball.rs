//! The scene the engine examples and the caustic layer's tests share, in
//! prismatic's terms: a dispersive glass ball on a grey floor under a spot
//! light aimed at the ball, seen by the engine's camera.

use prismatic_core::model::dispersion::Dispersion;
use prismatic_core::model::scene::{Camera, Light, Material, MaterialKind, Object, RenderSettings, Scene, Shape};
use prismatic_core::{PreparedScene, Vec3};

/// The ball's centre (radius 1, resting on the floor y = 0).
pub const CENTRE: Vec3 = Vec3::new(0.0, 1.0, 0.0);

/// The engine's camera, which prismatic's scene shares.
pub fn camera() -> Camera {
    Camera { position: Vec3::new(4.2, 2.6, 3.4), look_at: Vec3::new(0.4, 0.3, 0.0), up: Vec3::Y, fov_deg: 42.0 }
}

/// A 38 W spot light at `position`, aimed at the ball's centre, of half-angle `cone_deg`.
pub fn spot(position: Vec3, cone_deg: f32) -> Light {
    Light::Spot {
        position,
        direction: CENTRE - position,
        cone_deg,
        inner_cone_deg: cone_deg,
        power: 38.0,
        spectrum: Default::default(),
        range: None,
    }
}

/// The floor and (`with_ball`) the ball under `light`, rendered with `render`;
/// without the ball, the frame an engine's prepass draws (glass is
/// transparent to it).
pub fn scene(render: RenderSettings, light: Light, with_ball: bool) -> PreparedScene {
    let material = |name: &str, kind| Material::new(name, kind);
    let mut objects = vec![Object { shape: Shape::Plane { point: Vec3::ZERO, normal: Vec3::Y }, material: 0 }];
    if with_ball {
        objects.push(Object { shape: Shape::Sphere { center: CENTRE, radius: 1.0 }, material: 1 });
    }
    let glass = MaterialKind::Dielectric {
        dispersion: Dispersion::Paper,
        outside: Dispersion::Constant(1.0),
        attenuation: None,
        thin: false,
        film: None,
        roughness: 0.0,
    };
    PreparedScene::new(Scene {
        render,
        camera: camera(),
        lights: vec![light],
        materials: vec![
            material(
                "floor",
                MaterialKind::Diffuse { albedo: Vec3::splat(0.85), checker: None, texture: None, emission: Vec3::ZERO },
            ),
            material("glass", glass),
        ],
        objects,
    })
    .expect("a valid scene")
}
