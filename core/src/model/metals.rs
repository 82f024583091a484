//! Measured metals: silver, aluminium, gold and copper by their optical
//! constants (the complex index n + ik) per wavelength, so that a metal's
//! Fresnel reflectance is exact at each path's wavelength
//! ([`crate::optics::metal`]) instead of Schlick's curve through an RGB
//! colour; and [`MetalColor`], a metal material's colour: RGB, as glTF
//! gives it, or one of these.
//!
//! The constants are the measured values pbrt-v4 tabulates as its named
//! spectra `metal-{Ag,Al,Au,Cu}-{eta,k}` (every 0.05 eV over 299–886 nm),
//! resampled every 10 nm over 380–780 nm by linear interpolation; between
//! rows they are read linearly again, and outside the range they keep their
//! end rows.

use crate::model::wavelength_rgb::WavelengthRgb;
use glam::Vec3;

/// A metal's colour: what its Fresnel reflectance is made from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MetalColor {
    /// Reflectance at normal incidence per linear RGB channel, each in
    /// [0, 1] (glTF's base colour of a metal), with Schlick's Fresnel.
    Rgb(Vec3),
    /// A measured metal: its exact Fresnel per wavelength.
    Measured(NamedMetal),
}

impl MetalColor {
    /// Its reflectance at normal incidence in linear RGB (a measured
    /// metal's: [`NamedMetal::color`]).
    pub fn rgb(&self) -> Vec3 {
        match self {
            MetalColor::Rgb(c) => *c,
            MetalColor::Measured(m) => m.color(),
        }
    }
}

/// A metal whose optical constants were measured.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum NamedMetal {
    /// Silver (Ag).
    Silver,
    /// Aluminium (Al).
    Aluminium,
    /// Gold (Au).
    Gold,
    /// Copper (Cu).
    Copper,
}

/// First wavelength of [`CONSTANTS`], in nm.
pub const FIRST_NM: f32 = 380.0;
/// Spacing of [`CONSTANTS`], in nm.
pub const STEP_NM: f32 = 10.0;
/// Rows of [`CONSTANTS`] (380–780 nm).
pub const ROWS: usize = 41;

