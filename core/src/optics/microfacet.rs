//! The GGX (Trowbridge–Reitz) microfacet model, the scalar reference for
//! rough metals and rough glass: the normal distribution D, Smith's
//! height-correlated masking-shadowing, the visible normals' sampling
//! (Heitz 2018) and density, refraction through a facet (Walter et al.
//! 2007) and a conductor's reflectance. Directions are in the shading
//! frame, whose normal is +z; α is glTF's roughness squared.

use crate::util::math::{sin_cos_turns, sqrt};
use core::f32::consts::PI;
use glam::Vec3;

/// The smallest α the model takes: below it D's peak (1/πα²) overflows
/// what a pass's f32 sums keep, and the surface is a mirror to the eye.
pub const MIN_ALPHA: f32 = 1e-4;

/// The smallest α at which a view path's visible point gathers the
/// photons met on a rough surface ([`Ggx::gathers`]). A gather weighs each
/// photon within its radius by the BSDF from the photon's direction to the
/// eye; a lobe of width α holds a share of about α² of the directions a
/// caustic's photons arrive from, so as α falls fewer photons carry the
/// estimate, each with more weight: at 0.1 a caustic's gathered error is
/// 1.6 times a diffuse floor's, at 0.04 3.5 times, while light tracing's
/// stays near the diffuse floor's (docs: method/rough-surfaces.md). Below
/// it light tracing alone brings that light, where the camera sees the
/// surface directly.
pub const GATHER_ALPHA: f32 = 0.1;

/// An isotropic GGX distribution of microfacet normals.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ggx {
    /// Its width α (glTF: roughness²), at least [`MIN_ALPHA`].
    pub alpha: f32,
}

impl Ggx {
    /// The distribution of glTF's perceptual `roughness` ∈ [0, 1]: α = roughness².
    pub fn from_roughness(roughness: f32) -> Self {
        Ggx { alpha: (roughness * roughness).max(MIN_ALPHA) }
    }

    /// These facets where a roughness map's texel `scale` (in [0, 1])
    /// scales the roughness, so α by its square; `None` where it is 0
    /// (polished there).
    #[inline]
    pub fn scaled(self, scale: f32) -> Option<Self> {
        let alpha = self.alpha * (scale * scale);
        (alpha > 0.0).then(|| Ggx { alpha: alpha.max(MIN_ALPHA) })
    }

    /// Whether these facets are rough enough for a visible point to gather
    /// the photons met on them (α at least [`GATHER_ALPHA`]).
    #[inline]
    pub fn gathers(&self) -> bool {
        self.alpha >= GATHER_ALPHA
    }

    /// D(m): the density of microfacet normals `m` per solid angle, weighted
    /// so that ∫ D(m) m_z dω = 1. Zero below the horizon.
    pub fn d(&self, m: Vec3) -> f32 {
        if m.z <= 0.0 {
            return 0.0;
        }
        let a2 = self.alpha * self.alpha;
        let t = m.z * m.z * (a2 - 1.0) + 1.0;
        a2 / (PI * t * t)
    }

    /// Smith's Λ(ω) for GGX: (√(1 + x) − 1)/2 = x / (2(1 + √(1 + x))),
    /// x = α² tan² θ, the second form exact near the normal.
    pub fn lambda(&self, w: Vec3) -> f32 {
        let c2 = w.z * w.z;
        if c2 <= 0.0 {
            return f32::INFINITY;
        }
        let a2_tan2 = self.alpha * self.alpha * (1.0 - c2).max(0.0) / c2;
        0.5 * a2_tan2 / (1.0 + sqrt(1.0 + a2_tan2))
    }

    /// G1(ω) = 1/(1 + Λ(ω)): the share of the microsurface seen from `w`
    /// that is not masked.
    pub fn g1(&self, w: Vec3) -> f32 {
        if w.z <= 0.0 { 0.0 } else { 1.0 / (1.0 + self.lambda(w)) }
    }

