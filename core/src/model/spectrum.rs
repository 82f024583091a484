//! Light spectra: what a light emits at each wavelength, relative to its
//! power (the power itself stays the light's radiant flux in W over the
//! visible range).
//!
//! Continuous spectra (the CIE illuminants E, D65, A and F11, a blackbody,
//! a tabulated spectrum) give a relative power at every wavelength; line
//! lamps (mercury, sodium, neon, hydrogen) emit only at their lines.
//! [`crate::sampling::light_spectrum`] turns either into the distribution
//! photons' wavelengths are drawn from.
//!
//! Sources: the CIE daylight components S0, S1, S2 (10 nm, CIE 15:2004
//! Table T.2) give D65 at x = 0.31271, y = 0.32902 (M1 = −0.295, M2 =
//! −0.689 as the CIE rounds them); A is the CIE's closed form (Planck with
//! c2 = 1.435·10⁷ nm·K at 2848 K); F11 is CIE 15:2004 Table T.6 (5 nm). The
//! lamps' lines are NIST Atomic Spectra Database air wavelengths with
//! rounded relative intensities (a real lamp's depend on its pressure and
//! current).

use crate::model::rgb_spectrum::smooth_power;
use crate::util::math::exp_f64;
use alloc::string::String;
use alloc::vec::Vec;
use core::fmt;

/// What a light emits across the spectrum.
#[derive(Clone, Debug, Default, PartialEq)]
pub enum Spectrum {
    /// A CIE standard illuminant.
    Illuminant(Illuminant),
    /// Planck's law at `kelvin`.
    Blackbody {
        /// Temperature in K.
        kelvin: f32,
    },
    /// Relative power `power` at wavelengths `nm` (strictly increasing),
    /// read by linear interpolation, zero outside.
    Tabulated {
        /// Wavelengths in nm.
        nm: Vec<f32>,
        /// Relative power at each.
        power: Vec<f32>,
    },
    /// A gas-discharge lamp: light only at its lines.
    Lamp(Lamp),
    /// The smooth spectrum of an RGB colour
    /// ([`crate::model::rgb_spectrum`]; see [`Spectrum::from_rgb`]).
    Smooth {
        /// The sigmoid's coefficients.
        coefficients: [f32; 3],
    },
    /// The equal-energy spectrum E (white in the paper's sense).
    #[default]
    EqualEnergy,
}

/// The named CIE illuminants (E is [`Spectrum::EqualEnergy`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Illuminant {
    /// Average daylight, 6504 K (sRGB's white).
    D65,
    /// Incandescent tungsten, 2856 K.
    A,
    /// A narrow-band tri-phosphor fluorescent tube, 4000 K.
    F11,
}

/// The line lamps.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Lamp {
    /// Low-pressure mercury: violet, blue, green and a yellow doublet.
    Mercury,
    /// Sodium: the D doublet.
    Sodium,
    /// Neon: red and orange lines.
    Neon,
    /// Hydrogen: the Balmer series.
    Hydrogen,
}

impl Lamp {
    /// Every lamp, for listings and error messages.
    pub const ALL: [Lamp; 4] = [Lamp::Mercury, Lamp::Sodium, Lamp::Neon, Lamp::Hydrogen];

    /// The scene-file name.
    pub fn name(self) -> &'static str {
        match self {
            Lamp::Mercury => "mercury",
            Lamp::Sodium => "sodium",
            Lamp::Neon => "neon",
            Lamp::Hydrogen => "hydrogen",
        }
    }

    /// The visible lines: (air wavelength in nm, relative power).
    pub fn lines(self) -> &'static [(f32, f32)] {
        match self {
            Lamp::Mercury => &[
                (404.656, 1800.0),
                (407.783, 150.0),
                (435.833, 4000.0),
                (546.074, 1100.0),
                (576.960, 240.0),
                (579.066, 280.0),
            ],
            Lamp::Sodium => &[(588.995, 2.0), (589.592, 1.0)],
            Lamp::Neon => &[
                (585.249, 20.0),
                (588.190, 10.0),
                (594.483, 5.0),
                (603.000, 10.0),
                (607.434, 10.0),
                (609.616, 10.0),
                (614.306, 10.0),
                (616.359, 10.0),
                (621.728, 10.0),
                (626.650, 10.0),
                (630.479, 10.0),
                (633.443, 10.0),
                (638.299, 10.0),
                (640.225, 20.0),
                (650.653, 15.0),
                (659.895, 10.0),
                (667.828, 5.0),
                (671.704, 7.0),
                (692.947, 10.0),
                (703.241, 8.0),
            ],
            Lamp::Hydrogen => &[(410.174, 70.0), (434.047, 90.0), (486.135, 180.0), (656.279, 500.0)],
        }
    }
}

