//! The least a Bevy app needs for live caustics (the README quotes it):
//! the plugin, a caustic camera, a light, a floor and a glass ball, and a
//! sprite that shows the caustic image.
//!
//! `cargo run --release -p prismatic-bevy --example minimal`

use bevy::prelude::*;
use prismatic_bevy::prismatic_core::{Vec3 as V, model::dispersion::Dispersion, model::scene::Shape};
use prismatic_bevy::{CausticCamera, CausticImage, CausticLight, CausticShape, Glass, PrismaticPlugin, Receiver};

fn main() {
    App::new()
        .add_plugins((DefaultPlugins, PrismaticPlugin))
        .add_systems(Startup, scene)
        .add_systems(Update, show)
        .run();
}

fn scene(mut commands: Commands) {
    let eye = Transform::from_xyz(4.2, 2.6, 3.4).looking_at(Vec3::new(0.4, 0.3, 0.0), Vec3::Y);
    commands.spawn(Camera2d);
    commands.spawn((CausticCamera { fov_deg: 42.0 }, eye));
    let spot = Transform::from_xyz(-2.5, 6.0, -0.5).looking_at(Vec3::Y, Vec3::Y);
    commands.spawn((CausticLight::Spot { cone_deg: 40.0, power: 38.0 }, spot));
    let floor = CausticShape(Shape::Plane { point: V::ZERO, normal: V::Y });
    commands.spawn((floor, Receiver { albedo: V::splat(0.85), checker: None }, Transform::IDENTITY));
    let ball = CausticShape(Shape::Sphere { center: V::ZERO, radius: 1.0 });
    commands.spawn((
        ball,
        Glass { dispersion: Dispersion::Paper, film: None, roughness: 0.0 },
        Transform::from_xyz(0.0, 1.0, 0.0),
    ));
}

/// Shows the caustic image (the plugin makes it on its first frame).
fn show(mut commands: Commands, image: Option<Res<CausticImage>>, mut sprites: Query<&mut Sprite>) {
    let Some(image) = image else { return };
    match sprites.single_mut() {
        Ok(mut sprite) if sprite.image != image.0 => sprite.image = image.0.clone(),
        Ok(_) => {}
        Err(_) => _ = commands.spawn(Sprite::from_image(image.0.clone())),
    }
}
