//! Progressive photon mapping: many independent photon passes gathered at
//! visible points traced once, with a per-point radius that shrinks from
//! pass to pass, summed into one image.
//!
//! This is the memoryless form of Knaus & Zwicker (2011): pass k (from 1)
//! gathers with r_k² = r_1² · Π_{j=1}^{k−1} (j + α)/(j + 1), and the image is
//! the plain mean of the passes' estimates. With 0 < α < 1 both the variance
//! and the bias of the mean go to zero, so the mean converges to the true
//! caustic, which a fixed radius never does (it stays blurred by r).
//! Hachisuka's α ≈ 0.7 is the usual compromise between the two.
//!
//! Each visible point has its own r_1: a pilot pass (its own seed, an
//! eighth of the photons) counts the photons within the scene's radius R
//! around the point, and r_1 is the radius that would hold the scene's
//! `neighbours` photon paths of a full pass at that density, between
//! R·[`MIN_RADIUS_FRACTION`] and R. A path is what one white photon
//! leaves: N band photons when it splits into all N bands (they land
//! together until the glass fans them out), one otherwise. Dense caustics
//! get small radii (sharp, and each gather visits few photons); sparse
//! regions keep R.
//!
//! Passes share nothing but the visible points and their r_1, both fixed by
//! the scene and seed, so any set of passes can be rendered anywhere and
//! summed later: the sums are fixed-point integers ([`Accumulation`]), and
//! integer sums do not depend on the order of the passes, the points or
//! the threads.

use crate::backend::{Backend, BackendError, Progress};
use crate::gather::{GatherQuery, gather_counted};
use crate::grid::PhotonGrid;
use crate::image::Image;
use crate::math::sqrt;
use crate::photon::{PhotonMap, TraceStats};
use crate::prepared::PreparedScene;
use crate::rng::random_u32;
use crate::scene::WavelengthSampling;
use crate::visible::{VisiblePoint, VisiblePoints};
use alloc::vec;
use alloc::vec::Vec;
use glam::{DVec3, Vec3};

/// Hachisuka et al.'s recommended fraction of photons kept per pass.
pub const DEFAULT_ALPHA: f32 = 0.7;

/// Independent photon paths a visible point's first radius should hold
/// by default (Jensen's caustic gathers use 50–100 nearest photons).
pub const DEFAULT_NEIGHBOURS: u32 = 32;

/// The smallest first radius, as a fraction of the scene's radius: it
/// bounds the grid levels a pass needs (see [`level_of`]).
pub const MIN_RADIUS_FRACTION: f32 = 1.0 / 32.0;

/// The pilot pass traces this fraction (1/N) of a pass's photons.
pub const PILOT_PHOTON_DIVISOR: u32 = 8;

/// Grid levels of a pass: level l has cells for radius R_k / 4^l, so a
/// point of radius r uses the finest level whose radius is still ≥ r.
pub const GRID_LEVELS: usize = 3;

/// Fixed-point scale of the accumulated sums (2^32 per unit of radiance).
pub const FIXED_POINT_SCALE: f64 = 4_294_967_296.0;

/// The radius of pass `k` (1-based) when pass 1 uses `r1`.
pub fn pass_radius(r1: f32, alpha: f32, k: u32) -> f32 {
    let mut r2 = f64::from(r1) * f64::from(r1);
    for j in 1..k {
        r2 *= (f64::from(j) + f64::from(alpha)) / (f64::from(j) + 1.0);
    }
    sqrt(r2 as f32)
}

/// The scene of photon pass `pass` (0-based) of a progressive render: its
/// own seed (derived from the scene's, so passes are independent) and, as
/// its radius, the pass's largest radius R·s_k (k = pass + 1).
pub fn photon_pass_scene(scene: &PreparedScene, alpha: f32, pass: u32) -> PreparedScene {
    let k = pass.saturating_add(1);
    let mut photons = scene.clone();
    let r = &mut photons.scene.render;
    r.seed = random_u32(r.seed, k, u32::MAX);
    r.radius = pass_radius(r.radius, alpha, k);
    photons
}