    /// G2(ωo, ωi) = 1/(1 + Λ(ωo) + Λ(ωi)): height-correlated masking and
    /// shadowing for reflection (both above the surface).
    pub fn g2(&self, wo: Vec3, wi: Vec3) -> f32 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return 0.0;
        }
        1.0 / (1.0 + self.lambda(wo) + self.lambda(wi))
    }

    /// G2(ωo, ωi) = 1/(1 + Λ(ωo) + Λ(ωi)) for a pair on either side of the
    /// surface (Λ depends on the cosine's size only): refraction's masking
    /// and shadowing, in the height-correlated form pbrt-v4 takes for both
    /// reflection and transmission. Zero when either grazes.
    pub fn g2_through(&self, wo: Vec3, wi: Vec3) -> f32 {
        if wo.z == 0.0 || wi.z == 0.0 {
            return 0.0;
        }
        1.0 / (1.0 + self.lambda(wo) + self.lambda(wi))
    }

    /// D_ωo(m) = G1(ωo) max(0, ωo·m) D(m) / ωo_z: the density of the normals
    /// that `wo` sees, which [`Ggx::sample_visible_normal`] draws.
    pub fn visible_normal_pdf(&self, wo: Vec3, m: Vec3) -> f32 {
        if wo.z <= 0.0 {
            return 0.0;
        }
        self.g1(wo) * wo.dot(m).max(0.0) * self.d(m) / wo.z
    }

    /// A normal drawn with density [`Ggx::visible_normal_pdf`] for `wo`
    /// (above the surface) from two uniform numbers (Heitz 2018): a point
    /// on the projected hemisphere of the stretched configuration, its
    /// second coordinate bent toward the visible half, unstretched.
    pub fn sample_visible_normal(&self, wo: Vec3, u1: f32, u2: f32) -> Vec3 {
        let a = self.alpha;
        let vh = Vec3::new(a * wo.x, a * wo.y, wo.z).normalize();
        let len2 = vh.x * vh.x + vh.y * vh.y;
        let t1 = if len2 > 0.0 { Vec3::new(-vh.y, vh.x, 0.0) / sqrt(len2) } else { Vec3::X };
        let t2 = vh.cross(t1);
        let r = sqrt(u1);
        let (sin_phi, cos_phi) = sin_cos_turns(u2);
        let p1 = r * cos_phi;
        let s = 0.5 * (1.0 + vh.z);
        let p2 = (1.0 - s) * sqrt((1.0 - p1 * p1).max(0.0)) + s * r * sin_phi;
        let nh = t1 * p1 + t2 * p2 + vh * sqrt((1.0 - p1 * p1 - p2 * p2).max(0.0));
        Vec3::new(a * nh.x, a * nh.y, nh.z.max(0.0)).normalize()
    }

    /// The density per solid angle of `wi` reflected about a visible normal
    /// drawn for `wo`: D_ωo(m) / (4 ωo·m), m the half vector.
    pub fn reflection_pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        let m = (wo + wi).normalize_or_zero();
        let cos = wo.dot(m);
        if cos <= 0.0 || wi.z <= 0.0 { 0.0 } else { self.visible_normal_pdf(wo, m) / (4.0 * cos) }
    }

    /// The reflection BRDF D G2 F / (4 ωo_z ωi_z) of a surface whose facets
    /// reflect `f` (zero unless both are above it).
    pub fn reflection(&self, wo: Vec3, wi: Vec3, f: f32) -> f32 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return 0.0;
        }
        let m = (wo + wi).normalize();
        self.d(m) * self.g2(wo, wi) * f / (4.0 * wo.z * wi.z)
    }

    /// The facet normal (z ≥ 0) that refracts `wo` (above) into `wi`
    /// (below) for the index ratio `eta` = n_below/n_above: the generalised
    /// half vector ±(ωo + η ωi) (Walter et al. 2007, eq. 16). `None` when
    /// no facet does (the two are not on its opposite sides).
    pub fn refraction_normal(wo: Vec3, wi: Vec3, eta: f32) -> Option<Vec3> {
        let h = wo + wi * eta;
        let m = if h.z < 0.0 { -h } else { h }.normalize_or_zero();
        (m != Vec3::ZERO && wo.dot(m) > 0.0 && wi.dot(m) < 0.0 && wo.z > 0.0 && wi.z < 0.0).then_some(m)
    }

    /// The density per solid angle of `wi` (below) refracted through a
    /// visible normal drawn for `wo` (above), index ratio `eta` =
    /// n_below/n_above, before Fresnel's choice: D_ωo(m) η² |ωi·m| /
    /// (ωo·m + η ωi·m)² (the Jacobian of the half vector).
    pub fn refraction_pdf(&self, wo: Vec3, wi: Vec3, eta: f32) -> f32 {
        let Some(m) = Self::refraction_normal(wo, wi, eta) else { return 0.0 };
        let den = wo.dot(m) + eta * wi.dot(m);
        self.visible_normal_pdf(wo, m) * eta * eta * wi.dot(m).abs() / (den * den)
    }

    /// The transmission BTDF of facets that pass `t` of the light, seen
    /// from `wo` (above, index ratio `eta` = n_below/n_above) for light
    /// from `wi` (below): |ωo·m||ωi·m| / (ωo_z |ωi_z|) η² t D G2 / (ωo·m +
    /// η ωi·m)² (Walter et al. 2007, eq. 21, without the η² that radiance
    /// gains on entering a denser medium: the renderer's glass carries
    /// radiance across unscaled, as its photons carry flux, so the path
    /// weight of [`Ggx::refraction_pdf`]'s draw is t G2/G1).
    pub fn transmission(&self, wo: Vec3, wi: Vec3, eta: f32, t: f32) -> f32 {
        let Some(m) = Self::refraction_normal(wo, wi, eta) else { return 0.0 };
        let den = wo.dot(m) + eta * wi.dot(m);
        let jacobian = wo.dot(m) * wi.dot(m).abs() / (wo.z * wi.z.abs());
        jacobian * eta * eta * t * self.d(m) * self.g2_through(wo, wi) / (den * den)
    }

    /// A reflected direction for `wo` from two uniform numbers, and its
    /// weight BRDF·cos θi / pdf for facets that reflect 1: G2/G1(ωo) (`None`
    /// where the reflection leaves below the surface: the path ends).
    pub fn sample_reflection(&self, wo: Vec3, u1: f32, u2: f32) -> Option<(Vec3, f32)> {
        let m = self.sample_visible_normal(wo, u1, u2);
        let wi = m * (2.0 * wo.dot(m)) - wo;
        (wi.z > 0.0).then(|| (wi, self.g2(wo, wi) / self.g1(wo)))
    }
}

