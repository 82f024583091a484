//! What an environment light sends along each direction (its map read
//! bilinearly, turned and scaled), and the directional lights it is drawn
//! as: the median cut of its map (Debevec 2005, "A median cut algorithm for
//! light probe sampling").
//!
//! The cut splits the sphere into regions of about equal power (luminance
//! times solid angle), first at the horizon, then always the region with
//! the most power, across its longer side in angle, where half its power
//! lies on either side. Each region becomes one directional light along
//! its vector irradiance m = Σ L ω dω (per channel: luminance's m gives the
//! direction, and each channel Σ L dω scaled by |m|/Σ L dω of the
//! luminance): a diffuse surface that sees the whole region receives
//! m·n from it, exactly what the region sends it. The direct light and
//! shadows of an environment then are those of `n` suns, which every
//! backend draws, and its caustics are theirs (each sun's photons aimed at
//! the mirrors and glass). The approximation is in the regions a surface
//! sees only in part (cut by its horizon), and in shadows (n hard ones, not
//! one soft one); the render setting `environment_lights` sets n.
//!
//! With per-pass view paths the regions are strata instead: each pass
//! draws every region's sun anew ([`EnvironmentCut::draw`]), along a
//! direction of the region chosen with probability ∝ its radiance, with
//! the region's whole Σ L dω as irradiance. A surface then receives in
//! expectation exactly ∫ L cos θ V dω from the region, its horizon and
//! shadows included, so the passes' mean converges to the map's light
//! with no bias left. The draws' mean direction ([`CutRegion::mean_toward`],
//! exact for the draw's density) lets the direct light subtract what it
//! knows: a control variate ([`crate::plan::drawn_suns`]).

use crate::model::color::luminance;
use crate::model::environment::EnvironmentMap;
use crate::util::math::{acos, atan2, cos, floor, sin, sqrt};
use alloc::vec::Vec;
use core::f32::consts::PI;
use glam::Vec3;

/// An environment map turned by `rotation_deg` about +y and scaled by `strength`.
#[derive(Clone, Debug, PartialEq)]
pub struct EnvironmentLookup {
    /// The map.
    pub map: EnvironmentMap,
    /// Radiance multiplier.
    pub strength: f32,
    /// The turn about +y as a fraction of a full turn (added to u).
    pub turn: f32,
}

/// One light of the median cut: its region's fixed sun.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CutLight {
    /// Unit direction toward the light (its region's vector irradiance).
    pub toward: Vec3,
    /// The irradiance per channel on a surface facing it: the length of
    /// the region's vector irradiance.
    pub rgb: Vec3,
}

impl EnvironmentLookup {
    /// The lookup of `map` at `strength`, turned `rotation_deg` about +y.
    pub fn new(map: EnvironmentMap, strength: f32, rotation_deg: f32) -> Self {
        EnvironmentLookup { map, strength, turn: rotation_deg / 360.0 }
    }

    /// Radiance arriving from the environment along direction of travel `d`
    /// (a unit vector: the ray looks toward `d`), bilinear between texel
    /// centres, wrapping around in longitude.
    pub fn radiance(&self, d: Vec3) -> Vec3 {
        let u = 0.5 + atan2(d.x, -d.z) / (2.0 * PI) + self.turn;
        let v = acos(d.y.clamp(-1.0, 1.0)) / PI;
        self.texel_at(u, v) * self.strength
    }

    /// The map bilinearly at (u, v) ∈ [0, 1)² (u wraps, v is clamped).
    fn texel_at(&self, u: f32, v: f32) -> Vec3 {
        let (w, h) = (self.map.width as i64, self.map.height as i64);
        let fx = (u - floor(u)) * w as f32 - 0.5;
        let fy = (v * h as f32 - 0.5).clamp(0.0, (h - 1) as f32);
        let (x0, y0) = (floor(fx), floor(fy));
        let (tx, ty) = (fx - x0, fy - y0);
        let (x0, y0) = (x0 as i64, y0 as i64);
        let at = |x: i64, y: i64| self.map.texels[(y.min(h - 1) * w + x.rem_euclid(w)) as usize];
        let top = at(x0, y0) * (1.0 - tx) + at(x0 + 1, y0) * tx;
        let bottom = at(x0, y0 + 1) * (1.0 - tx) + at(x0 + 1, y0 + 1) * tx;
        top * (1.0 - ty) + bottom * ty
    }