impl Illuminant {
    /// Every named illuminant.
    pub const ALL: [Illuminant; 3] = [Illuminant::D65, Illuminant::A, Illuminant::F11];

    /// The scene-file name.
    pub fn name(self) -> &'static str {
        match self {
            Illuminant::D65 => "D65",
            Illuminant::A => "A",
            Illuminant::F11 => "F11",
        }
    }
}

impl Spectrum {
    /// Looks a named spectrum up: `E`, an illuminant (`D65`, `A`, `F11`) or
    /// a lamp (`mercury`, …), in any case.
    pub fn from_name(name: &str) -> Option<Spectrum> {
        if name.eq_ignore_ascii_case("E") {
            return Some(Spectrum::EqualEnergy);
        }
        let illuminant = Illuminant::ALL.into_iter().find(|i| i.name().eq_ignore_ascii_case(name));
        let lamp = Lamp::ALL.into_iter().find(|l| l.name().eq_ignore_ascii_case(name));
        illuminant.map(Spectrum::Illuminant).or(lamp.map(Spectrum::Lamp))
    }

    /// Every name [`Spectrum::from_name`] knows, for error messages.
    pub fn names() -> String {
        let mut names = String::from("E");
        for n in Illuminant::ALL.map(Illuminant::name).into_iter().chain(Lamp::ALL.map(Lamp::name)) {
            names.push_str(", ");
            names.push_str(n);
        }
        names
    }

    /// The smooth spectrum of linear RGB `rgb` (not negative), and the
    /// factor its light's power takes so that the light emits `rgb` times
    /// what a white light of that power emits: equal channels give the
    /// equal-energy spectrum (factor: the channel); others the spectrum of
    /// `rgb` over its largest channel m, whose light emits that colour at
    /// a mean relative power of s̄ (factor m·s̄).
    pub fn from_rgb(rgb: [f32; 3]) -> (Spectrum, f32) {
        let colours = crate::model::wavelength_rgb::WavelengthRgb::new();
        let rgb = glam::Vec3::from(rgb).max(glam::Vec3::ZERO);
        let m = rgb.max_element();
        if m <= 0.0 {
            return (Spectrum::EqualEnergy, 0.0);
        }
        match crate::model::rgb_spectrum::fit((rgb / m).as_dvec3(), &colours) {
            None => (Spectrum::EqualEnergy, m),
            Some(coefficients) => {
                let spectrum = Spectrum::Smooth { coefficients };
                let mean = crate::model::rgb_spectrum::mean_of(|nm| spectrum.power_at(nm));
                (spectrum, m * mean as f32)
            }
        }
    }

    /// True for the equal-energy spectrum, whose photons stay white until
    /// dispersive glass splits them.
    pub fn is_equal_energy(&self) -> bool {
        matches!(self, Spectrum::EqualEnergy)
    }

    /// The lines of a line spectrum.
    pub fn lines(&self) -> Option<&'static [(f32, f32)]> {
        match self {
            Spectrum::Lamp(lamp) => Some(lamp.lines()),
            _ => None,
        }
    }

    /// Relative power at `nm` of a continuous spectrum (0 for a lamp).
    pub fn power_at(&self, nm: f64) -> f64 {
        match self {
            Spectrum::EqualEnergy => 1.0,
            Spectrum::Illuminant(Illuminant::D65) => d65(nm),
            Spectrum::Illuminant(Illuminant::A) => planck_ratio(nm, 560.0, 1.435e7 / 2848.0),
            Spectrum::Illuminant(Illuminant::F11) => lerp_table(&F11, 380.0, 5.0, nm),
            Spectrum::Blackbody { kelvin } => planck_ratio(nm, 560.0, C2_NM_K / f64::from(*kelvin)),
            Spectrum::Tabulated { nm: at, power } => tabulated(at, power, nm),
            Spectrum::Smooth { coefficients } => smooth_power(*coefficients, nm),
            Spectrum::Lamp(_) => 0.0,
        }
    }
}

impl fmt::Display for Spectrum {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Spectrum::EqualEnergy => f.write_str("E"),
            Spectrum::Illuminant(i) => f.write_str(i.name()),
            Spectrum::Blackbody { kelvin } => write!(f, "blackbody {kelvin} K"),
            Spectrum::Tabulated { nm, .. } => write!(f, "tabulated ({} points)", nm.len()),
            Spectrum::Lamp(l) => write!(f, "{} lamp", l.name()),
            Spectrum::Smooth { coefficients: c } => write!(f, "smooth spectrum ({}, {}, {})", c[0], c[1], c[2]),
        }
    }
}

