//! The names of settings as scene files and command-line flags write
//! them: band tables, estimators, wavelength sampling, photon sequences,
//! radius modes, white points, tone maps.

use prismatic_core::model::bands::BandSpec;
use prismatic_core::model::color::ToneMap;
use prismatic_core::model::scene::{Estimator, PhotonSequence, RadiusMode, ViewPaths, WavelengthSampling, WhitePoint};

/// Parses a band table name: `paper3`, `paper7` or a number of bands.
pub fn parse_bands(s: &str) -> Result<BandSpec, String> {
    match s {
        "paper3" => Ok(BandSpec::Paper3),
        "paper7" => Ok(BandSpec::Paper7),
        _ => s
            .parse::<u16>()
            .map(BandSpec::Physical)
            .map_err(|_| format!("must be \"paper3\", \"paper7\" or a number of bands, got \"{s}\"")),
    }
}

/// Parses an estimator name.
pub fn parse_estimator(s: &str) -> Result<Estimator, String> {
    match s {
        "paper" => Ok(Estimator::Paper),
        "density" => Ok(Estimator::Density),
        _ => Err(format!("unknown estimator \"{s}\"; expected paper or density")),
    }
}

/// Parses a wavelength-sampling name.
pub fn parse_wavelengths(s: &str) -> Result<WavelengthSampling, String> {
    WavelengthSampling::from_name(s)
        .ok_or_else(|| format!("unknown wavelength sampling \"{s}\"; expected split, random_band, continuous or hero"))
}

/// Parses a photon-sequence name.
pub fn parse_photon_sequence(s: &str) -> Result<PhotonSequence, String> {
    PhotonSequence::from_name(s).ok_or_else(|| format!("unknown photon sequence \"{s}\"; expected sobol or random"))
}

/// Parses a white point's name.
pub fn parse_white_point(s: &str) -> Result<WhitePoint, String> {
    WhitePoint::from_name(s).ok_or_else(|| format!("unknown white point \"{s}\"; expected E or D65"))
}

/// Parses a tone map's name.
pub fn parse_tone_map(s: &str) -> Result<ToneMap, String> {
    ToneMap::from_name(s)
        .ok_or_else(|| format!("unknown tone map \"{s}\"; expected clamp, reinhard, pbr_neutral or agx"))
}

/// Parses a view-paths name.
pub fn parse_view_paths(s: &str) -> Result<ViewPaths, String> {
    ViewPaths::from_name(s).ok_or_else(|| format!("unknown view paths \"{s}\"; expected centre, hero or sampled"))
}

/// Parses a radius-mode name.
pub fn parse_radius_mode(s: &str) -> Result<RadiusMode, String> {
    RadiusMode::from_name(s).ok_or_else(|| format!("unknown radius mode \"{s}\"; expected progressive or fixed"))
}
