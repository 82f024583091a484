//! Every tolerance the parity tests use, with the reason for its size, in
//! two sets: [`Tolerance::STRICT`] for backends whose arithmetic rounds as
//! the reference's does, [`Tolerance::RELAXED`] for a GPU's compiler
//! ([`Arithmetic`]). Float compare rule: `|a − b| ≤ max(rel · max(|a|, |b|), abs)`.

use prismatic_core::Arithmetic;

/// How closely two backends' photon maps and images must agree.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerance {
    /// Photon positions, relative part.
    pub position_rel: f32,
    /// Photon positions, absolute part (world units).
    pub position_abs: f32,
    /// Photon flux, relative to the larger of the two or to the mean flux
    /// a photon of the map was emitted with (a weight near 0, as at a
    /// spot's soft edge, keeps its rounding as an absolute error).
    pub flux_rel: f32,
    /// Photons allowed to be outliers (missing on one side, or elsewhere),
    /// as a fraction of the map (at least [`MIN_OUTLIERS`]); each band's
    /// total flux may move by as much (an outlier takes its flux along).
    pub outlier_fraction: f64,
    /// A pixel matches when each channel is within this relative difference…
    pub pixel_rel: f32,
    /// …or this absolute one.
    pub pixel_abs: f32,
    /// Pixels allowed to differ by more.
    pub pixel_outlier_fraction: f64,
}

impl Tolerance {
    /// For backends with [`Arithmetic::Strict`] (the reference, the CPU,
    /// lavapipe):
    /// - positions: a backend that reorders or fuses an f32 operation here
    ///   and there differs by a few ulps per operation; over a path of up to
    ///   a dozen segments in scenes of size ~10 that is ≲ 1e-4 world units
    ///   (relative: f32 has 1.2e-7; 100 ulps of margin);
    /// - flux is a product of 1/N factors: exact to an ulp or two;
    /// - outliers are paths that took another branch at an edge (a Fresnel
    ///   draw within an ulp of R, a ray through an edge): 0.1 %;
    /// - pixels: 1e-3 relative, or 1/4 of an 8-bit step at mid-grey in
    ///   linear light; 0.2 % may differ by more (a view ray through an edge,
    ///   a gather radius that an outlier photon crosses).
    pub const STRICT: Tolerance = Tolerance {
        position_rel: 1e-5,
        position_abs: 1e-4,
        flux_rel: 1e-6,
        outlier_fraction: 1e-3,
        pixel_rel: 1e-3,
        pixel_abs: 1e-3,
        pixel_outlier_fraction: 2e-3,
    };

    /// For a GPU's compiler ([`Arithmetic::Relaxed`]), measured on an NVIDIA
    /// H200 (2026-11-26, docs `measurements/gpu.md`): half the photons land
    /// within 5e-7 of the reference and 97 % within 1e-4, but the rest
    /// have a long tail (a grazing hit on a far wall, a path through a
    /// caustic's focus, a hero wavelength one ulp apart through the prism
    /// go on from their few-ulp start): 0.2–0.3 % beyond 1e-3. Flux is
    /// exact to an ulp or two but where a photon carries a weight of its
    /// own: aimed at glass under a soft-edged spot (the falloff, a ratio of
    /// differences of cosines, over the aiming's density) it was up to
    /// 1.3e-5 apart in random scene 8 (median 1.1e-6, 99 % within 5.1e-6),
    /// so 1e-4; where the falloff is near 0 its difference of cosines
    /// cancels, and random scene 11's faintest photons (1e-8 of a photon's
    /// 0.014) were 1.5 % apart, 1.6e-10 in absolute terms (2026-11-27),
    /// hence the absolute part. Images follow the photons: a gather radius
    /// crossed by a moved photon changes a caustic pixel by a percent.
    /// The H200 meets the image rules since the sphere's normal is
    /// normalised (it had lost visible points behind glass to false total
    /// internal reflection); see `docs/src/measurements/gpu.md` for what it
    /// still fails.
    pub const RELAXED: Tolerance = Tolerance {
        position_rel: 1e-3,
        position_abs: 1e-3,
        flux_rel: 1e-4,
        outlier_fraction: 5e-3,
        pixel_rel: 1e-2,
        pixel_abs: 1e-3,
        pixel_outlier_fraction: 1e-2,
    };

    /// The set for a backend's arithmetic.
    pub fn of(arithmetic: Arithmetic) -> Tolerance {
        match arithmetic {
            Arithmetic::Strict => Tolerance::STRICT,
            Arithmetic::Relaxed => Tolerance::RELAXED,
        }
    }

    /// This set with at least `fraction` of the photons allowed as outliers.
    pub fn allowing_outliers(self, fraction: f64) -> Tolerance {
        Tolerance { outlier_fraction: self.outlier_fraction.max(fraction), ..self }
    }

    /// This set for the images of a scene whose visible points on rough
    /// surfaces gather (`EffectPlan::rough_gathers`): pixels within
    /// [`ROUGH_GATHER_PIXEL_REL`] at least. Such a gather weighs each
    /// photon by the surface's BSDF toward the eye, whose lobe moves with
    /// the photon's direction: a direction rounded to the neighbouring
    /// 16-bit octahedral code (0.004°, δ = 7e-5 rad) by a backend a few
    /// ulps apart moves D, so the photon's weight, by about 4θδ/α², up to
    /// 1 % at α = 0.1 off the lobe's peak; a pixel whose gather a few such
    /// photons carry moves by a few tenths of a percent (lavapipe against
    /// the reference on `frosted` at 96×96, one pass of 4,000 photons:
    /// 185 pixels past 1e-3 in a channel, none past 1e-2 but a dark
    /// channel's 1.1e-3 of 0.043; 2026-11-30).
    pub fn with_rough_gathers(self) -> Tolerance {
        Tolerance { pixel_rel: self.pixel_rel.max(ROUGH_GATHER_PIXEL_REL), ..self }
    }
}

/// Pixels' relative tolerance where rough surfaces gather ([`Tolerance::with_rough_gathers`]).
pub const ROUGH_GATHER_PIXEL_REL: f32 = 1e-2;

/// Outliers allowed however small the map.
pub const MIN_OUTLIERS: usize = 3;
/// Outlier fraction for the GPU on beams aimed exactly at a mesh vertex or
/// edge: which triangle such a ray meets is decided by one rounding, and a
/// GPU compiler may fuse multiply-adds (WGSL allows it), so a few more
/// photons than elsewhere take the other side (lavapipe: 7 of 5,502; an
/// NVIDIA H200: 28 of 5,544, none beyond ten times the tolerance, on
/// 2026-11-27).
pub const KNIFE_EDGE_OUTLIER_FRACTION: f64 = 1e-2;
/// Total flux per band (the 0.1 %), or the outlier fraction where
/// that is larger; up to [`MIN_OUTLIERS`] photons of a band found on one
/// side only are left out of its totals (one path that took the other
/// branch at an edge: since an indirect path carries its whole flux after
/// dispersive glass, its few photons can hold a percent of a band's flux
/// in a small map).
pub const BAND_FLUX_REL: f64 = 1e-3;

/// The float compare rule.
pub fn close(a: f32, b: f32, rel: f32, abs: f32) -> bool {
    (a - b).abs() <= (rel * a.abs().max(b.abs())).max(abs)
}