/// The unpolarised Fresnel reflectance of a conductor of complex index
/// `eta` + i`k` (relative to the outside) for light arriving with cosine
/// `cos_i`: the exact form with a² + b² = √((η² − k² − sin²θ)² + 4η²k²).
pub fn conductor_fresnel(cos_i: f32, eta: f32, k: f32) -> f32 {
    let c = cos_i.clamp(0.0, 1.0);
    let (c2, s2) = (c * c, 1.0 - c * c);
    let t0 = eta * eta - k * k - s2;
    let a2b2 = sqrt(t0 * t0 + 4.0 * eta * eta * k * k);
    let a = sqrt((0.5 * (a2b2 + t0)).max(0.0));
    let rs = (a2b2 + c2 - 2.0 * a * c) / (a2b2 + c2 + 2.0 * a * c);
    let rp = rs * (c2 * a2b2 + s2 * s2 - 2.0 * a * c * s2) / (c2 * a2b2 + s2 * s2 + 2.0 * a * c * s2);
    (0.5 * (rs + rp)).clamp(0.0, 1.0)
}

/// Quadrature over directions for the scattering tests.
#[cfg(test)]
pub(crate) mod quadrature {
    use glam::Vec3;

    /// The unit direction at polar angle `theta` and azimuth `phi` (radians).
    pub(crate) fn direction(theta: f64, phi: f64) -> Vec3 {
        Vec3::new((theta.sin() * phi.cos()) as f32, (theta.sin() * phi.sin()) as f32, theta.cos() as f32)
    }

