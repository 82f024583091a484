//! Rough metal and glass lit by hidden lights (spot, point and beam lights
//! no view ray can meet) through mirrors: scenes whose light only photons
//! bring to the rough surface, which light tracing connects to the camera
//! and visible points there gather.

use crate::backends::image_after;
use crate::{prepare, settings, white};
use prismatic_core::model::bands::BandSpec;
use prismatic_core::model::dispersion::Dispersion;
use prismatic_core::model::metalness::Metalness;
use prismatic_core::model::scene::{Camera, Light, Material, MaterialKind, Object, Scene, Shape, ViewPaths};
use prismatic_core::{Backend, MetalColor, PreparedScene, Vec3};

/// The sum of every pixel of `scene`'s image after `passes` passes on `backend`.
pub fn image_sum(backend: &mut dyn Backend, scene: &PreparedScene, passes: u32) -> f64 {
    image_after(backend, scene, passes).pixels.iter().map(|p| f64::from(p.element_sum())).sum()
}

/// A whole metal of RGB reflectance `color` (Schlick's F0) and `roughness`.
pub fn rough_metal(color: Vec3, roughness: f32) -> Material {
    let metalness = Metalness::WHOLE;
    let kind = MaterialKind::Metal { color: MetalColor::Rgb(color), roughness, texture: None, film: None, metalness };
    Material { kind, ..white("rough metal") }
}

/// Frosted glass of index `ior` and `roughness`: a thin sheet, or solid.
pub fn frosted(ior: f32, roughness: f32, thin: bool) -> Material {
    Material {
        kind: MaterialKind::Dielectric {
            dispersion: Dispersion::Constant(ior),
            outside: Dispersion::Constant(1.0),
            attenuation: None,
            thin,
            film: None,
            roughness,
        },
        ..white("frosted glass")
    }
}

/// What a rough `floor` (a disc of radius 0.9 about (1, 0, 0) in the plane y = 0) seen from above shows of a beam
/// of power 1000 (radius 0.6, white) that comes down on it obliquely (along
/// (1, −2, 0)/√5, its axis meeting the floor at (1, 0, 0); with `below`,
/// mirrored in the floor: from under it). `mirrored`: the beam travels
/// along +x at height 6 and a mirror (a disc at (0, ±6, 0)) folds it onto
/// the floor, so the floor's light is the caustic of one specular bounce,
/// which only photons bring (light traced, or gathered where the floor is
/// rough enough); else the beam itself comes from where the mirror sends
/// it, and the view's highlights bring it. What the floor reflects leaves
/// away from the mirror. A black sky, no ambient light: the floor's light
/// is the beam's alone. Jittered view paths: the passes' mean is each
/// pixel's mean, as a splat's is.
pub fn beam_on_a_rough_floor(floor: Material, below: bool, mirrored: bool, light_tracing: bool) -> PreparedScene {
    let side = if below { -1.0 } else { 1.0 };
    let mut render = settings(40_000, BandSpec::Paper3);
    (render.width, render.height, render.light_tracing) = (32, 32, light_tracing);
    render.view_paths = ViewPaths::Sampled;
    (render.background, render.ambient) = (Vec3::ZERO, 0.0);
    let mirror_at = Vec3::new(0.0, 6.0 * side, 0.0);
    let onto = Vec3::new(1.0, -2.0 * side, 0.0).normalize();
    let spot = Vec3::new(3.0, 0.0, 0.0);
    let (position, direction) = match mirrored {
        true => (Vec3::new(-3.0, 6.0 * side, 0.0), Vec3::X),
        false => (spot - 3.0 * onto, onto),
    };
    let beam = Light::Beam { position, direction, radius: 0.6, power: 1000.0, spectrum: Default::default() };
    let mirror = Material { kind: MaterialKind::Mirror, ..white("mirror") };
    // A floor just wide enough for the beam: what the mirror sends back misses it.
    let disc = Shape::Disk { center: spot, normal: Vec3::Y, radius: 0.9, inner_radius: 0.0 };
    let mut objects = vec![Object { shape: disc, material: 0 }];
    if mirrored {
        let normal = (onto - Vec3::X).normalize();
        let shape = Shape::Disk { center: mirror_at, normal, radius: 1.6, inner_radius: 0.0 };
        objects.push(Object { shape, material: 1 });
    }
    prepare(Scene {
        render,
        camera: Camera { position: spot + Vec3::new(0.0, 3.0, 5.0), look_at: spot, up: Vec3::Y, fov_deg: 36.0 },
        lights: vec![beam],
        materials: vec![floor, mirror],
        objects,
    })
}

