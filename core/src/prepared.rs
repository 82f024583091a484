//! A validated scene with everything derived that tracing and rendering need:
//! the band table, each object's primitive and optics (per-band indices of
//! refraction), and the light-selection distribution.

use crate::bands::{BandTable, VISIBLE_NM};
use crate::effects::EffectPlan;
use crate::geometry::{Primitive, Ray, mesh_triangles, prism_faces};
use crate::photon::WHITE_BAND;
use crate::scene::{Checker, MaterialKind, Scene, SceneError, Shape};
use crate::tolerance;
use alloc::vec::Vec;
use glam::Vec3;

/// How an object's surface scatters light, ready for tracing.
#[derive(Clone, Debug, PartialEq)]
pub enum Surface {
    /// Lambertian.
    Diffuse {
        /// Albedo.
        albedo: Vec3,
        /// Optional checker.
        checker: Option<Checker>,
    },
    /// Perfect mirror.
    Mirror,
    /// Dielectric with its indices per band.
    Dielectric(DielectricOptics),
}

/// A dielectric's indices of refraction for the render's band table, and
/// whether white light splits into bands there (the effect plan decides).
#[derive(Clone, Debug, PartialEq)]
pub struct DielectricOptics {
    /// n for each band.
    pub band_ior: Vec<f32>,
    /// n for white light that does not split: the glass's one index when it
    /// has one, else the middle band's.
    pub white_ior: f32,
    /// The bands do not all share one index.
    pub dispersive: bool,
    /// White photons split into bands here.
    pub splits_photons: bool,
    /// White view rays split into bands here.
    pub splits_view_rays: bool,
    /// The relative index as a function of wavelength, for photons traced at
    /// their own wavelength ([`crate::WavelengthSampling::Continuous`]);
    /// `None` when a per-band table gives the index (no wavelength axis).
    pub spectrum: Option<IorCurve>,
}

/// A relative index of refraction sampled every nanometre over the visible
/// range, read by linear interpolation (the error of a Sellmeier curve
/// between samples is below 1e-7).
#[derive(Clone, Debug, PartialEq)]
pub struct IorCurve {
    /// n at `VISIBLE_NM.0 + i` nm.
    samples: Vec<f32>,
}

impl IorCurve {
    /// Samples n_inside(λ)/n_outside(λ); `None` when either has no wavelength axis.
    pub fn new(inside: &crate::Dispersion, outside: &crate::Dispersion) -> Option<Self> {
        let (lo, hi) = (VISIBLE_NM.0 as u32, VISIBLE_NM.1 as u32);
        let samples = (lo..=hi)
            .map(|nm| Some(inside.ior_at(nm as f32)? / outside.ior_at(nm as f32)?))
            .collect::<Option<Vec<f32>>>()?;
        Some(IorCurve { samples })
    }

    /// The samples, n at `VISIBLE_NM.0 + i` nm (for backends that upload the curve).
    pub fn samples(&self) -> &[f32] {
        &self.samples
    }

    /// n at `lambda_nm` (clamped to the visible range).
    pub fn at(&self, lambda_nm: f32) -> f32 {
        let x = (lambda_nm - VISIBLE_NM.0).clamp(0.0, (self.samples.len() - 1) as f32);
        let i = (x as usize).min(self.samples.len() - 2);
        let f = x - i as f32;
        self.samples[i] + (self.samples[i + 1] - self.samples[i]) * f
    }
}

impl DielectricOptics {
    /// The index for `band` ([`WHITE_BAND`]: the white index).
    #[inline]
    pub fn ior(&self, band: u16) -> f32 {
        if band == WHITE_BAND { self.white_ior } else { self.band_ior[usize::from(band)] }
    }