/// Planck's second radiation constant, in nm·K.
const C2_NM_K: f64 = 1.438_776_9e7;

/// Planck's law at `nm` relative to `reference_nm`, with c2/T = `c2_over_t` (nm).
fn planck_ratio(nm: f64, reference_nm: f64, c2_over_t: f64) -> f64 {
    let at = |l: f64| 1.0 / (l * l * l * l * l * (exp_f64(c2_over_t / l) - 1.0));
    at(nm) / at(reference_nm)
}

fn lerp_table(table: &[f64], first_nm: f64, step_nm: f64, nm: f64) -> f64 {
    let x = (nm - first_nm) / step_nm;
    if !(x >= 0.0 && x <= (table.len() - 1) as f64) {
        return 0.0;
    }
    let i = (x as usize).min(table.len() - 2);
    let f = x - i as f64;
    table[i] * (1.0 - f) + table[i + 1] * f
}

fn tabulated(at: &[f32], power: &[f32], nm: f64) -> f64 {
    let k = at.partition_point(|&a| f64::from(a) <= nm);
    if k == 0 || k == at.len() {
        return if at.last().is_some_and(|&l| f64::from(l) == nm) { f64::from(power[at.len() - 1]) } else { 0.0 };
    }
    let (a, b) = (f64::from(at[k - 1]), f64::from(at[k]));
    let f = (nm - a) / (b - a);
    f64::from(power[k - 1]) * (1.0 - f) + f64::from(power[k]) * f
}

/// D65 from the daylight components (10 nm from 300 nm), the CIE's M1 and M2.
fn d65(nm: f64) -> f64 {
    let (m1, m2) = (-0.295, -0.689);
    lerp_table(&S0, 300.0, 10.0, nm) + m1 * lerp_table(&S1, 300.0, 10.0, nm) + m2 * lerp_table(&S2, 300.0, 10.0, nm)
}

