//! The exact sums of a render's passes: per pixel, Σ over passes of the
//! visible points' weight × caustic irradiance and the light-traced
//! photons' radiance (and with sampled view paths the pass's own view), in
//! fixed point. Integer sums do not depend on the order of the passes, the
//! points or the threads, so passes rendered anywhere (another process,
//! another machine) merge into the bits of one run.

use crate::model::image::Image;
use crate::photons::light_tracing::Splat;
use crate::render::visible::VisiblePoint;
use alloc::vec;
use alloc::vec::Vec;
use glam::{DVec3, Vec3};

/// Fixed-point scale of the accumulated sums (2^32 per unit of radiance).
pub const FIXED_POINT_SCALE: f64 = 4_294_967_296.0;

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
            insert_passes(&mut a.passes, x, y)?;
        }
        Ok(a)
    }

    /// Whether pass `pass` is summed.
    pub fn contains(&self, pass: u32) -> bool {
        contains_pass(&self.passes, pass)
    }

    /// How many passes are summed.
    pub fn pass_count(&self) -> u32 {
        count_passes(&self.passes)
    }

    /// Adds pass `pass`: its gather at `points` and its light-traced `splats`.
    ///
    /// # Panics
    /// If the pass is already in, or `gathered` does not match `points`.
    pub fn add_pass(&mut self, pass: u32, points: &[VisiblePoint], gathered: &[Vec3], splats: &[Splat]) {
        assert_eq!(points.len(), gathered.len(), "one irradiance per visible point");
        insert_passes(&mut self.passes, pass, pass + 1).expect("each pass once");
        for (p, e) in points.iter().zip(gathered) {
            self.add(p.pixel, (p.weight.as_dvec3() * e.as_dvec3()).to_array());
        }
        for s in splats {
            self.add(s.pixel, s.radiance.as_dvec3().to_array());
        }
    }

    /// Adds a pass's own view to the sums: its image without caustics (with
    /// sampled view paths each pass traces its own; see
    /// [`crate::model::scene::ViewPaths::Sampled`]). Call it with the pass's
    /// [`Accumulation::add_pass`].
    ///
    /// # Panics
    /// If `base` is not of the accumulation's size.
    pub fn add_view(&mut self, base: &Image) {
        assert_eq!((base.width, base.height), (self.width, self.height), "one pixel per sum");
        for (pixel, radiance) in base.pixels.iter().enumerate() {
            self.add(pixel as u32, radiance.as_dvec3().to_array());
        }
    }

    /// Adds radiance to a pixel's sums, each channel truncated to fixed point.
    fn add(&mut self, pixel: u32, radiance: [f64; 3]) {
        let sum = &mut self.sums[pixel as usize];
        for (s, x) in sum.iter_mut().zip(radiance) {
            *s = s.saturating_add(to_fixed(x));
        }
    }

    /// Adds another accumulation of the same image (disjoint passes).
    pub fn merge(&mut self, other: &Accumulation) -> Result<(), MergeError> {
        if (self.width, self.height) != (other.width, other.height) {
            return Err(MergeError::Size(self.width, self.height, other.width, other.height));
        }
        let before = self.passes.clone();
        for &(a, b) in &other.passes {
            if let Err(e) = insert_passes(&mut self.passes, a, b) {
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

/// Adds passes `a..b` to `passes` (sorted, disjoint half-open ranges,
/// touching ones joined: `0..8` and `8..16` are `0..16`); an error, and
/// nothing added, when one of them is in already.
pub fn insert_passes(passes: &mut Vec<(u32, u32)>, a: u32, b: u32) -> Result<(), MergeError> {
    if let Some(&(x, y)) = passes.iter().find(|&&(x, y)| a < y && x < b) {
        return Err(MergeError::Overlap(a.max(x).min(y - 1)));
    }
    passes.push((a, b));
    passes.sort_unstable();
    let mut joined: Vec<(u32, u32)> = Vec::with_capacity(passes.len());
    for &(x, y) in passes.iter() {
        match joined.last_mut() {
            Some(last) if last.1 == x => last.1 = y,
            _ => joined.push((x, y)),
        }
    }
    *passes = joined;
    Ok(())
}

/// Whether `passes` (as [`insert_passes`] keeps them) holds pass `pass`.
pub fn contains_pass(passes: &[(u32, u32)], pass: u32) -> bool {
    passes.iter().any(|&(a, b)| (a..b).contains(&pass))
}

/// How many passes `passes` holds.
pub fn count_passes(passes: &[(u32, u32)]) -> u32 {
    passes.iter().map(|(a, b)| b - a).sum()
}

/// A radiance contribution in fixed point (truncated toward zero,
/// saturating; NaN counts as 0). The GPU's twin is `to_fixed` in WGSL.
pub fn to_fixed(x: f64) -> i64 {
    (x * FIXED_POINT_SCALE) as i64
}