/// n and k of silver, aluminium, gold and copper (in [`NamedMetal::ALL`]'s
/// order) at 380, 390, …, 780 nm.
pub const CONSTANTS: [[f32; 8]; ROWS] = [
    [0.1986, 1.7182, 0.4422, 4.6147, 1.6876, 1.9182, 1.2064, 2.0941], // 380
    [0.1879, 1.8385, 0.4661, 4.7408, 1.6707, 1.9409, 1.1777, 2.1964], // 390
    [0.173, 1.9506, 0.4901, 4.8606, 1.6579, 1.956, 1.175, 2.1302],    // 400
    [0.1728, 2.071, 0.5149, 4.9804, 1.6414, 1.9587, 1.1788, 2.1858],  // 410
    [0.1669, 2.1831, 0.5394, 5.1051, 1.6283, 1.9516, 1.1782, 2.2483], // 420
    [0.1595, 2.2828, 0.5644, 5.2296, 1.6095, 1.9349, 1.1743, 2.3012], // 430
    [0.1575, 2.3745, 0.5905, 5.3476, 1.5743, 1.9114, 1.171, 2.349],   // 440
    [0.1517, 2.4704, 0.618, 5.4694, 1.5085, 1.8788, 1.1658, 2.3939],  // 450
    [0.1434, 2.5674, 0.6463, 5.5901, 1.4186, 1.8431, 1.1596, 2.4363], // 460
    [0.1361, 2.659, 0.6749, 5.7161, 1.3212, 1.8102, 1.1541, 2.4774],  // 470
    [0.1314, 2.7462, 0.7046, 5.8386, 1.1899, 1.7965, 1.1476, 2.5147], // 480
    [0.1302, 2.83, 0.7359, 5.9598, 1.0202, 1.814, 1.1398, 2.5468],    // 490
    [0.13, 2.9176, 0.7686, 6.0782, 0.8512, 1.8868, 1.1336, 2.5743],   // 500
    [0.13, 3.0097, 0.8028, 6.1986, 0.6997, 2.0176, 1.1272, 2.5954],   // 510
    [0.13, 3.0976, 0.8387, 6.3233, 0.572, 2.1838, 1.1115, 2.6021],    // 520
    [0.1298, 3.1784, 0.8764, 6.4473, 0.4729, 2.3711, 1.0814, 2.5929], // 530
    [0.1286, 3.2577, 0.916, 6.5617, 0.3976, 2.5549, 1.033, 2.5825],   // 540
    [0.1248, 3.3396, 0.9586, 6.687, 0.3504, 2.7141, 0.9582, 2.5771],  // 550
    [0.1212, 3.421, 1.0038, 6.8073, 0.3172, 2.8375, 0.8614, 2.5926],  // 560
    [0.1197, 3.5009, 1.0495, 6.9237, 0.2872, 2.9098, 0.7376, 2.6378], // 570
    [0.1197, 3.5795, 1.097, 7.0364, 0.26, 2.9477, 0.6027, 2.7098],    // 580
    [0.121, 3.6569, 1.148, 7.1456, 0.2369, 2.9691, 0.4732, 2.8052],   // 590
    [0.124, 3.7308, 1.1967, 7.2567, 0.2203, 3.0, 0.3902, 2.9435],     // 600
    [0.1274, 3.8054, 1.2475, 7.3685, 0.2061, 3.0305, 0.324, 3.0896],  // 610
    [0.131, 3.8807, 1.3004, 7.4808, 0.1939, 3.06, 0.2718, 3.2411],    // 620
    [0.1342, 3.9628, 1.3571, 7.5878, 0.1837, 3.0663, 0.2459, 3.3784], // 630
    [0.1371, 4.0455, 1.415, 7.6925, 0.1748, 3.09, 0.2266, 3.5111],    // 640
    [0.1394, 4.1288, 1.4748, 7.7941, 0.1678, 3.1378, 0.2166, 3.6377], // 650
    [0.14, 4.2105, 1.5365, 7.9003, 0.1639, 3.275, 0.212, 3.7516],     // 660
    [0.1401, 4.2916, 1.5988, 8.008, 0.1611, 3.4427, 0.2093, 3.8611],  // 670
    [0.14, 4.3706, 1.6738, 8.1154, 0.1605, 3.6326, 0.2112, 3.9617],   // 680
    [0.1403, 4.4489, 1.7504, 8.221, 0.1601, 3.8175, 0.2132, 4.0615],  // 690
    [0.1425, 4.5232, 1.8367, 8.3124, 0.1605, 3.9637, 0.2148, 4.1579], // 700
    [0.1446, 4.5975, 1.9268, 8.4031, 0.1611, 4.1073, 0.2167, 4.2534], // 710
    [0.1464, 4.6712, 2.0371, 8.4895, 0.1626, 4.2366, 0.22, 4.3448],   // 720
    [0.1479, 4.7452, 2.1483, 8.5715, 0.1642, 4.3648, 0.2234, 4.4358], // 730
    [0.147, 4.8213, 2.2705, 8.5942, 0.1667, 4.4794, 0.2295, 4.5216],  // 740
    [0.146, 4.8973, 2.3927, 8.6168, 0.1691, 4.5939, 0.2356, 4.6074],  // 750
    [0.1448, 4.9746, 2.4904, 8.6127, 0.1719, 4.7015, 0.2414, 4.6917], // 760
    [0.1436, 5.052, 2.5841, 8.6042, 0.1746, 4.8079, 0.2472, 4.7758],  // 770
    [0.1429, 5.1305, 2.6647, 8.5694, 0.1771, 4.9142, 0.2509, 4.8613], // 780
];

impl NamedMetal {
    /// Every named metal.
    pub const ALL: [NamedMetal; 4] = [NamedMetal::Silver, NamedMetal::Aluminium, NamedMetal::Gold, NamedMetal::Copper];