    /// The index for `band` traced at its own wavelength `lambda_nm`: the
    /// band's index moved along the glass's dispersion curve, so that the
    /// band's centre keeps exactly the band's index (and a per-band table,
    /// which has no curve, keeps it everywhere).
    #[inline]
    pub fn ior_at_wavelength(&self, band: u16, lambda_nm: f32, bands: &BandTable) -> f32 {
        let n = self.ior(band);
        match &self.spectrum {
            Some(curve) => n + (curve.at(lambda_nm) - curve.at(bands.band(usize::from(band)).lambda_nm)),
            None => n,
        }
    }

    /// True when the bands do not all share one index.
    #[inline]
    pub fn is_dispersive(&self) -> bool {
        self.dispersive
    }
}

impl Surface {
    /// Albedo at world point `p` with unit normal `n` (checker evaluated a
    /// hair below the surface so that planes through a cell border do not flicker).
    #[inline]
    pub fn albedo_at(&self, p: Vec3, n: Vec3) -> Vec3 {
        match self {
            Surface::Diffuse { albedo, checker: None } => *albedo,
            Surface::Diffuse { albedo, checker: Some(ch) } => {
                let q = (p + ch.offset - n * (ch.size * 1e-3)) / ch.size;
                let parity = (crate::math::floor(q.x) + crate::math::floor(q.y) + crate::math::floor(q.z)) as i64;
                if parity.rem_euclid(2) == 0 { *albedo } else { ch.albedo }
            }
            _ => Vec3::ZERO,
        }
    }
}

/// A hit with the scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Ray parameter.
    pub t: f32,
    /// World point.
    pub point: Vec3,
    /// Outward geometric unit normal.
    pub normal: Vec3,
    /// Index of the object hit.
    pub object: usize,
}

/// A validated scene plus the tables derived from it.
#[derive(Clone, Debug, PartialEq)]
pub struct PreparedScene {
    /// The scene as given.
    pub scene: Scene,
    /// The render's band table.
    pub bands: BandTable,
    /// One primitive per object.
    pub primitives: Vec<Primitive>,
    /// One surface per object.
    pub surfaces: Vec<Surface>,
    /// Cumulative light-selection probabilities (by power).
    pub light_cdf: Vec<f32>,
    /// Σ light power.
    pub total_power: f32,
    /// What the render simulates; backends follow it.
    pub plan: EffectPlan,
}

impl PreparedScene {
    /// Validates `scene` and derives the tables.
    pub fn new(scene: Scene) -> Result<Self, SceneError> {
        scene.validate()?;
        let bands = BandTable::new(scene.render.bands);
        let primitives = scene.objects.iter().map(|o| primitive(&o.shape)).collect();
        let surfaces: Vec<Surface> = scene
            .objects
            .iter()
            .map(|o| match &scene.materials[o.material].kind {
                MaterialKind::Diffuse { albedo, checker } => {
                    Surface::Diffuse { albedo: *albedo, checker: checker.clone() }
                }
                MaterialKind::Mirror => Surface::Mirror,
                MaterialKind::Dielectric { dispersion, outside } => {
                    // Snell's law and Fresnel depend only on the ratio of the
                    // indices, so the optics carry the relative index n/n_outside.
                    let per_band = |d: &crate::Dispersion| -> Vec<f32> {
                        (0..bands.len()).map(|b| d.ior_for_band(&bands, b)).collect()
                    };
                    let (inside_ior, outside_ior) = (per_band(dispersion), per_band(outside));
                    let band_ior: Vec<f32> = inside_ior.iter().zip(&outside_ior).map(|(n, m)| n / m).collect();
                    let constant = dispersion.is_constant() && outside.is_constant();
                    let dispersive = !constant && band_ior.iter().any(|&n| n != band_ior[0]);
                    let white_ior = white_index(dispersion, &inside_ior) / white_index(outside, &outside_ior);
                    // Whether white light splits here is set from the effect plan below.
                    Surface::Dielectric(DielectricOptics {
                        band_ior,
                        white_ior,
                        dispersive,
                        splits_photons: false,
                        splits_view_rays: false,
                        spectrum: IorCurve::new(dispersion, outside),
                    })
                }
            })
            .collect();
        let total_power: f32 = scene.lights.iter().map(|l| l.power()).sum();
        let mut acc = 0.0;
        let mut light_cdf: Vec<f32> = scene
            .lights
            .iter()
            .map(|l| {
                acc += l.power();
                acc / total_power
            })
            .collect();
        if let Some(last) = light_cdf.last_mut() {
            *last = 1.0;
        }
        let mut surfaces: Vec<Surface> = surfaces;
        let plan = EffectPlan::new(&scene, &surfaces);
        for s in &mut surfaces {
            if let Surface::Dielectric(g) = s {
                g.splits_photons = g.dispersive && plan.band_splitting.on;
                g.splits_view_rays = g.dispersive && plan.view_dispersion.on;
            }
        }
        Ok(PreparedScene { scene, bands, primitives, surfaces, light_cdf, total_power, plan })
    }