    /// The direction of travel whose look-up lands on map point (u, v):
    /// the inverse of [`EnvironmentLookup::radiance`]'s mapping.
    pub fn direction(&self, u: f32, v: f32) -> Vec3 {
        direction_at(u, v, self.turn)
    }

    /// The map's median cut into `n` regions (fewer when the map has fewer
    /// texels with light), each with its fixed sun and what a draw needs. A
    /// map coarser than [`CUT_GRID`] (a constant one is a single texel) is
    /// cut on that grid, read bilinearly. A texel's solid angle is exact
    /// (Δφ · (cos θ₀ − cos θ₁)), so a constant map's regions sum to 4π L.
    pub fn cut(&self, n: usize) -> EnvironmentCut {
        let (w, h) = ((self.map.width as usize).max(CUT_GRID.0), (self.map.height as usize).max(CUT_GRID.1));
        let at = |x: usize, y: usize| match (w, h) == (self.map.width as usize, self.map.height as usize) {
            true => self.map.texels[y * w + x],
            false => self.texel_at((x as f32 + 0.5) / w as f32, (y as f32 + 0.5) / h as f32),
        };
        let texels: Vec<Vec3> = (0..w * h).map(|i| at(i % w, i / w).max(Vec3::ZERO)).collect();
        let d_omega = |y: usize| (2.0 * PI / w as f32) * (row_cos(y, h) - row_cos(y + 1, h));
        let power: Vec<f32> = (0..w * h).map(|i| luminance(texels[i]) * self.strength * d_omega(i / w)).collect();
        let cut = Cut { w, h, power: &power };
        let whole = Region { x: (0, w), y: (0, h) };
        let halves = match h {
            1 => Vec::from([whole]),
            _ => Vec::from([Region { y: (0, h / 2), ..whole }, Region { y: (h / 2, h), ..whole }]),
        };
        // Each region with its power, summed once.
        let mut regions: Vec<(Region, f32)> = halves.into_iter().map(|r| (r, cut.power(&r))).collect();
        while regions.len() < n {
            let splittable =
                regions.iter().enumerate().filter(|(_, (r, _))| r.texels() > 1).max_by(|a, b| a.1.1.total_cmp(&b.1.1));
            let Some((i, &(region, _))) = splittable else { break };
            let (a, b) = cut.split(region);
            regions[i] = (a, cut.power(&a));
            regions.push((b, cut.power(&b)));
        }
        let regions = regions
            .iter()
            .filter_map(|&(rect, total)| {
                let (mut rgb, mut toward, mut mean) = (Vec3::ZERO, Vec3::ZERO, Vec3::ZERO);
                for y in rect.y.0..rect.y.1 {
                    for x in rect.x.0..rect.x.1 {
                        let dir = self.direction((x as f32 + 0.5) / w as f32, (y as f32 + 0.5) / h as f32);
                        rgb += texels[y * w + x] * (self.strength * d_omega(y));
                        toward += dir * power[y * w + x];
                        mean += texel_mean_direction(x, y, (w, h), self.turn) * power[y * w + x];
                    }
                }
                let length = sqrt(toward.length_squared());
                (length > 0.0 && rgb.max_element() > 0.0).then(|| CutRegion {
                    rect,
                    rows: (rect.y.0..rect.y.1).map(|y| cut.power(&Region { y: (y, y + 1), ..rect })).collect(),
                    power: total,
                    rgb,
                    fixed: CutLight { toward: toward / length, rgb: rgb * (length / total) },
                    mean_toward: mean / total,
                })
            })
            .collect();
        EnvironmentCut { w, h, turn: self.turn, power, regions }
    }
}

/// The direction of travel whose look-up lands on map point (u, v) of a
/// map turned by `turn`.
fn direction_at(u: f32, v: f32, turn: f32) -> Vec3 {
    let phi = (u - turn - 0.5) * 2.0 * PI;
    let theta = v * PI;
    Vec3::new(sin(theta) * sin(phi), cos(theta), -sin(theta) * cos(phi))
}

/// cos θ at the top of row `y` of `h` (θ from the zenith).
fn row_cos(y: usize, h: usize) -> f32 {
    cos(PI * y as f32 / h as f32)
}