    /// ∫ f(ω) dω over the directions whose cos θ is above `lowest` (0: the
    /// upper hemisphere, −1: the sphere) by the midpoint rule in (cos θ,
    /// φ), with `n` steps in each.
    pub(crate) fn integrate(n: usize, lowest: f64, f: impl Fn(Vec3) -> f64) -> f64 {
        let (dc, dp) = ((1.0 - lowest) / n as f64, 2.0 * core::f64::consts::PI / n as f64);
        let mut sum = 0.0;
        for i in 0..n {
            let theta = (1.0 - (i as f64 + 0.5) * dc).acos();
            for j in 0..n {
                sum += f(direction(theta, (j as f64 + 0.5) * dp));
            }
        }
        sum * dc * dp
    }
}

#[cfg(test)]
mod tests {
    use super::quadrature::{direction, integrate};
    use super::*;
    use crate::optics::fresnel::fresnel;
    use crate::util::rng::random_f32;

    const ALPHAS: [f32; 5] = [0.05, 0.1, 0.3, 0.6, 1.0];

    /// ∫ f(ω) dω over the upper hemisphere.
    fn hemisphere(n: usize, f: impl Fn(Vec3) -> f64) -> f64 {
        integrate(n, 0.0, f)
    }

    #[test]
    fn the_projected_normals_and_the_visible_normals_each_integrate_to_one() {
        for alpha in ALPHAS {
            let ggx = Ggx { alpha };
            // In θ for the narrow peaks: ∫ D cos θ sin θ 2π dθ.
            let n = 200_000;
            let dt = core::f64::consts::FRAC_PI_2 / n as f64;
            let projected: f64 = (0..n)
                .map(|i| {
                    let t = (i as f64 + 0.5) * dt;
                    f64::from(ggx.d(direction(t, 0.0))) * t.cos() * t.sin() * 2.0 * core::f64::consts::PI * dt
                })
                .sum();
            assert!((projected - 1.0).abs() < 1e-3, "α {alpha}: ∫ D cos θ = {projected}");
            if alpha >= 0.3 {
                for theta in [0.0f64, 0.7, 1.3, 1.55] {
                    let wo = direction(theta, 0.4);
                    let visible = hemisphere(800, |m| f64::from(ggx.visible_normal_pdf(wo, m)));
                    assert!((visible - 1.0).abs() < 3e-3, "α {alpha}, θo {theta}: ∫ D_ωo = {visible}");
                }
            }
        }
    }

    /// Pearson's χ² of `samples` draws of `draw` against `pdf` over bins of
    /// (s, φ), s = √(1 − cos θ) (which spreads a narrow lobe at the normal
    /// over several bins), bins expecting fewer than 5 pooled, and its
    /// degrees of freedom.
    fn chi_square(samples: u32, draw: impl Fn(u32) -> Vec3, pdf: impl Fn(Vec3) -> f64) -> (f64, usize) {
        let (nc, np) = (16usize, 32usize);
        let mut observed = vec![0f64; nc * np];
        let bin = |w: Vec3| {
            let s = (1.0 - f64::from(w.z)).max(0.0).sqrt();
            let c = (s * nc as f64).clamp(0.0, nc as f64 - 1.0) as usize;
            let phi = f64::from(w.y).atan2(f64::from(w.x)).rem_euclid(2.0 * core::f64::consts::PI);
            let p = (phi / (2.0 * core::f64::consts::PI) * np as f64).clamp(0.0, np as f64 - 1.0) as usize;
            c * np + p
        };
        for i in 0..samples {
            let w = draw(i);
            if w.z > 0.0 {
                observed[bin(w)] += 1.0;
            }
        }
        // Each bin's expected count by a 32 × 8 midpoint rule over it: dω = 2s ds dφ.
        let (sub_s, sub_p) = (32, 8);
        let (ds, dp) = (1.0 / (nc * sub_s) as f64, 2.0 * core::f64::consts::PI / (np * sub_p) as f64);
        let mut expected = vec![0f64; nc * np];
        for i in 0..nc * sub_s {
            let s = (i as f64 + 0.5) * ds;
            let theta = (1.0 - s * s).acos();
            for j in 0..np * sub_p {
                let w = direction(theta, (j as f64 + 0.5) * dp);
                expected[(i / sub_s) * np + j / sub_p] += pdf(w) * 2.0 * s * ds * dp * f64::from(samples);
            }
        }
        let (mut chi2, mut dof, mut pooled) = (0.0, 0usize, (0.0, 0.0));
        for (o, e) in observed.iter().zip(&expected) {
            if *e < 5.0 {
                pooled = (pooled.0 + o, pooled.1 + e);
            } else {
                chi2 += (o - e) * (o - e) / e;
                dof += 1;
            }
        }
        if pooled.1 > 0.0 {
            chi2 += (pooled.0 - pooled.1) * (pooled.0 - pooled.1) / pooled.1;
            dof += 1;
        }
        (chi2, dof - 1)
    }