/// The pilot pass: a seed no photon pass uses, the scene's radius, and
/// 1/[`PILOT_PHOTON_DIVISOR`] of the photons.
pub fn pilot_scene(scene: &PreparedScene) -> PreparedScene {
    let mut pilot = scene.clone();
    let r = &mut pilot.scene.render;
    r.seed = random_u32(r.seed, 0, u32::MAX);
    r.photons = (r.photons / PILOT_PHOTON_DIVISOR).max(1);
    pilot
}

/// A point's first radius from the photons its pilot gather found within
/// `r0`, when a full pass has `scale` times the pilot's photons and the
/// radius should hold `neighbours` of them.
pub fn initial_radius(r0: f32, pilot_photons: u32, scale: f32, neighbours: f32) -> f32 {
    let expected = pilot_photons as f32 * scale;
    if expected <= neighbours {
        return r0;
    }
    (r0 * sqrt(neighbours / expected)).clamp(r0 * MIN_RADIUS_FRACTION, r0)
}

/// Stored photons per independent photon path: a white photon split into
/// N bands leaves N photons that travel together until the glass fans them.
pub fn photons_per_path(scene: &PreparedScene) -> u32 {
    match scene.scene.render.wavelengths {
        WavelengthSampling::Split => scene.bands.len() as u32,
        WavelengthSampling::RandomBand | WavelengthSampling::Continuous => 1,
    }
}

/// The grid radius of `level` in a pass whose largest radius is `r_pass`.
pub fn level_radius(r_pass: f32, level: usize) -> f32 {
    r_pass / (1u32 << (2 * level)) as f32
}

/// The finest grid level whose radius is at least `r` (≤ `r_pass`).
pub fn level_of(r: f32, r_pass: f32) -> usize {
    let mut level = 0;
    while level + 1 < GRID_LEVELS && r <= level_radius(r_pass, level + 1) {
        level += 1;
    }
    level
}

/// Which grid levels a pass whose largest radius is `r_pass` needs for
/// points of radii `radii` (the rest are not built).
pub fn levels_used(radii: &[f32], r_pass: f32) -> [bool; GRID_LEVELS] {
    let mut used = [false; GRID_LEVELS];
    for &r in radii {
        used[level_of(r, r_pass)] = true;
    }
    used
}

/// What one pass's gather found at each visible point.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PassGather {
    /// Caustic irradiance (linear RGB, before the point's weight).
    pub irradiance: Vec<Vec3>,
    /// Photons accepted within the point's radius.
    pub photons: Vec<u32>,
    /// What the pass's photon trace did.
    pub stats: TraceStats,
}

/// The scalar reference of a pass's gather: `map`'s photons at `points`,
/// each with its own radius (`radii`, at most `r_pass`), from grids of
/// [`GRID_LEVELS`] cell sizes.
pub fn gather_pass(scene: &PreparedScene, map: &PhotonMap, points: &[VisiblePoint], radii: &[f32]) -> PassGather {
    let r_pass = scene.scene.render.radius;
    let used = levels_used(radii, r_pass);
    let grids: Vec<Option<PhotonGrid>> =
        (0..GRID_LEVELS).map(|l| used[l].then(|| PhotonGrid::build(&map.photons, level_radius(r_pass, l)))).collect();
    let settings = &scene.scene.render;
    let (irradiance, photons) = points
        .iter()
        .zip(radii)
        .map(|(p, &r)| {
            let grid = grids[level_of(r, r_pass)].as_ref().expect("level built");
            let q = GatherQuery { point: p.point, normal: p.normal, radius: r };
            gather_counted(grid, &map.photons, &scene.bands, settings.estimator, &q)
        })
        .unzip();
    PassGather { irradiance, photons, stats: map.stats }
}

/// Why two accumulations cannot be merged.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum MergeError {
    /// Different image sizes.
    #[error("image sizes differ: {0}x{1} and {2}x{3}")]
    Size(u32, u32, u32, u32),
    /// A pass is in both.
    #[error("pass {0} is in both")]
    Overlap(u32),
    /// A range of no passes.
    #[error("empty pass range {0}..{1}")]
    Empty(u32, u32),
    /// Not one sum per pixel.
    #[error("{0} pixel sums for a {1}x{2} image")]
    Sums(usize, u32, u32),
}

