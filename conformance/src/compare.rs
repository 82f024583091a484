//! Comparisons under the rules of [`crate::tolerance`]: photon maps (key by
//! key, with a stated number of outliers, and flux per band) and images
//! (pixel by pixel, with a stated number of outlier pixels); and the
//! caustic's relative error against a long render, for convergence tests
//! and measurements.

use crate::tolerance::*;
use prismatic_core::model::photon::WHITE_BAND;
use prismatic_core::{Image, PhotonMap};

/// What a comparison found.
#[derive(Debug, Default)]
pub struct ParityReport {
    /// Photons compared.
    pub matched: usize,
    /// Keys missing on one side, or matched photons that landed elsewhere.
    pub outliers: usize,
    /// Worst relative difference of per-band total flux.
    pub worst_band_flux: f64,
}

/// Compares two photon maps (both in canonical order) under `tol`.
pub fn compare_maps(
    expected: &PhotonMap,
    got: &PhotonMap,
    bands: usize,
    tol: Tolerance,
) -> Result<ParityReport, String> {
    let (a, b) = (&expected.photons, &got.photons);
    let mut report = ParityReport::default();
    // Matched outliers beyond ten times the tolerance (said when it fails).
    let mut far = 0;
    let band_of = |band: u16| if band == WHITE_BAND { bands } else { usize::from(band) };
    // Per band: photons on one side only, and their flux on each side.
    let mut lone = vec![(0usize, 0.0f64, 0.0f64); bands + 1];
    let s = &expected.stats;
    let flux_abs = tol.flux_rel * (s.flux_emitted / s.emitted.max(1) as f64) as f32;
    let (mut i, mut j) = (0, 0);
    while i < a.len() || j < b.len() {
        match (a.get(i), b.get(j)) {
            (Some(x), Some(y)) if x.key() == y.key() => {
                let within = |scale: f32| {
                    (0..3).all(|k| {
                        close(x.position[k], y.position[k], scale * tol.position_rel, scale * tol.position_abs)
                    }) && close(x.flux, y.flux, scale * tol.flux_rel, scale * flux_abs)
                };
                if !within(1.0) {
                    report.outliers += 1;
                    far += usize::from(!within(10.0));
                }
                report.matched += 1;
                i += 1;
                j += 1;
            }
            (Some(x), Some(y)) if x.key() < y.key() => {
                report.outliers += 1;
                lone_photon(&mut lone[band_of(x.band)], x.flux, 0.0);
                i += 1;
            }
            (Some(x), None) => {
                report.outliers += 1;
                lone_photon(&mut lone[band_of(x.band)], x.flux, 0.0);
                i += 1;
            }
            (_, Some(y)) => {
                report.outliers += 1;
                lone_photon(&mut lone[band_of(y.band)], 0.0, y.flux);
                j += 1;
            }
            (None, None) => break,
        }
    }
    let allowed = MIN_OUTLIERS.max((tol.outlier_fraction * a.len().max(b.len()) as f64) as usize);
    if report.outliers > allowed {
        return Err(format!(
            "{} outlier photons of {} (allowed {allowed}; {far} beyond 10× the tolerance)",
            report.outliers,
            a.len()
        ));
    }
    let per_band = |m: &PhotonMap| {
        let mut f = vec![0.0f64; bands + 1];
        for p in &m.photons {
            f[band_of(p.band)] += f64::from(p.flux);
        }
        f
    };
    let (fa, fb) = (per_band(expected), per_band(got));
    let total: f64 = fa.iter().sum();
    for (band, (x, y)) in fa.iter().zip(&fb).enumerate() {
        // A path that took the other branch at an edge (an allowed outlier)
        // takes its photons' flux along: up to MIN_OUTLIERS such photons
        // of a band are left out of its totals; more are a band's fault.
        let (count, lone_x, lone_y) = lone[band];
        let (x, y) = if count <= MIN_OUTLIERS { (&(x - lone_x), &(y - lone_y)) } else { (x, y) };
        // Bands that carry almost nothing are compared against the whole map's flux.
        let rel = (x - y).abs() / x.abs().max(y.abs()).max(1e-3 * total).max(f64::MIN_POSITIVE);
        report.worst_band_flux = report.worst_band_flux.max(rel);
        if rel > BAND_FLUX_REL.max(tol.outlier_fraction) {
            return Err(format!("band {band}: total flux {x} vs {y} ({:.3} % apart)", rel * 100.0));
        }
    }
    Ok(report)
}

fn lone_photon((count, x, y): &mut (usize, f64, f64), flux_x: f32, flux_y: f32) {
    *count += 1;
    *x += f64::from(flux_x);
    *y += f64::from(flux_y);
}