    /// The name scene files give it.
    pub fn name(self) -> &'static str {
        match self {
            NamedMetal::Silver => "silver",
            NamedMetal::Aluminium => "aluminium",
            NamedMetal::Gold => "gold",
            NamedMetal::Copper => "copper",
        }
    }

    /// The metal of that name.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|m| m.name() == name)
    }

    /// Its column pair in [`CONSTANTS`].
    fn column(self) -> usize {
        match self {
            NamedMetal::Silver => 0,
            NamedMetal::Aluminium => 2,
            NamedMetal::Gold => 4,
            NamedMetal::Copper => 6,
        }
    }

    /// Its (n, k) in each row of [`CONSTANTS`] (what backends upload).
    pub fn rows(self) -> [[f32; 2]; ROWS] {
        let c = self.column();
        core::array::from_fn(|i| [CONSTANTS[i][c], CONSTANTS[i][c + 1]])
    }

    /// Its complex index (n, k) at `lambda_nm`, read linearly between rows
    /// (the end rows outside 380–780 nm).
    #[inline]
    pub fn optical_constants(self, lambda_nm: f32) -> (f32, f32) {
        let x = ((lambda_nm - FIRST_NM) / STEP_NM).clamp(0.0, (ROWS - 1) as f32);
        let i = (x as usize).min(ROWS - 2);
        let f = x - i as f32;
        let c = self.column();
        let (a, b) = (CONSTANTS[i], CONSTANTS[i + 1]);
        (a[c] + (b[c] - a[c]) * f, a[c + 1] + (b[c + 1] - a[c + 1]) * f)
    }

    /// Its reflectance at normal incidence at `lambda_nm`:
    /// ((n − 1)² + k²)/((n + 1)² + k²).
    pub fn normal_reflectance(self, lambda_nm: f32) -> f32 {
        let (n, k) = self.optical_constants(lambda_nm);
        ((n - 1.0) * (n - 1.0) + k * k) / ((n + 1.0) * (n + 1.0) + k * k)
    }

    /// The colour of its reflectance at normal incidence under the
    /// equal-energy light, in linear RGB (this renderer's white,
    /// [`crate::model::wavelength_rgb`]): the mean over 380–780 nm of each
    /// wavelength's colour times the reflectance, on a 1 nm grid.
    pub fn color(self) -> Vec3 {
        let colours = WavelengthRgb::new();
        let mut sum = Vec3::ZERO;
        for nm in 380..=780 {
            let lambda = nm as f32;
            let w = if nm == 380 || nm == 780 { 0.5 } else { 1.0 };
            sum += colours.at(lambda) * (w * self.normal_reflectance(lambda));
        }
        sum / 400.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_reads_back_its_rows_and_clamps_outside_them() {
        let gold = NamedMetal::Gold;
        assert_eq!(gold.optical_constants(550.0), (CONSTANTS[17][4], CONSTANTS[17][5]));
        assert_eq!(gold.optical_constants(300.0), gold.optical_constants(380.0));
        assert_eq!(gold.optical_constants(900.0), gold.optical_constants(780.0));
        let (n, _) = gold.optical_constants(555.0);
        assert!((n - 0.5 * (CONSTANTS[17][4] + CONSTANTS[18][4])).abs() < 1e-6);
        for m in NamedMetal::ALL {
            assert_eq!(NamedMetal::from_name(m.name()), Some(m));
            assert_eq!(m.rows()[17], [m.optical_constants(550.0).0, m.optical_constants(550.0).1]);
        }
    }

    #[test]
    fn gold_and_copper_are_warm_silver_and_aluminium_nearly_white() {
        let [silver, aluminium, gold, copper] = NamedMetal::ALL.map(NamedMetal::color);
        // Gold and copper reflect red best and blue worst; copper is the redder.
        assert!(gold.x > gold.y && gold.y > gold.z, "{gold}");
        assert!(copper.x > copper.y && copper.y > copper.z && copper.y < gold.y, "{copper}");
        // Silver and aluminium: bright and within a few per cent of grey.
        for c in [silver, aluminium] {
            assert!(c.min_element() > 0.85 && c.max_element() - c.min_element() < 0.08, "{c}");
        }
        // Real-time PBR tables give gold's F0 as (1.0, 0.766, 0.336) in linear sRGB.
        assert!((gold - Vec3::new(1.0, 0.766, 0.336)).abs().max_element() < 0.1, "{gold}");
    }
}
