//! Helpers shared by the cross-crate tests: scenes built in code for
//! experiments with closed-form answers, and float comparison.

pub mod parity;
pub mod random_scene;
pub mod tolerance;

use prismatic_core::bands::BandSpec;
use prismatic_core::dispersion::Dispersion;
use prismatic_core::scene::{Camera, Estimator, Light, Material, MaterialKind, Object, RenderSettings, Shape};
use prismatic_core::{PreparedScene, Scene, Vec3};

/// A small render setting for tests: 32×32 pixels, `photons` photons.
pub fn settings(photons: u32, bands: BandSpec) -> RenderSettings {
    RenderSettings { width: 32, height: 32, photons, bands, estimator: Estimator::Density, ..RenderSettings::default() }
}

/// A camera that looks at the origin from +z (any valid camera will do for photon tests).
pub fn camera() -> Camera {
    Camera { position: Vec3::new(0.0, 0.0, 10.0), look_at: Vec3::ZERO, up: Vec3::Y, fov_deg: 40.0 }
}

/// A diffuse white material called `name`.
pub fn white(name: &str) -> Material {
    Material { name: name.into(), kind: MaterialKind::Diffuse { albedo: Vec3::splat(0.8), checker: None } }
}

/// A dielectric called `name`.
pub fn glass(name: &str, dispersion: Dispersion) -> Material {
    Material { name: name.into(), kind: MaterialKind::Dielectric { dispersion } }
}

/// The prism experiment in the xy-plane, as a closed-form problem.
///
/// A symmetric prism with apex angle `apex_deg` (apex up, base on y = 0, faces
/// of length 2, extruded from z = −1 to 1). A beam of radius `beam_radius`
/// arrives at the middle of the left face at incidence `incidence_deg`
/// (measured from the face normal). A diffuse screen stands at x = `screen_x`.
#[derive(Clone, Debug)]
pub struct PrismExperiment {
    /// Apex angle A.
    pub apex_deg: f64,
    /// Angle of incidence on the first face.
    pub incidence_deg: f64,
    /// Beam radius.
    pub beam_radius: f32,
    /// Position of the screen plane.
    pub screen_x: f32,
}

impl PrismExperiment {
    fn half(&self) -> f64 {
        (self.apex_deg / 2.0).to_radians()
    }

    /// Corners of the prism's cross-section: left base, right base, apex.
    pub fn corners(&self) -> [(f64, f64); 3] {
        let h = self.half();
        [(-2.0 * h.sin(), 0.0), (2.0 * h.sin(), 0.0), (0.0, 2.0 * h.cos())]
    }

    /// Direction of the incoming beam, as an angle from +x (radians).
    pub fn beam_angle(&self) -> f64 {
        self.incidence_deg.to_radians() - self.half()
    }

    /// Where the beam's centre meets the first face.
    pub fn entry_point(&self) -> (f64, f64) {
        let [l, _, t] = self.corners();
        ((l.0 + t.0) / 2.0, (l.1 + t.1) / 2.0)
    }

    /// The scene: prism of `dispersion`, the beam, the screen.
    pub fn scene(&self, dispersion: Dispersion, render: RenderSettings) -> Scene {
        let [l, r, t] = self.corners();
        let v = |p: (f64, f64)| Vec3::new(p.0 as f32, p.1 as f32, -1.0);
        let phi = self.beam_angle();
        let dir = Vec3::new(phi.cos() as f32, phi.sin() as f32, 0.0);
        let (ex, ey) = self.entry_point();
        let entry = Vec3::new(ex as f32, ey as f32, 0.0);
        Scene {
            render,
            camera: camera(),
            lights: vec![Light::Beam {
                position: entry - dir * 4.0,
                direction: dir,
                radius: self.beam_radius,
                power: 1.0,
            }],
            materials: vec![glass("glass", dispersion), white("screen")],
            objects: vec![
                Object {
                    shape: Shape::Prism { vertices: [v(l), v(r), v(t)], extrude: Vec3::new(0.0, 0.0, 2.0) },
                    material: 0,
                },
                Object {
                    shape: Shape::Plane {
                        point: Vec3::new(self.screen_x, 0.0, 0.0),
                        normal: Vec3::new(-1.0, 0.0, 0.0),
                    },
                    material: 1,
                },
            ],
        }
    }

    /// Closed form: deviation (degrees) of a ray of index `n` by Snell's law
    /// at both faces, or `None` if it is totally reflected at the second face.
    pub fn deviation_deg(&self, n: f64) -> Option<f64> {
        let a = self.apex_deg.to_radians();
        let i = self.incidence_deg.to_radians();
        let r1 = (i.sin() / n).asin();
        let s = n * (a - r1).sin();
        (s.abs() <= 1.0).then(|| (i + s.asin() - a).to_degrees())
    }

    /// Closed form: where the centre ray of index `n` meets the screen (y).
    pub fn screen_y(&self, n: f64) -> Option<f64> {
        let h = self.half();
        let r1 = (self.incidence_deg.to_radians().sin() / n).asin();
        // Inside, the ray turns from the left face's inward normal (angle −A/2) by r1.
        let inside = -h + r1;
        let (px, py) = self.entry_point();
        // Right face: the line through the right base corner and the apex.
        let [_, r, t] = self.corners();
        let (fx, fy) = (t.0 - r.0, t.1 - r.1);
        let (dx, dy) = (inside.cos(), inside.sin());
        // Solve p + s·d = r + u·f.
        let det = dx * (-fy) - dy * (-fx);
        let s = ((r.0 - px) * (-fy) - (r.1 - py) * (-fx)) / det;
        let (qx, qy) = (px + s * dx, py + s * dy);
        let out = self.beam_angle() - self.deviation_deg(n)?.to_radians();
        Some(qy + (f64::from(self.screen_x) - qx) * out.tan())
    }

    /// Closed form: minimum deviation D_min = 2·asin(n·sin(A/2)) − A, degrees.
    pub fn min_deviation_deg(apex_deg: f64, n: f64) -> f64 {
        let a = apex_deg.to_radians();
        (2.0 * (n * (a / 2.0).sin()).asin() - a).to_degrees()
    }
}

/// Built-in scene `name` with its render settings edited by `edit`, prepared.
pub fn builtin(name: &str, edit: impl FnOnce(&mut RenderSettings)) -> PreparedScene {
    let mut doc = prismatic_cli::load_scene(name).unwrap_or_else(|e| panic!("{e}"));
    edit(&mut doc.scene.render);
    PreparedScene::new(doc.scene).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// Prepares a scene that tests build (panics with the validation message if invalid).
pub fn prepare(scene: Scene) -> PreparedScene {
    PreparedScene::new(scene).unwrap_or_else(|e| panic!("test scene is invalid: {e}"))
}