/// The per-pixel sums of a set of passes: Σ over passes and visible points
/// of weight × irradiance, in fixed point ([`FIXED_POINT_SCALE`]). Integer
/// sums make the result independent of order: same passes, same bits.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Accumulation {
    /// Image width.
    pub width: u32,
    /// Image height.
    pub height: u32,
    /// The passes summed, as sorted, disjoint half-open ranges.
    pub passes: Vec<(u32, u32)>,
    /// Per pixel: the caustic radiance sums (R, G, B).
    pub sums: Vec<[i64; 3]>,
}

impl Accumulation {
    /// No passes yet.
    pub fn new(width: u32, height: u32) -> Self {
        Accumulation { width, height, passes: Vec::new(), sums: vec![[0; 3]; width as usize * height as usize] }
    }

    /// Sums read back (a partial render's file): `passes` must be disjoint
    /// and non-empty, `sums` one per pixel.
    pub fn from_parts(width: u32, height: u32, passes: &[(u32, u32)], sums: Vec<[i64; 3]>) -> Result<Self, MergeError> {
        if sums.len() != width as usize * height as usize {
            return Err(MergeError::Sums(sums.len(), width, height));
        }
        let mut a = Accumulation { width, height, passes: Vec::new(), sums };
        for &(x, y) in passes {
            if x >= y {
                return Err(MergeError::Empty(x, y));
            }
            a.insert_range(x, y)?;
        }
        Ok(a)
    }

    /// How many passes are summed.
    pub fn pass_count(&self) -> u32 {
        self.passes.iter().map(|(a, b)| b - a).sum()
    }

    /// Adds pass `pass`'s gather at `points`.
    ///
    /// # Panics
    /// If the pass is already in, or `gathered` does not match `points`.
    pub fn add_pass(&mut self, pass: u32, points: &[VisiblePoint], gathered: &[Vec3]) {
        assert_eq!(points.len(), gathered.len(), "one irradiance per visible point");
        self.insert_range(pass, pass + 1).expect("each pass once");
        for (p, e) in points.iter().zip(gathered) {
            let sum = &mut self.sums[p.pixel as usize];
            for (c, s) in sum.iter_mut().enumerate() {
                *s = s.saturating_add(to_fixed(f64::from(p.weight[c]) * f64::from(e[c])));
            }
        }
    }

    /// Adds another accumulation of the same image (disjoint passes).
    pub fn merge(&mut self, other: &Accumulation) -> Result<(), MergeError> {
        if (self.width, self.height) != (other.width, other.height) {
            return Err(MergeError::Size(self.width, self.height, other.width, other.height));
        }
        let before = self.passes.clone();
        for &(a, b) in &other.passes {
            if let Err(e) = self.insert_range(a, b) {
                self.passes = before;
                return Err(e);
            }
        }
        for (s, o) in self.sums.iter_mut().zip(&other.sums) {
            for c in 0..3 {
                s[c] = s[c].saturating_add(o[c]);
            }
        }
        Ok(())
    }

    fn insert_range(&mut self, a: u32, b: u32) -> Result<(), MergeError> {
        if let Some(&(x, y)) = self.passes.iter().find(|&&(x, y)| a < y && x < b) {
            return Err(MergeError::Overlap(a.max(x).min(y - 1)));
        }
        self.passes.push((a, b));
        self.passes.sort_unstable();
        // Join touching ranges: 0..8 and 8..16 are 0..16.
        let mut joined: Vec<(u32, u32)> = Vec::with_capacity(self.passes.len());
        for &(x, y) in &self.passes {
            match joined.last_mut() {
                Some(last) if last.1 == x => last.1 = y,
                _ => joined.push((x, y)),
            }
        }
        self.passes = joined;
        Ok(())
    }