/// The mean of the directions [`EnvironmentCut::draw`] takes in texel
/// (`x`, `y`) of a `w` × `h` grid turned by `turn`: uniform in cos θ across
/// the row and in φ across the texel, so E[cos θ] is the row's mid cos θ,
/// E[sin θ] = (Δθ − cos(θ₀ + θ₁) sin Δθ) / (4 sin θ_mid sin(Δθ/2)) (the
/// integral of √(1 − c²) over the row's c), and the azimuth's mean is the
/// centre's shortened by sin(Δφ/2)/(Δφ/2). Shorter than 1: a texel's
/// directions spread.
fn texel_mean_direction(x: usize, y: usize, (w, h): (usize, usize), turn: f32) -> Vec3 {
    let (theta0, theta1) = (PI * y as f32 / h as f32, PI * (y + 1) as f32 / h as f32);
    let d_theta = theta1 - theta0;
    let mean_cos = 0.5 * (cos(theta0) + cos(theta1));
    let mean_sin =
        (d_theta - cos(theta0 + theta1) * sin(d_theta)) / (4.0 * sin(0.5 * (theta0 + theta1)) * sin(0.5 * d_theta));
    let half_phi = PI / w as f32;
    let shorten = sin(half_phi) / half_phi;
    let centre = direction_at((x as f32 + 0.5) / w as f32, 0.5, turn);
    Vec3::new(centre.x * mean_sin * shorten, mean_cos, centre.z * mean_sin * shorten)
}

/// An environment's median cut, kept to draw its suns from: the grid it
/// was cut on, each texel's power (luminance × solid angle) and the
/// regions with light.
#[derive(Clone, Debug, PartialEq)]
pub struct EnvironmentCut {
    w: usize,
    h: usize,
    /// The map's turn (see [`EnvironmentLookup::turn`]).
    turn: f32,
    power: Vec<f32>,
    /// The regions, each with its fixed sun.
    pub regions: Vec<CutRegion>,
}

/// A region of the cut.
#[derive(Clone, Debug, PartialEq)]
pub struct CutRegion {
    rect: Region,
    /// Each of its rows' power.
    rows: Vec<f32>,
    /// Σ luminance × dω over the region.
    pub power: f32,
    /// Σ L dω per channel: the irradiance of a drawn sun on a surface facing it.
    pub rgb: Vec3,
    /// The sun along the region's vector irradiance.
    pub fixed: CutLight,
    /// The mean of [`EnvironmentCut::draw`]'s directions in the region
    /// (shorter than 1): a drawn sun of irradiance E sends an unshadowed
    /// plane facing n the mean E · n·`mean_toward` over the draws, below
    /// the horizon included (cos θ signed).
    pub mean_toward: Vec3,
}

impl EnvironmentCut {
    /// A direction toward region `region`'s light, drawn with two uniform
    /// numbers: a texel with probability ∝ its power (`u1` picks the row,
    /// `u2` the texel in it), and a point of the texel uniform in solid
    /// angle (each number's remainder within its pick). The density over
    /// solid angle is L/Σ L dω (the map as constant texels), so the sun
    /// [`CutRegion::rgb`] along it sends a surface ∫ L cos θ V dω in expectation.
    pub fn draw(&self, region: usize, u1: f32, u2: f32) -> Vec3 {
        let CutRegion { rect: r, rows, .. } = &self.regions[region];
        let (row, t) = pick(rows, u1);
        let y = r.y.0 + row;
        let (column, s) = pick(&self.power[y * self.w + r.x.0..y * self.w + r.x.1], u2);
        let x = r.x.0 + column;
        // Uniform in cos θ across the row and in φ across the texel.
        let (c0, c1) = (row_cos(y, self.h), row_cos(y + 1, self.h));
        let v = acos((c0 - t * (c0 - c1)).clamp(-1.0, 1.0)) / PI;
        let u = (x as f32 + s) / self.w as f32;
        direction_at(u, v, self.turn)
    }
}

/// The entry of `weights` at cumulative share `u` and where `u` fell inside
/// it (a fraction in [0, 1)); the last entry with weight when rounding
/// leaves `u` past the sum.
fn pick(weights: &[f32], u: f32) -> (usize, f32) {
    let target = u * weights.iter().sum::<f32>();
    let mut acc = 0.0;
    for (i, &w) in weights.iter().enumerate() {
        if w > 0.0 && target < acc + w {
            return (i, ((target - acc) / w).clamp(0.0, 0.999_999_9));
        }
        acc += w;
    }
    (weights.iter().rposition(|&w| w > 0.0).unwrap_or(0), 0.5)
}