    #[test]
    fn the_sampled_visible_normals_and_reflections_follow_their_densities() {
        let samples = 200_000;
        for alpha in [0.1, 0.3, 1.0] {
            let ggx = Ggx { alpha };
            for theta in [0.2f64, 1.0, 1.45] {
                let wo = direction(theta, 1.1);
                let u = |i: u32, d: u32| random_f32(7, i, d);
                let draws = [
                    chi_square(
                        samples,
                        |i| ggx.sample_visible_normal(wo, u(i, 0), u(i, 1)),
                        |m| f64::from(ggx.visible_normal_pdf(wo, m)),
                    ),
                    chi_square(
                        samples,
                        |i| ggx.sample_reflection(wo, u(i, 0), u(i, 1)).map_or(Vec3::NEG_Z, |(wi, _)| wi),
                        |wi| f64::from(ggx.reflection_pdf(wo, wi)),
                    ),
                ];
                for (what, (chi2, dof)) in ["visible normals", "reflections"].iter().zip(draws) {
                    // χ² of `dof` degrees has mean dof and deviation √(2 dof): 5 deviations is p < 1e-6.
                    let limit = dof as f64 + 5.0 * (2.0 * dof as f64).sqrt();
                    assert!(chi2 < limit, "α {alpha}, θo {theta}, {what}: χ² {chi2:.0} over {dof} degrees");
                }
            }
        }
    }

    #[test]
    fn the_sampled_refractions_follow_their_density() {
        // Refracted about a visible normal (Walter et al. 2007), binned
        // mirrored into the upper hemisphere, against Ggx::refraction_pdf;
        // into glass (η 1.5) and out of it (η 1/1.5, with total internal
        // reflection: those draws are dropped, and the density has none).
        let samples = 200_000;
        for alpha in [0.1, 0.3, 1.0] {
            let ggx = Ggx { alpha };
            for eta in [1.5f32, 1.0 / 1.5] {
                for theta in [0.2f64, 1.0, 1.45] {
                    let wo = direction(theta, 1.1);
                    let mirror = |w: Vec3| Vec3::new(w.x, w.y, -w.z);
                    let draw = |i: u32| {
                        let m = ggx.sample_visible_normal(wo, random_f32(9, i, 0), random_f32(9, i, 1));
                        crate::optics::fresnel::refract(-wo, m, 1.0, eta).map_or(Vec3::NEG_Z, mirror)
                    };
                    let (chi2, dof) = chi_square(samples, draw, |w| f64::from(ggx.refraction_pdf(wo, mirror(w), eta)));
                    let limit = dof as f64 + 5.0 * (2.0 * dof as f64).sqrt();
                    assert!(chi2 < limit, "α {alpha}, η {eta}, θo {theta}: χ² {chi2:.0} over {dof} degrees");
                }
            }
        }
    }

