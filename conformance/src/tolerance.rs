//! Every tolerance the parity tests use, with the reason for its size.
//! Float compare rule: `|a − b| ≤ max(rel · max(|a|, |b|), abs)`.

/// Photon positions: a backend that reorders or fuses f32 operations
/// (a GPU) differs by a few ulps per operation; over a path of up to a dozen
/// segments in scenes of size ~10 that is ≲ 1e-4 world units.
pub const POSITION_ABS: f32 = 1e-4;
/// Relative part of the position rule (f32 has 1.2e-7; 100 ulps of margin).
pub const POSITION_REL: f32 = 1e-5;
/// Photon flux is a product of 1/N factors: exact to an ulp or two.
pub const FLUX_REL: f32 = 1e-6;
/// Paths that took another branch at an edge (a Fresnel draw within an ulp
/// of R, a ray through an edge): at most this fraction of the photons…
pub const OUTLIER_FRACTION: f64 = 1e-3;
/// …or this many, whichever is larger (small maps).
pub const MIN_OUTLIERS: usize = 3;
/// Outlier fraction for the GPU on beams aimed exactly at a mesh vertex or
/// edge: which triangle such a ray meets is decided by one rounding, and a
/// GPU compiler may fuse multiply-adds (WGSL allows it), so a few more
/// photons than elsewhere take the other side (lavapipe: 7 of 5,502).
pub const KNIFE_EDGE_OUTLIER_FRACTION: f64 = 5e-3;
/// Total flux per band (the 0.1 %).
pub const BAND_FLUX_REL: f64 = 1e-3;
/// A pixel matches when each channel is within this relative difference…
pub const PIXEL_REL: f32 = 1e-3;
/// …or this absolute one (1/4 of an 8-bit step at mid-grey in linear light).
pub const PIXEL_ABS: f32 = 1e-3;
/// Pixels allowed to differ by more (a view ray through an edge, a gather
/// radius that an outlier photon crosses).
pub const PIXEL_OUTLIER_FRACTION: f64 = 2e-3;

/// The float compare rule.
pub fn close(a: f32, b: f32, rel: f32, abs: f32) -> bool {
    (a - b).abs() <= (rel * a.abs().max(b.abs())).max(abs)
}
