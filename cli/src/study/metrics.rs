//! How far a render is from the reference: CIEDE2000 over the pixels the
//! caustic touches, RMSE in linear RGB, and the position of each band's
//! stripe.
//!
//! ΔE00 is computed on what the viewer sees: the pixel after the scene's
//! tone map, clipped to [0, 1] as the PNG is, converted from linear sRGB to
//! CIELAB (D65 white). A mean ΔE00 below 1 is not noticeable side by side;
//! 2.3 is the usual just-noticeable difference.

use glam::{DVec3, Vec3};
use prismatic_core::Image;
use prismatic_core::model::color::ToneMap;
use prismatic_core::model::photon::WHITE_BAND;
use prismatic_core::{BandTable, PhotonMap};

/// A pixel the reference caustic changes by more than this (ΔE00 between the
/// reference with and without caustic photons) counts as touched.
pub const CAUSTIC_MASK_DELTA_E: f64 = 0.5;

/// Errors of one render against the reference.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RenderError {
    /// Mean ΔE00 over the caustic pixels.
    pub delta_e: f64,
    /// RMSE of linear RGB over all pixels.
    pub rmse: f64,
    /// Mean distance of the band stripes' centroids from the reference's
    /// (world units); `None` when the scene has no stripes to compare.
    pub stripe: Option<f64>,
}

/// CIELAB (D65) of a displayed pixel: tone mapped, clipped, linear sRGB in.
pub fn lab(linear: Vec3, tone_map: ToneMap) -> DVec3 {
    let c = tone_map.apply(linear).as_dvec3().clamp(DVec3::ZERO, DVec3::ONE);
    let xyz = DVec3::new(
        0.412_456_4 * c.x + 0.357_576_1 * c.y + 0.180_437_5 * c.z,
        0.212_672_9 * c.x + 0.715_152_2 * c.y + 0.072_175_0 * c.z,
        0.019_333_9 * c.x + 0.119_192_0 * c.y + 0.950_304_1 * c.z,
    );
    let white = DVec3::new(0.950_47, 1.0, 1.088_83);
    let f = |t: f64| if t > 216.0 / 24_389.0 { t.cbrt() } else { (24_389.0 / 27.0 * t + 16.0) / 116.0 };
    let (fx, fy, fz) = (f(xyz.x / white.x), f(xyz.y / white.y), f(xyz.z / white.z));
    DVec3::new(116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz))
}

/// CIEDE2000 colour difference of two CIELAB colours (Sharma, Wu & Dalal
/// 2005, with k_L = k_C = k_H = 1).
pub fn ciede2000(lab1: DVec3, lab2: DVec3) -> f64 {
    use std::f64::consts::PI;
    let (l1, a1, b1) = (lab1.x, lab1.y, lab1.z);
    let (l2, a2, b2) = (lab2.x, lab2.y, lab2.z);
    let c_bar = ((a1 * a1 + b1 * b1).sqrt() + (a2 * a2 + b2 * b2).sqrt()) / 2.0;
    let c7 = c_bar.powi(7);
    let g = 0.5 * (1.0 - (c7 / (c7 + 25f64.powi(7))).sqrt());
    let (a1p, a2p) = ((1.0 + g) * a1, (1.0 + g) * a2);
    let (c1p, c2p) = ((a1p * a1p + b1 * b1).sqrt(), (a2p * a2p + b2 * b2).sqrt());
    let hue = |b: f64, a: f64| if b == 0.0 && a == 0.0 { 0.0 } else { b.atan2(a).rem_euclid(2.0 * PI) };
    let (h1p, h2p) = (hue(b1, a1p), hue(b2, a2p));
    let dl = l2 - l1;
    let dc = c2p - c1p;
    let dh = if c1p * c2p == 0.0 {
        0.0
    } else {
        let d = h2p - h1p;
        if d > PI {
            d - 2.0 * PI
        } else if d < -PI {
            d + 2.0 * PI
        } else {
            d
        }
    };
    let dhh = 2.0 * (c1p * c2p).sqrt() * (dh / 2.0).sin();
    let l_bar = (l1 + l2) / 2.0;
    let c_bar_p = (c1p + c2p) / 2.0;
    let h_bar = if c1p * c2p == 0.0 {
        h1p + h2p
    } else if (h1p - h2p).abs() <= PI {
        (h1p + h2p) / 2.0
    } else if h1p + h2p < 2.0 * PI {
        (h1p + h2p + 2.0 * PI) / 2.0
    } else {
        (h1p + h2p - 2.0 * PI) / 2.0
    };
    let deg = |d: f64| d.to_radians();
    let t = 1.0 - 0.17 * (h_bar - deg(30.0)).cos() + 0.24 * (2.0 * h_bar).cos() + 0.32 * (3.0 * h_bar + deg(6.0)).cos()
        - 0.20 * (4.0 * h_bar - deg(63.0)).cos();
    let d_theta = deg(30.0) * (-((h_bar.to_degrees() - 275.0) / 25.0).powi(2)).exp();
    let cp7 = c_bar_p.powi(7);
    let rc = 2.0 * (cp7 / (cp7 + 25f64.powi(7))).sqrt();
    let l50 = (l_bar - 50.0).powi(2);
    let sl = 1.0 + 0.015 * l50 / (20.0 + l50).sqrt();
    let sc = 1.0 + 0.045 * c_bar_p;
    let sh = 1.0 + 0.015 * c_bar_p * t;
    let rt = -(2.0 * d_theta).sin() * rc;
    let (x, y, z) = (dl / sl, dc / sc, dhh / sh);
    (x * x + y * y + z * z + rt * y * z).sqrt()
}