    #[test]
    fn a_conductor_that_reflects_everything_loses_only_what_single_scattering_loses() {
        // The white furnace: facets with F = 1 under a uniform environment.
        // Its directional albedo ∫ f cos θi dωi is below 1 by the light that
        // single scattering drops (what would bounce between facets), and
        // the sampled weights G2/G1 have the same mean. Measured (θo 0, 0.8,
        // 1.3): α 0.05: 0.997, 0.996, 0.977; α 0.1: 0.988, 0.981, 0.927;
        // α 0.3: 0.878, 0.844, 0.823; α 0.6: 0.590, 0.609, 0.722; α 1: 0.305,
        // 0.378, 0.583.
        for alpha in ALPHAS {
            let ggx = Ggx { alpha };
            for theta in [0.0f64, 0.8, 1.3] {
                let wo = direction(theta, 0.3);
                let n = 2_000;
                let evaluated = if alpha >= 0.3 {
                    Some(hemisphere(n, |wi| f64::from(ggx.reflection(wo, wi, 1.0) * wi.z)))
                } else {
                    None
                };
                let m = 100_000;
                let sampled: f64 = (0..m)
                    .map(|i| {
                        let w = ggx.sample_reflection(wo, random_f32(3, i, 0), random_f32(3, i, 1));
                        f64::from(w.map_or(0.0, |(_, weight)| weight))
                    })
                    .sum::<f64>()
                    / f64::from(m);
                assert!(sampled <= 1.0 + 1e-6, "α {alpha}, θo {theta}: albedo {sampled} gains energy");
                if let Some(e) = evaluated {
                    assert!((e - sampled).abs() < 0.01, "α {alpha}, θo {theta}: ∫ f cos {e}, sampled {sampled}");
                }
                assert!(sampled > 0.3, "α {alpha}, θo {theta}: albedo {sampled}");
                if alpha == 1.0 && theta == 0.0 {
                    // At α = 1 the facets are cosine-distributed; from the normal,
                    // θi = 2θm and G2 = (1 − 2u)/(1 − u), u = sin² θm: ∫₀^½ G2 du = 1 − ln 2.
                    let want = 1.0 - core::f64::consts::LN_2;
                    assert!((sampled - want).abs() < 0.005, "α 1 from the normal: {sampled}, 1 − ln 2 = {want}");
                }
            }
            // Seen from the normal, nothing is masked and a reflection stays
            // above the surface exactly where its facet is within 45° of the
            // normal: P(tan² θm < 1) = 1/(1 + α²) (GGX's tan² θm has CDF t/(α² + t)).
            let m = 100_000;
            let kept =
                (0..m).filter(|&i| ggx.sample_reflection(Vec3::Z, random_f32(5, i, 0), random_f32(5, i, 1)).is_some());
            let share = kept.count() as f64 / f64::from(m);
            let want = 1.0 / (1.0 + f64::from(alpha * alpha));
            assert!((share - want).abs() < 0.005, "α {alpha}: {share} of the reflections kept, {want} expected");
        }
    }

    #[test]
    fn a_conductors_fresnel_meets_the_dielectrics_and_the_normal_incidence_form() {
        for cos in [1.0f32, 0.8, 0.4, 0.1] {
            // No extinction: a dielectric of that index.
            let (got, want) = (conductor_fresnel(cos, 1.5, 0.0), fresnel(cos, 1.0, 1.5));
            assert!((got - want).abs() < 1e-5, "cos {cos}: {got} vs {want}");
        }
        // Gold near 550 nm: ((η − 1)² + k²)/((η + 1)² + k²) at normal incidence, 1 at grazing.
        let (eta, k) = (0.43f32, 2.45f32);
        let normal = ((eta - 1.0).powi(2) + k * k) / ((eta + 1.0).powi(2) + k * k);
        assert!((conductor_fresnel(1.0, eta, k) - normal).abs() < 1e-5);
        assert!(conductor_fresnel(0.0, eta, k) > 0.999);
    }
}