    /// The image: `base` plus the mean caustic of the passes.
    pub fn image(&self, base: &Image) -> Image {
        let scale = 1.0 / (FIXED_POINT_SCALE * f64::from(self.pass_count().max(1)));
        let mut image = base.clone();
        for (p, s) in image.pixels.iter_mut().zip(&self.sums) {
            *p += DVec3::new(s[0] as f64, s[1] as f64, s[2] as f64).as_vec3() * scale as f32;
        }
        image
    }
}

/// A radiance contribution in fixed point (saturating; NaN counts as 0).
fn to_fixed(x: f64) -> i64 {
    (x * FIXED_POINT_SCALE) as i64
}

/// A progressive render in progress: visible points traced once, their
/// first radii, and the sums of the passes run so far.
#[derive(Clone, Debug)]
pub struct ProgressiveRender {
    scene: PreparedScene,
    points: VisiblePoints,
    radii: Vec<f32>,
    accumulation: Accumulation,
}

impl ProgressiveRender {
    /// Traces the view rays and runs the pilot pass on `backend`; passes
    /// will shrink radii with the scene's `alpha`.
    pub fn prepare(
        backend: &mut dyn Backend,
        scene: &PreparedScene,
        progress: &mut dyn Progress,
    ) -> Result<Self, BackendError> {
        let points = backend.visible_points(scene, progress)?;
        let r0 = scene.scene.render.radius;
        let radii = if points.points.is_empty() {
            Vec::new()
        } else {
            let pilot = pilot_scene(scene);
            let scale = scene.scene.render.photons as f32 / pilot.scene.render.photons as f32;
            let neighbours = (scene.scene.render.neighbours * photons_per_path(scene)) as f32;
            let found = backend.gather_pass(&pilot, &points.points, &vec![r0; points.points.len()])?;
            found.photons.iter().map(|&n| initial_radius(r0, n, scale, neighbours)).collect()
        };
        let r = &scene.scene.render;
        Ok(ProgressiveRender {
            scene: scene.clone(),
            points,
            radii,
            accumulation: Accumulation::new(r.width, r.height),
        })
    }

    /// Runs photon pass `pass` (0-based) and adds it to the sums.
    pub fn run_pass(&mut self, backend: &mut dyn Backend, pass: u32) -> Result<TraceStats, BackendError> {
        let points = &self.points.points;
        if points.is_empty() {
            self.accumulation.add_pass(pass, &[], &[]);
            return Ok(TraceStats::default());
        }
        let alpha = self.scene.scene.render.alpha;
        let scene = photon_pass_scene(&self.scene, alpha, pass);
        let shrink = pass_radius(1.0, alpha, pass.saturating_add(1));
        let radii: Vec<f32> = self.radii.iter().map(|&r| (r * shrink).min(scene.scene.render.radius)).collect();
        let found = backend.gather_pass(&scene, points, &radii)?;
        self.accumulation.add_pass(pass, points, &found.irradiance);
        Ok(found.stats)
    }

    /// The image of the passes so far.
    pub fn image(&self) -> Image {
        self.accumulation.image(&self.points.base)
    }

    /// The visible points.
    pub fn points(&self) -> &VisiblePoints {
        &self.points
    }

    /// Each visible point's first radius.
    pub fn initial_radii(&self) -> &[f32] {
        &self.radii
    }

    /// The sums of the passes so far.
    pub fn accumulation(&self) -> &Accumulation {
        &self.accumulation
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn radius_shrinks_as_the_closed_form_says() {
        assert_eq!(pass_radius(0.1, 0.7, 1), 0.1);
        // r_2² = r_1² (1 + α)/2.
        assert!((pass_radius(0.1, 0.7, 2) - 0.1 * (0.85f32).sqrt()).abs() < 1e-7);
        // Π (j+α)/(j+1) ~ Γ(2)/Γ(1+α) · k^(α−1): r_k² falls like k^(−0.3).
        let r = |k| f64::from(pass_radius(1.0, 0.7, k)).powi(2);
        let slope = (r(4000) / r(1000)).ln() / 4f64.ln();
        assert!((slope + 0.3).abs() < 1e-3, "slope {slope}");
        // α = 1 keeps the radius.
        assert_eq!(pass_radius(0.1, 1.0, 50), 0.1);
    }
}
