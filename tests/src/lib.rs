//! Helpers shared by the cross-crate tests: scenes built in code for
//! experiments with closed-form answers, and float comparison.

pub mod backends;
pub mod parity;
pub mod random_scene;
pub mod rough;

pub use prismatic_conformance::tolerance;

use prismatic_core::model::bands::BandSpec;
use prismatic_core::model::dispersion::Dispersion;
use prismatic_core::model::scene::{Camera, Estimator, Light, Material, MaterialKind, Object, RenderSettings, Shape};
use prismatic_core::{PreparedScene, Scene, Vec3};

/// A small render setting for tests: the paper's method at 32×32 pixels,
/// `photons` photons, `bands` and the density estimator.
pub fn settings(photons: u32, bands: BandSpec) -> RenderSettings {
    RenderSettings { width: 32, height: 32, photons, bands, estimator: Estimator::Density, ..RenderSettings::paper() }
}

/// A camera that looks at the origin from +z (any valid camera will do for photon tests).
pub fn camera() -> Camera {
    Camera { position: Vec3::new(0.0, 0.0, 10.0), look_at: Vec3::ZERO, up: Vec3::Y, fov_deg: 40.0 }
}

/// A diffuse white material called `name`.
pub fn white(name: &str) -> Material {
    Material {
        name: name.into(),
        kind: MaterialKind::Diffuse { albedo: Vec3::splat(0.8), checker: None, texture: None, emission: Vec3::ZERO },
        normal_map: None,
        roughness_map: None,
        film_map: None,
        specular_map: None,
    }
}