/// The pixels the reference caustic touches: where it changes the reference
/// by more than [`CAUSTIC_MASK_DELTA_E`].
pub fn caustic_mask(reference: &Image, without_caustics: &Image, tone_map: ToneMap) -> Vec<bool> {
    reference
        .pixels
        .iter()
        .zip(&without_caustics.pixels)
        .map(|(&a, &b)| ciede2000(lab(a, tone_map), lab(b, tone_map)) > CAUSTIC_MASK_DELTA_E)
        .collect()
}

/// Mean ΔE00 between two images over the pixels of `mask`.
pub fn mean_delta_e(a: &Image, b: &Image, mask: &[bool], tone_map: ToneMap) -> f64 {
    let (sum, n) = a
        .pixels
        .iter()
        .zip(&b.pixels)
        .zip(mask)
        .filter(|(_, m)| **m)
        .fold((0.0, 0usize), |(s, n), ((p, q), _)| (s + ciede2000(lab(*p, tone_map), lab(*q, tone_map)), n + 1));
    if n == 0 { 0.0 } else { sum / n as f64 }
}

/// Root-mean-square difference of linear RGB over all pixels and channels.
pub fn rmse(a: &Image, b: &Image) -> f64 {
    let sum: f64 = a.pixels.iter().zip(&b.pixels).map(|(p, q)| (*p - *q).as_dvec3().length_squared()).sum();
    (sum / (3 * a.pixels.len().max(1)) as f64).sqrt()
}

/// Flux-weighted sums of stored photon positions per band of a fine table,
/// from which the centroid of any wavelength interval's stripe follows.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StripeSums {
    /// Per fine band: its wavelength interval, Σ flux, Σ flux · position.
    pub bands: Vec<((f32, f32), f64, DVec3)>,
}

impl StripeSums {
    /// Empty sums for `table`'s bands.
    pub fn new(table: &BandTable) -> Self {
        StripeSums { bands: table.bands().iter().map(|b| (b.interval_nm, 0.0, DVec3::ZERO)).collect() }
    }

    /// Adds a photon map traced with this table (white photons are ignored).
    pub fn add(&mut self, map: &PhotonMap) {
        for p in map.photons.iter().filter(|p| p.band != WHITE_BAND) {
            let (_, flux, moment) = &mut self.bands[usize::from(p.band)];
            *flux += f64::from(p.flux);
            *moment += p.pos().as_dvec3() * f64::from(p.flux);
        }
    }

