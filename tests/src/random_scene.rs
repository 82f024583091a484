//! Random but valid scenes for parity tests: glass spheres and prisms (the
//! glass frosted a third of the time), mirror and metal spheres and prisms
//! (metals of random colour, polished or rough), random glasses and band
//! tables, a spot, point or beam
//! light aimed at the first object, over a floor and in front of a wall.
//! A pure function of the seed.

use crate::{camera, glass, white};
use prismatic_core::model::bands::BandSpec;
use prismatic_core::model::dispersion::{Dispersion, Glass};
use prismatic_core::model::metalness::Metalness;
use prismatic_core::model::scene::{Checker, Estimator, Light, Material, MaterialKind, Object, RenderSettings, Shape};
use prismatic_core::util::rng::random_f32;
use prismatic_core::{MetalColor, NamedMetal, Scene, Vec3};

struct Dice {
    seed: u32,
    n: u32,
}

impl Dice {
    fn f(&mut self, lo: f32, hi: f32) -> f32 {
        self.n += 1;
        lo + (hi - lo) * random_f32(self.seed, 0x5eed, self.n)
    }
    fn pick(&mut self, n: usize) -> usize {
        ((self.f(0.0, 1.0) * n as f32) as usize).min(n - 1)
    }
    fn v(&mut self, lo: Vec3, hi: Vec3) -> Vec3 {
        Vec3::new(self.f(lo.x, hi.x), self.f(lo.y, hi.y), self.f(lo.z, hi.z))
    }
}