/// A rough metal floor (a disc of radius 2 about the origin, roughness
/// 0.6) under a rough metal ceiling (a disc of radius 1, 1.5 above it,
/// roughness 0.4) that a spot light between them lights from below, seen
/// from the side; the floor's only light is what the ceiling reflects (the
/// spot shines up). `photons` a pass (0: the view alone, which finds the
/// ceiling's highlight from the floor), light traced or not, per-pass
/// jittered view paths.
pub fn lit_between_rough_metals(photons: u32, light_tracing: bool) -> PreparedScene {
    let metal = |roughness| rough_metal(Vec3::splat(0.9), roughness);
    let mut render = settings(photons, BandSpec::Paper3);
    (render.width, render.height, render.light_tracing) = (32, 32, light_tracing);
    (render.view_paths, render.background, render.ambient) = (ViewPaths::Sampled, Vec3::ZERO, 0.0);
    let spot = Light::Spot {
        position: Vec3::new(0.0, 0.5, 0.0),
        direction: Vec3::Y,
        cone_deg: 70.0,
        inner_cone_deg: 70.0,
        power: 1000.0,
        spectrum: Default::default(),
        range: None,
    };
    let disc =
        |y: f32, normal: Vec3, radius: f32| Shape::Disk { center: Vec3::Y * y, normal, radius, inner_radius: 0.0 };
    prepare(Scene {
        render,
        camera: Camera { position: Vec3::new(0.0, 1.0, 5.0), look_at: Vec3::ZERO, up: Vec3::Y, fov_deg: 50.0 },
        lights: vec![spot],
        materials: vec![metal(0.6), metal(0.4)],
        objects: vec![
            Object { shape: disc(0.0, Vec3::Y, 2.0), material: 0 },
            Object { shape: disc(1.5, Vec3::NEG_Y, 1.0), material: 1 },
        ],
    })
}

/// Radius of [`beam_in_a_frosted_ball`]'s beam.
pub const BALL_BEAM_RADIUS: f32 = 0.3;

/// A beam of power 1 (radius [`BALL_BEAM_RADIUS`]) inside a ball of
/// frosted glass (index 1.5, roughness 0.5: α 0.25, radius 10) folded by a
/// mirror straight up onto the ball's top, which the camera (8×8 pixels)
/// sees head on from far above, every pixel within the beam's spot:
/// directly from (0, 40, 0), or `in_a_mirror` from (40, 30, 0) in a mirror
/// at (0, 30, 0) that turns its rays straight down. Light traced or not.
pub fn beam_in_a_frosted_ball(light_tracing: bool, in_a_mirror: bool) -> PreparedScene {
    let mut render = settings(40_000, BandSpec::Paper3);
    (render.width, render.height, render.light_tracing) = (8, 8, light_tracing);
    (render.background, render.ambient) = (Vec3::ZERO, 0.0);
    let mirror = |center: Vec3, normal: Vec3, radius: f32| Object {
        shape: Shape::Disk { center, normal: normal.normalize(), radius, inner_radius: 0.0 },
        material: 1,
    };
    let beam = Light::Beam {
        position: Vec3::new(-5.0, 5.0, 0.0),
        direction: Vec3::X,
        radius: BALL_BEAM_RADIUS,
        power: 1.0,
        spectrum: Default::default(),
    };
    let mut objects = vec![
        Object { shape: Shape::Sphere { center: Vec3::ZERO, radius: 10.0 }, material: 0 },
        mirror(Vec3::new(0.0, 5.0, 0.0), Vec3::new(-1.0, 1.0, 0.0), 0.6),
    ];
    // The same patch of the top from 30 above, or 40 + 10 away in the mirror.
    let camera = match in_a_mirror {
        false => Camera { position: Vec3::new(0.0, 40.0, 0.0), look_at: Vec3::Y * 10.0, up: Vec3::Z, fov_deg: 0.6 },
        true => {
            objects.push(mirror(Vec3::new(0.0, 30.0, 0.0), Vec3::new(1.0, -1.0, 0.0), 2.0));
            let position = Vec3::new(40.0, 30.0, 0.0);
            Camera { position, look_at: Vec3::new(0.0, 30.0, 0.0), up: Vec3::Z, fov_deg: 0.36 }
        }
    };
    prepare(Scene {
        render,
        camera,
        lights: vec![beam],
        materials: vec![frosted(1.5, 0.5, false), Material { kind: MaterialKind::Mirror, ..white("mirror") }],
        objects,
    })
}

/// The radiance that [`beam_in_a_frosted_ball`]'s camera sees of the top:
/// Walter et al.'s BTDF times the irradiance inside, E = P/(πr²). Head on,
/// the facet is the normal, so f = η_o² (1 − F) D(n) G2 / (η_i cos i −
/// η_o cos o)² with D(n) = 1/(πα²), G2 = 1, F = 0.04, η_i = 1.5 inside
/// and η_o = 1: radiance over n² is what a ray keeps leaving the glass.
pub fn ball_top_radiance() -> f64 {
    let (alpha, n_glass, radius) = (0.25f64, 1.5f64, f64::from(BALL_BEAM_RADIUS));
    let fresnel = ((n_glass - 1.0) / (n_glass + 1.0)).powi(2);
    let d = 1.0 / (std::f64::consts::PI * alpha * alpha);
    let btdf = (1.0 - fresnel) * d / (n_glass - 1.0).powi(2);
    btdf / (std::f64::consts::PI * radius * radius)
}