    /// Centroid of the light in `interval` nm: each fine band counts with the
    /// fraction of its interval that lies inside. `None` when no light falls there.
    pub fn centroid(&self, interval: (f32, f32)) -> Option<DVec3> {
        let (mut flux, mut moment) = (0.0, DVec3::ZERO);
        for &((lo, hi), f, m) in &self.bands {
            let overlap = (hi.min(interval.1) - lo.max(interval.0)).max(0.0) / (hi - lo);
            flux += f * f64::from(overlap);
            moment += m * f64::from(overlap);
        }
        (flux > 0.0).then(|| moment / flux)
    }
}

/// Mean distance between each band's stripe centroid (`own`, traced with
/// `table`) and the reference's centroid of the same wavelength interval,
/// over the bands that have light in both.
pub fn stripe_error(own: &StripeSums, table: &BandTable, reference: &StripeSums) -> Option<f64> {
    let distances: Vec<f64> = table
        .bands()
        .iter()
        .filter_map(|b| Some((own.centroid(b.interval_nm)? - reference.centroid(b.interval_nm)?).length()))
        .collect();
    (!distances.is_empty()).then(|| distances.iter().sum::<f64>() / distances.len() as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Pairs and ΔE00 from Sharma, Wu & Dalal (2005), Table 1.
    const SHARMA: [([f64; 3], [f64; 3], f64); 8] = [
        ([50.0, 2.6772, -79.7751], [50.0, 0.0, -82.7485], 2.0425),
        ([50.0, 3.1571, -77.2803], [50.0, 0.0, -82.7485], 2.8615),
        ([50.0, 0.0, 0.0], [50.0, -1.0, 2.0], 2.3669),
        ([50.0, 2.5, 0.0], [50.0, 0.0, -2.5], 4.3065),
        ([50.0, 2.5, 0.0], [73.0, 25.0, -18.0], 27.1492),
        ([60.2574, -34.0099, 36.2677], [60.4626, -34.1751, 39.4387], 1.2644),
        ([22.7233, 20.0904, -46.6940], [23.0331, 14.9730, -42.5619], 2.0373),
        ([90.9257, -0.5406, -0.9208], [88.6381, -0.8985, -0.7239], 1.5381),
    ];

    #[test]
    fn ciede2000_matches_sharmas_test_data() {
        for (a, b, expected) in SHARMA {
            let (a, b) = (DVec3::from(a), DVec3::from(b));
            assert!((ciede2000(a, b) - expected).abs() < 1e-4, "{a} {b}: {} vs {expected}", ciede2000(a, b));
            assert!((ciede2000(b, a) - expected).abs() < 1e-4, "symmetric");
        }
        assert_eq!(ciede2000(DVec3::new(50.0, 10.0, -5.0), DVec3::new(50.0, 10.0, -5.0)), 0.0);
    }

    #[test]
    fn lab_of_white_black_and_grey() {
        assert!((lab(Vec3::ONE, ToneMap::Clamp) - DVec3::new(100.0, 0.0, 0.0)).abs().max_element() < 1e-3);
        assert!(lab(Vec3::ZERO, ToneMap::Clamp).abs().max_element() < 1e-9);
        // 18 % grey is L* ≈ 49.5; over-bright pixels clip as the PNG does.
        assert!((lab(Vec3::splat(0.18), ToneMap::Clamp).x - 49.496).abs() < 1e-2);
        assert_eq!(lab(Vec3::splat(5.0), ToneMap::Clamp), lab(Vec3::ONE, ToneMap::Clamp));
    }

    #[test]
    fn stripe_centroids_weight_partial_overlaps() {
        let mut sums =
            StripeSums { bands: vec![((400.0, 500.0), 0.0, DVec3::ZERO), ((500.0, 600.0), 0.0, DVec3::ZERO)] };
        sums.bands[0] = ((400.0, 500.0), 2.0, DVec3::new(0.0, 2.0, 0.0)); // centroid y = 1
        sums.bands[1] = ((500.0, 600.0), 2.0, DVec3::new(0.0, 6.0, 0.0)); // centroid y = 3
        assert_eq!(sums.centroid((400.0, 600.0)), Some(DVec3::new(0.0, 2.0, 0.0)));
        // Half of the first band, all of the second: (1·1 + 2·3)/3.
        assert_eq!(sums.centroid((450.0, 600.0)), Some(DVec3::new(0.0, 7.0 / 3.0, 0.0)));
        assert_eq!(sums.centroid((700.0, 750.0)), None);
    }
}