/// Scene number `seed`, with `photons` white photons and a `side`×`side` image.
pub fn random_scene(seed: u32, photons: u32, side: u32) -> Scene {
    let mut d = Dice { seed, n: 0 };
    let bands = match d.pick(3) {
        0 => BandSpec::Paper3,
        1 => BandSpec::Paper7,
        _ => BandSpec::Physical(1 + d.pick(24) as u16),
    };
    let render = RenderSettings {
        width: side,
        height: side,
        photons,
        radius: d.f(0.03, 0.12),
        bands,
        estimator: if d.pick(2) == 0 { Estimator::Paper } else { Estimator::Density },
        seed,
        ..RenderSettings::paper()
    };
    let dispersion = match d.pick(5) {
        0 => Glass::ALL[d.pick(Glass::ALL.len())].dispersion(),
        1 => Dispersion::Constant(d.f(1.2, 2.4)),
        2 => Dispersion::Cauchy { a: d.f(1.4, 1.7), b: d.f(0.002, 0.02) },
        3 => Dispersion::Abbe { nd: d.f(1.45, 1.9), vd: d.f(20.0, 70.0) },
        _ => Glass::Paper.dispersion(),
    };
    let floor = Material {
        name: "floor".into(),
        kind: MaterialKind::Diffuse {
            albedo: Vec3::splat(0.8),
            checker: (d.pick(2) == 0).then(|| Checker {
                size: d.f(0.2, 1.0),
                albedo: Vec3::new(0.3, 0.3, 0.5),
                offset: Vec3::ZERO,
            }),
            texture: None,
            emission: Vec3::ZERO,
        },
        normal_map: None,
        roughness_map: None,
        film_map: None,
        specular_map: None,
    };
    // The metal's own dice, so that the draws above and below are those
    // the scenes had before metals came.
    let mut m = Dice { seed, n: 1 << 20 };
    let mut color = MetalColor::Rgb(m.v(Vec3::splat(0.3), Vec3::ONE));
    let roughness = if m.pick(3) == 0 { 0.0 } else { m.f(0.02, 0.6) };
    // A third of the metals measured, from their own dice.
    let mut named = Dice { seed, n: 1 << 22 };
    if named.pick(3) == 0 {
        color = MetalColor::Measured(NamedMetal::ALL[named.pick(4)]);
    }
    let metal = MaterialKind::Metal { color, roughness, texture: None, film: None, metalness: Metalness::WHOLE };
    // A third of the scenes' glass frosted, from its own dice too.
    let mut g = Dice { seed, n: 1 << 21 };
    let mut glass = glass("glass", dispersion);
    if let MaterialKind::Dielectric { roughness, .. } = &mut glass.kind
        && g.pick(3) == 0
    {
        *roughness = g.f(0.05, 0.6);
    }
    let materials =
        vec![glass, white("wall"), floor, Material::new("mirror", MaterialKind::Mirror), Material::new("metal", metal)];
    let mut objects = vec![
        Object { shape: Shape::Plane { point: Vec3::ZERO, normal: Vec3::Y }, material: 2 },
        Object { shape: Shape::Plane { point: Vec3::new(0.0, 0.0, -4.0), normal: Vec3::Z }, material: 1 },
    ];
    let mut first_center = Vec3::new(0.0, 1.0, 0.0);
    for k in 0..1 + d.pick(3) {
        let center = d.v(Vec3::new(-2.0, 0.8, -2.0), Vec3::new(2.0, 2.0, 1.0));
        if k == 0 {
            first_center = center;
        }
        let shape = if d.pick(2) == 0 {
            Shape::Sphere { center, radius: d.f(0.3, 0.8) }
        } else {
            let s = d.f(0.4, 0.9);
            let a = d.f(0.0, std::f32::consts::TAU);
            let corner = |t: f32| center + Vec3::new((a + t).cos() * s, (a + t).sin() * s, -0.6);
            Shape::Prism {
                vertices: [corner(0.0), corner(2.1), corner(4.2)],
                extrude: Vec3::new(d.f(-0.3, 0.3), 0.0, 1.2),
            }
        };
        // Objects after the first: a third mirrors or metals, and a third
        // of the rest metals.
        let material = match k {
            0 => 0,
            _ if d.pick(3) == 0 => 3 + m.pick(2),
            _ if m.pick(3) == 0 => 4,
            _ => 0,
        };
        objects.push(Object { shape, material });
    }
    let from = d.v(Vec3::new(-4.0, 3.0, -1.0), Vec3::new(4.0, 6.0, 3.0));
    let light = match d.pick(3) {
        0 => Light::Spot {
            position: from,
            direction: first_center - from,
            cone_deg: d.f(8.0, 30.0),
            inner_cone_deg: 8.0,
            power: d.f(5.0, 50.0),
            spectrum: Default::default(),
            range: None,
        },
        1 => Light::Point { position: from, power: d.f(5.0, 50.0), spectrum: Default::default(), range: None },
        _ => Light::Beam {
            position: from,
            direction: first_center - from,
            radius: d.f(0.1, 0.6),
            power: d.f(1.0, 10.0),
            spectrum: Default::default(),
        },
    };
    let mut cam = camera();
    cam.position = Vec3::new(0.5, 3.5, 7.0);
    cam.look_at = Vec3::new(0.0, 0.8, -0.5);
    cam.fov_deg = 55.0;
    // A third of the spots and points get a range (drawn last, so that the
    // rest of each scene is what it was): from short of the first object,
    // which then gets part of the light, to well beyond it.
    let mut light = light;
    if let Light::Spot { range, .. } | Light::Point { range, .. } = &mut light
        && d.pick(3) == 0
    {
        *range = Some((first_center - from).length() * d.f(0.8, 2.0));
    }
    Scene { render, camera: cam, lights: vec![light], materials, objects }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The seeds the parity tests take (1 to 16) place mirrors, polished
    /// and rough metals, and polished and frosted glass, so those tests
    /// hold every backend to them.
    #[test]
    fn the_parity_seeds_place_mirrors_metals_and_glass_polished_and_rough() {
        let (mut mirrors, mut metals, mut glass) = (0, Vec::new(), Vec::new());
        for seed in 1..=16 {
            let scene = random_scene(seed, 1, 8);
            for o in &scene.objects {
                match &scene.materials[o.material].kind {
                    MaterialKind::Mirror => mirrors += 1,
                    MaterialKind::Metal { roughness: r, .. } => metals.push(*r),
                    MaterialKind::Dielectric { roughness: r, .. } => glass.push(*r),
                    _ => {}
                }
            }
        }
        assert!(mirrors > 0, "no mirror");
        for (what, roughness) in [("metals'", metals), ("glass's", glass)] {
            assert!(roughness.contains(&0.0) && roughness.iter().any(|&r| r > 0.0), "{what} roughness: {roughness:?}");
        }
    }
}