/// A dielectric called `name`.
pub fn glass(name: &str, dispersion: Dispersion) -> Material {
    Material {
        name: name.into(),
        kind: MaterialKind::Dielectric {
            dispersion,
            outside: Dispersion::Constant(1.0),
            attenuation: None,
            thin: false,
            film: None,
            roughness: 0.0,
        },
        normal_map: None,
        roughness_map: None,
        film_map: None,
        specular_map: None,
    }
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
                spectrum: Default::default(),
            }],
            materials: vec![glass("glass", dispersion), white("screen")],
            objects: vec![
                Object {
                    shape: Shape::Prism { vertices: self.vertices(), extrude: Vec3::new(0.0, 0.0, 2.0) },
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

    /// Closed form: where the centre ray of index `n` leaves the prism's
    /// second face, and its direction there as an angle from +x (radians).
    pub fn exit_ray(&self, n: f64) -> Option<((f64, f64), f64)> {
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
        let out = self.beam_angle() - self.deviation_deg(n)?.to_radians();
        Some(((px + s * dx, py + s * dy), out))
    }

    /// Closed form: where the centre ray of index `n` meets the screen (y).
    pub fn screen_y(&self, n: f64) -> Option<f64> {
        let ((qx, qy), out) = self.exit_ray(n)?;
        Some(qy + (f64::from(self.screen_x) - qx) * out.tan())
    }

    /// The prism's vertices as given to [`Shape::Prism`] (back face, z = −1).
    fn vertices(&self) -> [Vec3; 3] {
        self.corners().map(|p| Vec3::new(p.0 as f32, p.1 as f32, -1.0))
    }

    /// Adds the recombining prism: the first prism's point reflection through
    /// the point `gap / 2` past where the centre ray of index `n` leaves it,
    /// so that its first face is parallel to the first prism's exit face,
    /// `gap` further along that ray.
    /// Returns the cross-section of the new prism.
    pub fn add_inverted_prism(&self, scene: &mut Scene, n: f64, gap: f64) -> [(f64, f64); 3] {
        let ((qx, qy), out) = self.exit_ray(n).expect("the centre ray leaves the first prism");
        let c = (qx + out.cos() * gap / 2.0, qy + out.sin() * gap / 2.0);
        // Rounded to f32 first, so that the closed form sees the prism the tracer sees.
        let reflect = |p: (f64, f64)| (f64::from((2.0 * c.0 - p.0) as f32), f64::from((2.0 * c.1 - p.1) as f32));
        let corners = self.corners().map(reflect);
        let v = corners.map(|p| Vec3::new(p.0 as f32, p.1 as f32, 1.0));
        scene
            .objects
            .push(Object { shape: Shape::Prism { vertices: v, extrude: Vec3::new(0.0, 0.0, -2.0) }, material: 0 });
        corners
    }

    /// Closed form: minimum deviation D_min = 2·asin(n·sin(A/2)) − A, degrees.
    pub fn min_deviation_deg(apex_deg: f64, n: f64) -> f64 {
        let a = apex_deg.to_radians();
        (2.0 * (n * (a / 2.0).sin()).asin() - a).to_degrees()
    }
}

/// A dielectric sphere of radius 1 at the origin inside a diffuse catcher
/// sphere of radius 50 that closes the scene, lit by a beam along −z of
/// radius `beam_radius` whose axis passes `beam_x` from the centre.
pub fn sphere_in_a_catcher(dispersion: Dispersion, render: RenderSettings, beam_x: f32, beam_radius: f32) -> Scene {
    Scene {
        render,
        camera: camera(),
        lights: vec![Light::Beam {
            position: Vec3::new(beam_x, 0.0, 5.0),
            direction: Vec3::NEG_Z,
            radius: beam_radius,
            power: 1.0,
            spectrum: Default::default(),
        }],
        materials: vec![glass("sphere", dispersion), white("catcher")],
        objects: vec![
            Object { shape: Shape::Sphere { center: Vec3::ZERO, radius: 1.0 }, material: 0 },
            Object { shape: Shape::Sphere { center: Vec3::ZERO, radius: 50.0 }, material: 1 },
        ],
    }
}

/// A beam of radius 0.2 along +x from x = −1 through `glass` (material 0,
/// the object `shape`) onto a white wall at x = 3 (`photons` a pass, paper7).
pub fn beam_onto_a_wall(photons: u32, glass: Material, shape: Shape) -> PreparedScene {
    prepare(Scene {
        render: settings(photons, BandSpec::Paper7),
        camera: camera(),
        lights: vec![Light::Beam {
            position: Vec3::new(-1.0, 0.0, 0.0),
            direction: Vec3::X,
            radius: 0.2,
            power: 1.0,
            spectrum: Default::default(),
        }],
        materials: vec![glass, white("wall")],
        objects: vec![
            Object { shape, material: 0 },
            Object { shape: Shape::Plane { point: Vec3::new(3.0, 0.0, 0.0), normal: Vec3::NEG_X }, material: 1 },
        ],
    })
}

/// A camera on the x axis looking head on through `sheet` (an open mesh:
/// one square in the plane x = 0, its texture coordinates from 0 to 1
/// across it) at a background of radiance 1; behind
/// the camera a black wall, which is what the sheet's reflection shows
/// (3×3 pixels: the middle one looks straight through).
pub fn view_through_a_sheet(sheet: Material) -> PreparedScene {
    let mut render = settings(1000, BandSpec::Paper7);
    (render.width, render.height, render.background, render.ambient) = (3, 3, Vec3::ONE, 0.0);
    let black = Material {
        name: "black".into(),
        kind: MaterialKind::Diffuse { albedo: Vec3::ZERO, checker: None, texture: None, emission: Vec3::ZERO },
        normal_map: None,
        roughness_map: None,
        film_map: None,
        specular_map: None,
    };
    let square =
        [Vec3::new(0.0, -2.0, -2.0), Vec3::new(0.0, 2.0, -2.0), Vec3::new(0.0, 2.0, 2.0), Vec3::new(0.0, -2.0, 2.0)];
    prepare(Scene {
        render,
        camera: Camera { position: Vec3::new(-5.0, 0.0, 0.0), look_at: Vec3::ZERO, up: Vec3::Z, fov_deg: 10.0 },
        lights: vec![Light::Point {
            position: Vec3::new(-5.0, 0.0, 5.0),
            power: 1.0,
            spectrum: Default::default(),
            range: None,
        }],
        materials: vec![sheet, black],
        objects: vec![
            Object {
                shape: Shape::Mesh {
                    positions: square.to_vec(),
                    triangles: vec![[0, 1, 2], [0, 2, 3]],
                    uvs: vec![[0.0, 0.0].into(), [1.0, 0.0].into(), [1.0, 1.0].into(), [0.0, 1.0].into()],
                    normals: Vec::new(),
                    tangents: Vec::new(),
                },
                material: 0,
            },
            Object { shape: Shape::Plane { point: Vec3::new(-6.0, 0.0, 0.0), normal: Vec3::X }, material: 1 },
        ],
    })
}

/// Descartes: the k-reflection bow's angle from the antisolar point, degrees.
pub fn descartes_deg(n: f64, k: f64) -> f64 {
    let i = ((n * n - 1.0) / (k * k + 2.0 * k)).sqrt().acos();
    let r = (i.sin() / n).asin();
    let d = 2.0 * (i - r) + k * (std::f64::consts::PI - 2.0 * r);
    (180.0 - d.to_degrees().rem_euclid(360.0)).abs()
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

/// Closed form for a ray in the xy-plane through glass triangles of index
/// `n` (in air), refracting at every face (Snell's law in f64, no
/// reflections): where it meets the screen plane x = `screen_x` (y), or
/// `None` when it is totally reflected somewhere.
pub fn snell_path_2d(
    triangles: &[[(f64, f64); 3]],
    start: (f64, f64),
    angle: f64,
    n: f64,
    screen_x: f64,
) -> Option<f64> {
    let (mut p, mut d) = (start, (angle.cos(), angle.sin()));
    loop {
        // Nearest face ahead, with its outward normal.
        let mut nearest: Option<(f64, (f64, f64))> = None;
        for tri in triangles {
            let centroid = ((tri[0].0 + tri[1].0 + tri[2].0) / 3.0, (tri[0].1 + tri[1].1 + tri[2].1) / 3.0);
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                let e = (b.0 - a.0, b.1 - a.1);
                let mut normal = (e.1, -e.0);
                if normal.0 * (a.0 - centroid.0) + normal.1 * (a.1 - centroid.1) < 0.0 {
                    normal = (-normal.0, -normal.1);
                }
                let det = d.0 * (-e.1) + d.1 * e.0;
                if det.abs() < 1e-15 {
                    continue;
                }
                let t = ((a.0 - p.0) * (-e.1) + (a.1 - p.1) * e.0) / det;
                let u = (d.0 * (a.1 - p.1) - d.1 * (a.0 - p.0)) / det;
                if t > 1e-9 && (0.0..=1.0).contains(&u) && nearest.is_none_or(|(best, _)| t < best) {
                    let len = normal.0.hypot(normal.1);
                    nearest = Some((t, (normal.0 / len, normal.1 / len)));
                }
            }
        }
        let Some((t, outward)) = nearest else {
            return Some(p.1 + (screen_x - p.0) * d.1 / d.0);
        };
        p = (p.0 + t * d.0, p.1 + t * d.1);
        let cos = d.0 * outward.0 + d.1 * outward.1;
        let (facing, eta) = if cos < 0.0 { (outward, 1.0 / n) } else { ((-outward.0, -outward.1), n) };
        let cos_i = -(d.0 * facing.0 + d.1 * facing.1);
        let cos2_t = 1.0 - eta * eta * (1.0 - cos_i * cos_i);
        if cos2_t < 0.0 {
            return None;
        }
        let k = eta * cos_i - cos2_t.sqrt();
        d = (eta * d.0 + k * facing.0, eta * d.1 + k * facing.1);
    }
}

/// A scene file's object keys: one triangle of a mesh with texture coordinates.
pub const TRIANGLE_WITH_UVS: &str = "shape = \"mesh\"\npositions = [[0, 0, 0], [1, 0, 0], [0, 0, -1]]\n\
                                     triangles = [[0, 1, 2]]\nuvs = [[0, 1], [1, 1], [0, 0]]";

/// A scene file's object keys: a unit sphere (no texture coordinates).
pub const UNIT_SPHERE: &str = "shape = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1";

/// A scene file of one material `m` (its keys: `material`) on one object
/// (its keys: `shape`) under a point light, read from folder `dir` (where
/// its images are) and validated.
pub fn one_material_scene_file(
    dir: &std::path::Path,
    material: &str,
    shape: &str,
) -> Result<prismatic_cli::scene_file::SceneDocument, prismatic_cli::scene_file::SceneFileError> {
    let text = format!(
        "[camera]\nposition = [0, 1, 5]\nlook_at = [0, 0, 0]\n\n\
         [[light]]\nkind = \"point\"\nposition = [0, 4, 0]\npower = 10\n\n\
         [material.m]\n{material}\n\n[[object]]\nmaterial = \"m\"\n{shape}\n"
    );
    let doc = prismatic_cli::scene_file::parse(&text, "test.toml", Some(dir))?;
    doc.validate().map(|_| doc)
}