    /// Simulates every effect, ignoring the plan (see [`EffectPlan::simulate_everything`]).
    pub fn simulate_everything(&mut self) {
        self.plan.simulate_everything(self.scene.render.max_depth, &mut self.surfaces);
    }

    /// The nearest hit along `ray` closer than `t_max`. Rays start off their
    /// surface (see [`offset_origin`]), so any positive distance counts.
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<Hit> {
        let mut best: Option<Hit> = None;
        let mut limit = t_max;
        for (object, prim) in self.primitives.iter().enumerate() {
            if let Some(h) = prim.intersect(ray, 0.0, limit) {
                limit = h.t;
                best = Some(Hit { t: h.t, point: ray.at(h.t), normal: h.normal, object });
            }
        }
        best
    }

    /// True when something blocks the segment from `origin` along unit `dir` before `dist`.
    pub fn occluded(&self, origin: Vec3, dir: Vec3, dist: f32) -> bool {
        let ray = Ray { origin, direction: dir };
        self.primitives.iter().any(|p| p.intersect(&ray, 0.0, dist).is_some())
    }
}

/// n for white light: the model's one index when it has one, else the
/// middle band's of `band_ior`.
fn white_index(dispersion: &crate::Dispersion, band_ior: &[f32]) -> f32 {
    match dispersion {
        crate::Dispersion::Constant(n) => *n,
        _ => band_ior[band_ior.len() / 2],
    }
}

fn primitive(shape: &Shape) -> Primitive {
    match shape {
        Shape::Sphere { center, radius } => Primitive::Sphere { center: *center, radius: *radius },
        Shape::Plane { point, normal } => Primitive::Plane { point: *point, normal: normal.normalize() },
        Shape::Disk { center, normal, radius, inner_radius } => Primitive::Disk {
            center: *center,
            normal: normal.normalize(),
            radius2: radius * radius,
            inner_radius2: inner_radius * inner_radius,
        },
        Shape::Prism { vertices, extrude } => Primitive::Convex { faces: prism_faces(*vertices, *extrude) },
        Shape::Mesh { positions, triangles } => {
            let tris = mesh_triangles(positions, triangles);
            let (lo, hi) =
                positions.iter().fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), p| (lo.min(*p), hi.max(*p)));
            let center = (lo + hi) * 0.5;
            let radius = positions.iter().map(|p| (*p - center).length()).fold(0.0f32, f32::max) * 1.0001 + 1e-6;
            Primitive::Mesh { triangles: tris, bound_center: center, bound_radius: radius }
        }
    }
}

/// The origin of a ray leaving surface point `p` (normal `n`, either side)
/// in direction `dir`: pushed off the surface to the side `dir` goes.
#[inline]
pub fn offset_origin(p: Vec3, n: Vec3, dir: Vec3) -> Vec3 {
    let eps = tolerance::surface_offset(p);
    if dir.dot(n) >= 0.0 { p + n * eps } else { p - n * eps }
}