/// The coarsest grid a map is cut on (columns, rows): fine enough for
/// [`crate::model::scene::DEFAULT_ENVIRONMENT_LIGHTS`] regions of many cells each.
pub const CUT_GRID: (usize, usize) = (64, 32);

/// A rectangle of texels: columns `x.0..x.1`, rows `y.0..y.1`.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Region {
    x: (usize, usize),
    y: (usize, usize),
}

impl Region {
    fn texels(&self) -> usize {
        (self.x.1 - self.x.0) * (self.y.1 - self.y.0)
    }
}

/// The map's per-texel power, for cutting regions.
struct Cut<'a> {
    w: usize,
    h: usize,
    power: &'a [f32],
}

impl Cut<'_> {
    fn power(&self, r: &Region) -> f32 {
        (r.y.0..r.y.1).map(|y| self.power[y * self.w + r.x.0..y * self.w + r.x.1].iter().sum::<f32>()).sum()
    }

    /// `r` in two across its longer side in angle (its width measured at
    /// its middle latitude), where half its power lies on either side (at
    /// least one texel each).
    fn split(&self, r: Region) -> (Region, Region) {
        let mid = PI * (r.y.0 + r.y.1) as f32 / (2 * self.h) as f32;
        let width = (r.x.1 - r.x.0) as f32 / self.w as f32 * 2.0 * PI * sin(mid);
        let height = (r.y.1 - r.y.0) as f32 / self.h as f32 * PI;
        let across_x = (width >= height && r.x.1 - r.x.0 > 1) || r.y.1 - r.y.0 == 1;
        let (lo, hi) = if across_x { r.x } else { r.y };
        let slice = |k: usize| match across_x {
            true => self.power(&Region { x: (k, k + 1), ..r }),
            false => self.power(&Region { y: (k, k + 1), ..r }),
        };
        let total: f32 = (lo..hi).map(slice).sum();
        let (mut at, mut acc) = (lo + 1, slice(lo));
        while at < hi - 1 && acc < total / 2.0 {
            acc += slice(at);
            at += 1;
        }
        match across_x {
            true => (Region { x: (lo, at), ..r }, Region { x: (at, hi), ..r }),
            false => (Region { y: (lo, at), ..r }, Region { y: (at, hi), ..r }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::f64::consts::PI as PI64;

    /// The cut's fixed suns.
    fn fixed_suns(env: &EnvironmentLookup, n: usize) -> Vec<CutLight> {
        env.cut(n).regions.iter().map(|r| r.fixed).collect()
    }

    fn lookup(map: EnvironmentMap) -> EnvironmentLookup {
        EnvironmentLookup::new(map, 2.0, 0.0)
    }

    #[test]
    fn directions_and_radiance_round_trip_through_the_map() {
        let texels: Vec<Vec3> = (0..8 * 4).map(|i| Vec3::splat(i as f32)).collect();
        let env = EnvironmentLookup::new(
            EnvironmentMap { name: "ramp".into(), width: 8, height: 4, texels: texels.into() },
            1.0,
            90.0,
        );
        for (x, y) in [(0, 0), (3, 1), (7, 3), (5, 2)] {
            let d = env.direction((x as f32 + 0.5) / 8.0, (y as f32 + 0.5) / 4.0);
            assert!((d.length() - 1.0).abs() < 1e-6);
            let got = env.radiance(d).x;
            assert!((got - (y * 8 + x) as f32).abs() < 1e-3, "texel ({x}, {y}) reads {got}");
        }
        // The image's centre is what a camera looking down −z sees (before turning).
        let at_rest = EnvironmentLookup::new(EnvironmentMap::constant(Vec3::ONE), 1.0, 0.0);
        assert!((at_rest.direction(0.5, 0.5) - Vec3::NEG_Z).length() < 1e-6);
        assert!((at_rest.direction(0.75, 0.5) - Vec3::X).length() < 1e-6);
    }

    /// Σ over the lights above a surface of E cos θ: the irradiance the cut
    /// gives a diffuse plane facing up.
    fn upward_irradiance(lights: &[CutLight]) -> f32 {
        lights.iter().map(|l| luminance(l.rgb) * l.toward.y.max(0.0)).sum()
    }

    #[test]
    fn a_constant_environment_cut_gives_pi_l_on_planes_that_see_whole_regions() {
        let texels: Vec<Vec3> = (0..128 * 64).map(|_| Vec3::ONE).collect();
        let env = lookup(EnvironmentMap { name: "grey".into(), width: 128, height: 64, texels: texels.into() });
        for n in [2, 32, 512] {
            let lights = fixed_suns(&env, n);
            assert_eq!(lights.len(), n);
            // The first cut is the horizon: a plane facing up sees the upper
            // regions whole, and each sends it its vector irradiance.
            let e = upward_irradiance(&lights);
            let want = PI * 2.0;
            assert!((e - want).abs() < 2e-3 * want, "{n} lights: E = {e}, πL = {want}");
        }
        // A tilted plane cuts regions with its horizon: the error is there,
        // and shrinks as the regions do.
        let tilted = Vec3::new(0.6, 0.8, 0.0);
        let error = |n: usize| {
            let e: f32 = fixed_suns(&env, n).iter().map(|l| luminance(l.rgb) * l.toward.dot(tilted).max(0.0)).sum();
            (e / (PI * 2.0) - 1.0).abs()
        };
        let (coarse, fine) = (error(32), error(512));
        assert!(coarse < 0.05 && fine < 0.01 && fine < coarse, "{coarse} at 32 lights, {fine} at 512");
    }

    /// The irradiance of a plane facing `n` from every region's drawn suns,
    /// each region's draws on a 24 × 24 grid of numbers averaged.
    fn drawn_irradiance(cut: &EnvironmentCut, n: Vec3) -> f32 {
        let k = 24;
        let mut e = 0.0;
        for (i, region) in cut.regions.iter().enumerate() {
            for a in 0..k * k {
                let (u1, u2) = (((a / k) as f32 + 0.5) / k as f32, ((a % k) as f32 + 0.5) / k as f32);
                e += luminance(region.rgb) * cut.draw(i, u1, u2).dot(n).max(0.0) / (k * k) as f32;
            }
        }
        e
    }

    #[test]
    fn drawn_suns_give_a_constant_sky_pi_l_on_any_plane() {
        let env = lookup(EnvironmentMap::constant(Vec3::ONE));
        let cut = env.cut(32);
        let whole: f32 = cut.regions.iter().map(|r| r.power).sum();
        assert!((whole - 8.0 * PI).abs() < 1e-4 * whole, "Σ L dω = {whole}, 4π · 2");
        // A tilted plane cuts regions with its horizon: the fixed suns err
        // there, drawn ones do not (on average over the draws).
        for n in [Vec3::Y, Vec3::new(0.6, 0.8, 0.0), Vec3::new(0.0, -0.28, 0.96)] {
            let e = drawn_irradiance(&cut, n);
            assert!((e - 2.0 * PI).abs() < 2e-3 * 2.0 * PI, "facing {n}: E = {e}, πL = {}", 2.0 * PI);
        }
    }

    #[test]
    fn a_drawn_direction_lies_in_its_region_and_follows_the_light() {
        let (w, h) = CUT_GRID;
        let mut texels: Vec<Vec3> = (0..w * h).map(|_| Vec3::splat(0.01)).collect();
        let (px, py) = (48, 7);
        texels[py * w + px] = Vec3::new(500.0, 400.0, 300.0);
        let map = EnvironmentMap { name: "sun".into(), width: w as u32, height: h as u32, texels: texels.into() };
        let env = EnvironmentLookup::new(map, 1.0, 40.0);
        let cut = env.cut(16);
        let at = |x: usize, y: usize| env.direction((x as f32 + 0.5) / w as f32, (y as f32 + 0.5) / h as f32);
        // Within the texel: closer than the angle between neighbouring rows' centres.
        let texel = at(px, py).dot(at(px, py + 1));
        let mut drew_patch = 0;
        for (i, region) in cut.regions.iter().enumerate() {
            let r = region.rect;
            let patch_share = match (r.x.0..r.x.1).contains(&px) && (r.y.0..r.y.1).contains(&py) {
                true => cut.power[py * w + px] / region.power,
                false => 0.0,
            };
            for a in 0..64 {
                let d = cut.draw(i, (a as f32 + 0.5) / 64.0, ((a * 37 % 64) as f32 + 0.5) / 64.0);
                // Back to map coordinates (the turn undone).
                let u = (0.5 + atan2(d.x, -d.z) / (2.0 * PI) + env.turn).rem_euclid(1.0);
                let (x, y) = (((u * w as f32) as usize).min(w - 1), ((acos(d.y) / PI * h as f32) as usize).min(h - 1));
                assert!(r.x.0 <= x && x < r.x.1 && r.y.0 <= y && y < r.y.1, "region {i} {r:?} drew texel ({x}, {y})");
                if patch_share > 0.99 {
                    assert!(d.dot(at(px, py)) > texel, "the patch's region drew {d}");
                    drew_patch += 1;
                }
            }
        }
        assert_eq!(drew_patch, 64, "one region is the patch's alone");
    }

    #[test]
    fn a_texels_mean_direction_is_the_integral_of_its_directions() {
        // Uniform in cos θ and φ over the texel, integrated on a fine grid in f64.
        let (w, h, turn) = (64, 32, 0.3_f64);
        for (x, y) in [(0, 0), (17, 5), (40, 16), (63, 31)] {
            let k = 400;
            let (c0, c1) = ((PI64 * y as f64 / h as f64).cos(), (PI64 * (y + 1) as f64 / h as f64).cos());
            let mut sum = [0.0_f64; 3];
            for i in 0..k {
                for j in 0..k {
                    let c = c0 + (c1 - c0) * (i as f64 + 0.5) / k as f64;
                    let u = (x as f64 + (j as f64 + 0.5) / k as f64) / w as f64;
                    let (s, phi) = ((1.0 - c * c).sqrt(), (u - turn - 0.5) * 2.0 * PI64);
                    for (a, v) in sum.iter_mut().zip([s * phi.sin(), c, -s * phi.cos()]) {
                        *a += v / (k * k) as f64;
                    }
                }
            }
            let got = texel_mean_direction(x, y, (w, h), turn as f32);
            let want = Vec3::new(sum[0] as f32, sum[1] as f32, sum[2] as f32);
            assert!((got - want).length() < 2e-6, "texel ({x}, {y}): {got}, integral {want}");
            // The spread shortens it below the centre's unit length.
            assert!(got.length() < 1.0 - 1e-4, "texel ({x}, {y}): |mean| = {}", got.length());
        }
    }

    #[test]
    fn a_regions_mean_direction_is_its_draws_mean() {
        let (w, h) = CUT_GRID;
        let texels: Vec<Vec3> = (0..w * h).map(|i| Vec3::splat(1.0 + (i * 7919 % 13) as f32)).collect();
        let map = EnvironmentMap { name: "patches".into(), width: w as u32, height: h as u32, texels: texels.into() };
        let cut = EnvironmentLookup::new(map, 1.0, 25.0).cut(16);
        let k = 128;
        for (i, region) in cut.regions.iter().enumerate() {
            let mut sum = Vec3::ZERO;
            for a in 0..k * k {
                sum += cut.draw(i, ((a / k) as f32 + 0.5) / k as f32, ((a % k) as f32 + 0.5) / k as f32);
            }
            let mean = sum / (k * k) as f32;
            assert!((mean - region.mean_toward).length() < 1e-3, "region {i}: draws {mean}, {}", region.mean_toward);
        }
    }

    #[test]
    fn a_constant_map_of_one_texel_is_cut_on_the_grid() {
        let lights = fixed_suns(&lookup(EnvironmentMap::constant(Vec3::ONE)), 32);
        assert_eq!(lights.len(), 32);
        let e = upward_irradiance(&lights);
        assert!((e - 2.0 * PI).abs() < 2e-3 * 2.0 * PI, "{e}");
    }

    #[test]
    fn a_bright_patch_becomes_lights_from_its_direction() {
        let mut texels: Vec<Vec3> = (0..32 * 16).map(|_| Vec3::splat(0.01)).collect();
        texels[3 * 32 + 24] = Vec3::new(500.0, 400.0, 300.0);
        let env = lookup(EnvironmentMap { name: "sun".into(), width: 32, height: 16, texels: texels.into() });
        let patch = env.direction(24.5 / 32.0, 3.5 / 16.0);
        let lights = fixed_suns(&env, 16);
        // The cut spends its lights where the power is: most of them, and
        // nearly all the power, come from around the patch.
        let total: f32 = lights.iter().map(|l| l.rgb.x).sum();
        let near: f32 = lights.iter().filter(|l| l.toward.dot(patch) > 0.98).map(|l| l.rgb.x).sum();
        assert!(near > 0.9 * total, "{near} of {total} from the patch");
    }
}