const S0: [f64; 54] = [
    0.04, 6.0, 29.6, 55.3, 57.3, 61.8, 61.5, 68.8, 63.4, 65.8, 94.8, 104.8, 105.9, 96.8, 113.9, 125.6, 125.5, 121.3,
    121.3, 113.5, 113.1, 110.8, 106.5, 108.8, 105.3, 104.4, 100.0, 96.0, 95.1, 89.1, 90.5, 90.3, 88.4, 84.0, 85.1,
    81.9, 82.6, 84.9, 81.3, 71.9, 74.3, 76.4, 63.3, 71.7, 77.0, 65.2, 47.7, 68.6, 65.0, 66.0, 61.0, 53.3, 58.9, 61.9,
];
const S1: [f64; 54] = [
    0.02, 4.5, 22.4, 42.0, 40.6, 41.6, 38.0, 42.4, 38.5, 35.0, 43.4, 46.3, 43.9, 37.1, 36.7, 35.9, 32.6, 27.9, 24.3,
    20.1, 16.2, 13.2, 8.6, 6.1, 4.2, 1.9, 0.0, -1.6, -3.5, -3.5, -5.8, -7.2, -8.6, -9.5, -10.9, -10.7, -12.0, -14.0,
    -13.6, -12.0, -13.3, -12.9, -10.6, -11.6, -12.2, -10.2, -7.8, -11.2, -10.4, -10.6, -9.7, -8.3, -9.3, -9.8,
];
const S2: [f64; 54] = [
    0.0, 2.0, 4.0, 8.5, 7.8, 6.7, 5.3, 6.1, 3.0, 1.2, -1.1, -0.5, -0.7, -1.2, -2.6, -2.9, -2.8, -2.6, -2.6, -1.8, -1.5,
    -1.3, -1.2, -1.0, -0.5, -0.3, 0.0, 0.2, 0.5, 2.1, 3.2, 4.1, 4.7, 5.1, 6.7, 7.3, 8.6, 9.8, 10.2, 8.3, 9.6, 8.5, 7.0,
    7.6, 8.0, 6.7, 5.2, 7.4, 6.8, 7.0, 6.4, 5.5, 6.1, 6.5,
];
const F11: [f64; 81] = [
    0.91, 0.63, 0.46, 0.37, 1.29, 12.68, 1.59, 1.79, 2.46, 3.38, 4.49, 33.94, 12.13, 6.95, 7.19, 7.12, 6.72, 6.13,
    5.46, 4.79, 5.66, 14.29, 14.96, 8.97, 4.72, 2.33, 1.47, 1.1, 0.89, 0.83, 1.18, 4.9, 39.59, 72.84, 32.61, 7.52,
    2.83, 1.96, 1.67, 4.43, 11.28, 14.76, 12.73, 9.74, 7.33, 9.72, 55.27, 42.58, 13.18, 13.16, 12.26, 5.11, 2.07, 2.34,
    3.58, 3.01, 2.48, 2.14, 1.54, 1.33, 1.46, 1.94, 2.0, 1.2, 1.35, 4.1, 5.58, 2.51, 0.57, 0.27, 0.23, 0.21, 0.24,
    0.24, 0.2, 0.24, 0.32, 0.26, 0.16, 0.12, 0.09,
];

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::cie::cmf;

    /// CIE 1931 chromaticity (x, y) of a continuous spectrum over 360–830 nm.
    fn chromaticity(s: &Spectrum) -> (f64, f64) {
        let mut xyz = glam::DVec3::ZERO;
        for nm in 360..=830 {
            xyz += cmf(f64::from(nm)) * s.power_at(f64::from(nm));
        }
        (xyz.x / xyz.element_sum(), xyz.y / xyz.element_sum())
    }

    #[test]
    fn illuminants_have_their_published_white_points() {
        // CIE 15:2004 Table T.3 (2° observer).
        for (s, x, y, tolerance) in [
            (Spectrum::Illuminant(Illuminant::D65), 0.31272, 0.32903, 6e-4),
            (Spectrum::Illuminant(Illuminant::A), 0.44757, 0.40745, 3e-4),
            (Spectrum::Illuminant(Illuminant::F11), 0.38052, 0.37713, 1e-3),
            (Spectrum::EqualEnergy, 1.0 / 3.0, 1.0 / 3.0, 3e-4),
        ] {
            let (gx, gy) = chromaticity(&s);
            assert!((gx - x).abs() < tolerance && (gy - y).abs() < tolerance, "{s}: ({gx:.5}, {gy:.5}) vs ({x}, {y})");
        }
    }

    #[test]
    fn blackbodies_lie_on_the_planckian_locus() {
        // Planckian locus, CIE 1931 (Wyszecki & Stiles, Table 1(3.11)).
        for (kelvin, x, y) in [(2000.0, 0.5267, 0.4133), (2700.0, 0.4599, 0.4106), (6500.0, 0.3135, 0.3236)] {
            let (gx, gy) = chromaticity(&Spectrum::Blackbody { kelvin });
            assert!((gx - x).abs() < 6e-4 && (gy - y).abs() < 6e-4, "{kelvin} K: ({gx:.4}, {gy:.4}) vs ({x}, {y})");
        }
    }

    #[test]
    fn an_rgb_light_emits_its_colour() {
        // The light's colour per unit flux is the RGB's chromaticity, and
        // its power factor makes the emission rgb × a white light's.
        let colours = crate::model::wavelength_rgb::WavelengthRgb::new();
        for rgb in [[1.0, 0.5, 0.2], [0.2, 0.4, 2.0], [0.3, 0.3, 0.3]] {
            let (s, factor) = Spectrum::from_rgb(rgb);
            let colour = crate::model::rgb_spectrum::colour_of(|nm| s.power_at(nm), &colours);
            let power = crate::model::rgb_spectrum::mean_of(|nm| s.power_at(nm));
            let emitted = colour / power * f64::from(factor);
            let want = glam::DVec3::from(rgb.map(f64::from));
            assert!((emitted - want).abs().max_element() < 2e-3 * want.max_element(), "{rgb:?}: {emitted}");
        }
        assert_eq!(Spectrum::from_rgb([0.3, 0.3, 0.3]), (Spectrum::EqualEnergy, 0.3));
    }

    #[test]
    fn names_and_tables() {
        assert_eq!(Spectrum::from_name("d65"), Some(Spectrum::Illuminant(Illuminant::D65)));
        assert_eq!(Spectrum::from_name("Mercury"), Some(Spectrum::Lamp(Lamp::Mercury)));
        assert_eq!(Spectrum::from_name("e"), Some(Spectrum::EqualEnergy));
        assert_eq!(Spectrum::from_name("d50"), None);
        let t = Spectrum::Tabulated { nm: alloc::vec![400.0, 500.0], power: alloc::vec![1.0, 3.0] };
        assert_eq!((t.power_at(450.0), t.power_at(500.0), t.power_at(399.0), t.power_at(501.0)), (2.0, 3.0, 0.0, 0.0));
    }
}