/// Compares two images pixel by pixel under `tol`.
pub fn compare_images(expected: &Image, got: &Image, tol: Tolerance) -> Result<usize, String> {
    if (expected.width, expected.height) != (got.width, got.height) {
        return Err(format!("sizes differ: {}x{} vs {}x{}", expected.width, expected.height, got.width, got.height));
    }
    let differing = |scale: f32| {
        let pairs = expected.pixels.iter().zip(&got.pixels);
        pairs.filter(|(a, b)| !(0..3).all(|k| close(a[k], b[k], scale * tol.pixel_rel, scale * tol.pixel_abs))).count()
    };
    let bad = differing(1.0);
    let allowed = (tol.pixel_outlier_fraction * expected.pixels.len() as f64).ceil() as usize;
    if bad > allowed {
        return Err(format!(
            "{bad} of {} pixels differ (allowed {allowed}; {} beyond 10× the tolerance)",
            expected.pixels.len(),
            differing(10.0)
        ));
    }
    Ok(bad)
}

/// Pearson correlation of two images' channel values (1: the same picture
/// up to brightness and offset). Images of different sizes correlate 0.
pub fn image_correlation(a: &Image, b: &Image) -> f64 {
    if (a.width, a.height) != (b.width, b.height) {
        return 0.0;
    }
    let values = |img: &Image| img.pixels.iter().flat_map(|p| p.to_array()).map(f64::from).collect::<Vec<_>>();
    let (x, y) = (values(a), values(b));
    let n = x.len() as f64;
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let (mut sxy, mut sxx, mut syy) = (0.0, 0.0, 0.0);
    for (u, v) in x.iter().zip(&y) {
        sxy += (u - mx) * (v - my);
        sxx += (u - mx) * (u - mx);
        syy += (v - my) * (v - my);
    }
    if sxx == 0.0 || syy == 0.0 { 0.0 } else { sxy / (sxx * syy).sqrt() }
}

/// The caustic alone of `image` over its `base`: per pixel, the sum of R,
/// G and B of the difference.
pub fn caustic_of(image: &Image, base: &Image) -> Vec<f64> {
    image.pixels.iter().zip(&base.pixels).map(|(a, b)| f64::from((*a - *b).element_sum())).collect()
}

/// relRMSE over the caustic: the RMSE over the pixels whose reference is
/// above 5 % of the reference's maximum, over the reference's mean there
/// (NaN when the reference has no caustic).
pub fn caustic_rel_rmse(got: &[f64], reference: &[f64]) -> f64 {
    let max = reference.iter().copied().fold(0.0, f64::max);
    let (mut squares, mut sum, mut n) = (0.0, 0.0, 0.0);
    for (g, r) in got.iter().zip(reference) {
        if *r > 0.05 * max {
            (squares, sum, n) = (squares + (g - r).powi(2), sum + r, n + 1.0);
        }
    }
    (squares / n).sqrt() / (sum / n)
}

#[cfg(test)]
mod tests {
    use super::*;
    use prismatic_core::model::photon::Photon;

    fn photon(emission: u32, band: u16, flux: f32) -> Photon {
        let position = [emission as f32, 0.0, 0.0];
        Photon { position, flux, direction_oct: 0, lambda_nm: 500.0, emission, band, bounces: 1 }
    }

    /// 10,000 photons of 1 W in two bands, and `lone` more of 10 W in
    /// band 0 that only the expected map has (a divergent path's).
    fn maps(lone: u32) -> (PhotonMap, PhotonMap) {
        let shared: Vec<Photon> = (0..10_000).map(|e| photon(e, (e % 2) as u16, 1.0)).collect();
        let mut expected = shared.clone();
        expected.extend((0..lone).map(|k| photon(20_000 + k, 0, 10.0)));
        let map = |photons| PhotonMap { photons, stats: Default::default() };
        (map(expected), map(shared))
    }

    #[test]
    fn a_bands_few_lone_photons_leave_its_totals_but_more_do_not() {
        let tol = Tolerance::STRICT;
        // Three lone photons hold 0.6 % of band 0: left out of its totals.
        let (expected, got) = maps(MIN_OUTLIERS as u32);
        assert!(compare_maps(&expected, &got, 2, tol).is_ok());
        // Four (within the map's outlier count of 10) move band 0 by 0.8 %.
        let (expected, got) = maps(MIN_OUTLIERS as u32 + 1);
        let err = compare_maps(&expected, &got, 2, tol).expect_err("four lone photons are the band's fault");
        assert!(err.starts_with("band 0"), "{err}");
    }
}
