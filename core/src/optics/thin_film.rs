//! Thin-film interference, the scalar reference for iridescence (soap
//! films, oil on water, coated lenses; glTF's `KHR_materials_iridescence`):
//! the reflectance of a film of index n₁ and thickness d between an outside
//! medium n₀ and a base n₂, at one wavelength, from the Airy sum of the
//! film's multiple reflections, r = (r₀₁ + r₁₂ e^{iδ}) / (1 + r₀₁ r₁₂ e^{iδ}),
//! δ = 4π n₁ d cos θ₁ / λ, for each polarisation, then their mean. Beyond
//! the critical angle into the film cos θ₁ is imaginary and the film's wave
//! decays (frustrated total reflection), which the same sum carries.

use crate::model::scene::ThinFilm;
use crate::util::math::{exp, sin_cos_turns, sqrt};
use core::ops::{Add, Div, Mul, Sub};

/// A complex number: the Fresnel amplitudes and the film's phase factor.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Complex {
    re: f32,
    im: f32,
}

impl Complex {
    const ONE: Complex = Complex { re: 1.0, im: 0.0 };

    fn real(re: f32) -> Self {
        Complex { re, im: 0.0 }
    }

    /// √x of a real x: real, or i√−x (the root whose wave decays).
    fn sqrt_of(x: f32) -> Self {
        if x >= 0.0 { Complex::real(sqrt(x)) } else { Complex { re: 0.0, im: sqrt(-x) } }
    }

    fn norm2(self) -> f32 {
        self.re * self.re + self.im * self.im
    }

    /// e^{i·self}.
    fn exp_i(self) -> Self {
        let (s, c) = sin_cos_turns(self.re * (0.5 / core::f32::consts::PI));
        let decay = exp(-self.im);
        Complex { re: decay * c, im: decay * s }
    }
}

impl Add for Complex {
    type Output = Complex;
    fn add(self, o: Complex) -> Complex {
        Complex { re: self.re + o.re, im: self.im + o.im }
    }
}

impl Sub for Complex {
    type Output = Complex;
    fn sub(self, o: Complex) -> Complex {
        Complex { re: self.re - o.re, im: self.im - o.im }
    }
}

impl Mul for Complex {
    type Output = Complex;
    fn mul(self, o: Complex) -> Complex {
        Complex { re: self.re * o.re - self.im * o.im, im: self.re * o.im + self.im * o.re }
    }
}

impl Div for Complex {
    type Output = Complex;
    fn div(self, o: Complex) -> Complex {
        let d = o.norm2();
        Complex { re: (self.re * o.re + self.im * o.im) / d, im: (self.im * o.re - self.re * o.im) / d }
    }
}

impl ThinFilm {
    /// The unpolarised reflectance for light of wavelength `lambda_nm`
    /// arriving with cosine `cos0` from a medium of index `n0` at this film
    /// over a base of index `n2` (a total reflection at the base is 1).
    /// The film's own light is not absorbed, so what is not reflected is
    /// transmitted into the base.
    pub fn reflectance(&self, cos0: f32, n0: f32, n2: f32, lambda_nm: f32) -> f32 {
        let n1 = self.ior;
        let cos0 = cos0.clamp(0.0, 1.0);
        let sin2 = 1.0 - cos0 * cos0;
        let cos_in = |n: f32| Complex::sqrt_of(1.0 - (n0 / n) * (n0 / n) * sin2);
        let (c0, c1, c2) = (Complex::real(cos0), cos_in(n1), cos_in(n2));
        let (n0, n1c, n2c) = (Complex::real(n0), Complex::real(n1), Complex::real(n2));
        // δ = 4π n₁ d cos θ₁ / λ; e^{iδ} decays where cos θ₁ is imaginary.
        let phase = (c1 * Complex::real(4.0 * core::f32::consts::PI * n1 * self.thickness_nm / lambda_nm)).exp_i();
        let airy = |r01: Complex, r12: Complex| ((r01 + r12 * phase) / (Complex::ONE + r01 * r12 * phase)).norm2();
        let s = |(na, ca): (Complex, Complex), (nb, cb): (Complex, Complex)| (na * ca - nb * cb) / (na * ca + nb * cb);
        let p = |(na, ca): (Complex, Complex), (nb, cb): (Complex, Complex)| (nb * ca - na * cb) / (nb * ca + na * cb);
        let (top, film, base) = ((n0, c0), (n1c, c1), (n2c, c2));
        let rs = airy(s(top, film), s(film, base));
        let rp = airy(p(top, film), p(film, base));
        (0.5 * (rs + rp)).clamp(0.0, 1.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::cie::cmf;
    use crate::model::color::xyz_to_linear_srgb;
    use crate::optics::fresnel::fresnel;

    /// The reflectance by the characteristic (transfer) matrix of the film
    /// (Born & Wolf §1.6), in f64: an independent form of the same optics,
    /// for angles where every cosine is real.
    fn by_transfer_matrix(cos0: f64, n0: f64, n1: f64, n2: f64, d: f64, lambda: f64) -> f64 {
        let sin2 = 1.0 - cos0 * cos0;
        let cos_in = |n: f64| (1.0 - (n0 / n).powi(2) * sin2).sqrt();
        let (c1, c2) = (cos_in(n1), cos_in(n2));
        let beta = 2.0 * core::f64::consts::PI * n1 * d * c1 / lambda;
        let reflectance = |eta0: f64, eta1: f64, eta2: f64| {
            // [B, C] = [[cos β, i sin β/η₁], [i η₁ sin β, cos β]] [1, η₂]; r = (η₀B − C)/(η₀B + C).
            let (b_re, b_im) = (beta.cos(), beta.sin() * eta2 / eta1);
            let (c_re, c_im) = (eta2 * beta.cos(), eta1 * beta.sin());
            let (num_re, num_im) = (eta0 * b_re - c_re, eta0 * b_im - c_im);
            let (den_re, den_im) = (eta0 * b_re + c_re, eta0 * b_im + c_im);
            (num_re * num_re + num_im * num_im) / (den_re * den_re + den_im * den_im)
        };
        let s = reflectance(n0 * cos0, n1 * c1, n2 * c2);
        let p = reflectance(n0 / cos0, n1 / c1, n2 / c2);
        0.5 * (s + p)
    }

    #[test]
    fn the_airy_sum_is_the_transfer_matrix_at_ten_wavelengths() {
        // A soap film on glass, a coating on a lens, oil on water, seen at several angles.
        for (n0, n1, n2, d) in [(1.0, 1.33, 1.5, 380.0), (1.0, 1.38, 1.52, 100.0), (1.0, 1.47, 1.33, 900.0)] {
            for cos0 in [1.0, 0.8, 0.5, 0.2] {
                let mut seen = (f64::INFINITY, 0.0f64);
                for k in 0..10 {
                    let lambda = 400.0 + 30.0 * f64::from(k);
                    let film = ThinFilm { ior: n1 as f32, thickness_nm: d as f32 };
                    let got = film.reflectance(cos0 as f32, n0 as f32, n2 as f32, lambda as f32);
                    let want = by_transfer_matrix(cos0, n0, n1, n2, d, lambda);
                    assert!(
                        (f64::from(got) - want).abs() < 2e-5,
                        "n {n1} on {n2}, d {d} nm, cos {cos0}, λ {lambda}: {got} vs {want}"
                    );
                    seen = (seen.0.min(want), seen.1.max(want));
                }
                // The film's colour: its reflectance changes across the spectrum.
                assert!(seen.1 - seen.0 > 0.005, "n {n1} on {n2}, d {d} nm, cos {cos0}: {seen:?}");
            }
        }
    }

    #[test]
    fn no_film_is_the_bare_interface() {
        for cos in [1.0f32, 0.7, 0.3, 0.05] {
            let bare = fresnel(cos, 1.0, 1.5);
            // No thickness, or a film of the outside's own index.
            for film in [ThinFilm { ior: 1.33, thickness_nm: 0.0 }, ThinFilm { ior: 1.0, thickness_nm: 450.0 }] {
                let got = film.reflectance(cos, 1.0, 1.5, 550.0);
                assert!((got - bare).abs() < 1e-5, "{film:?}, cos {cos}: {got} vs {bare}");
            }
        }
    }

    #[test]
    fn a_quarter_wave_coating_cancels_its_wavelengths_reflection() {
        // n₁ = √(n₀n₂), d = λ/4n₁: the two reflections cancel at λ, at normal incidence.
        let n1 = 1.5f32.sqrt();
        let film = ThinFilm { ior: n1, thickness_nm: 550.0 / (4.0 * n1) };
        assert!(film.reflectance(1.0, 1.0, 1.5, 550.0) < 1e-6);
        // Away from λ it reflects, less than the bare glass's 4 %.
        let blue = film.reflectance(1.0, 1.0, 1.5, 400.0);
        assert!(blue > 2e-3 && blue < fresnel(1.0, 1.0, 1.5), "{blue}");
    }

    #[test]
    fn a_soap_film_is_black_when_thin_and_brightest_a_quarter_wave_thick() {
        let (n, lambda) = (1.33f32, 550.0f32);
        let thin = ThinFilm { ior: n, thickness_nm: 1.0 };
        assert!(thin.reflectance(1.0, 1.0, 1.0, lambda) < 1e-3, "Newton's black film");
        // At d = λ/4n, e^{iδ} = −1 and r = 2r₀₁/(1 + r₀₁²).
        let r = (1.0 - n) / (1.0 + n);
        let want = 4.0 * r * r / ((1.0 + r * r) * (1.0 + r * r));
        let quarter = ThinFilm { ior: n, thickness_nm: lambda / (4.0 * n) };
        let got = quarter.reflectance(1.0, 1.0, 1.0, lambda);
        assert!((got - want).abs() < 1e-6, "{got} vs {want}");
    }

    /// The CIE XYZ a soap film `d` nm thick reflects of equal-energy white
    /// at normal incidence (CIE 1931, 5 nm steps), white itself of Y = 1.
    fn soap_film_xyz(d: f32) -> glam::DVec3 {
        let film = ThinFilm { ior: 1.33, thickness_nm: d };
        let xyz: glam::DVec3 = (0..=80)
            .map(|k| {
                let lambda = 380.0 + 5.0 * k as f32;
                cmf(f64::from(lambda)) * f64::from(film.reflectance(1.0, 1.0, 1.0, lambda))
            })
            .sum();
        let white: f64 = (0..=80).map(|k| cmf(380.0 + 5.0 * f64::from(k)).y).sum();
        xyz / white
    }

    #[test]
    fn a_wedge_of_soap_film_shows_newtons_colours_in_their_order() {
        // Black at the thin edge, first-order white brightest where 2nd ≈ 555/2 nm,
        // then each thickness 2nd = λ cancels λ: blue (yellow shows), green
        // (purple shows), red (blue shows), in Newton's order.
        assert!(soap_film_xyz(5.0).y < 1e-3, "black");
        let luminance = |d: u32| soap_film_xyz(d as f32).y;
        let brightest = (0..=200).step_by(2).max_by(|&a, &b| luminance(a).total_cmp(&luminance(b)));
        assert!((90..=120).contains(&brightest.unwrap()), "first-order white at {brightest:?} nm");
        let cancelled = |lambda: f32| xyz_to_linear_srgb(soap_film_xyz(lambda / (2.0 * 1.33)));
        let yellow = cancelled(450.0);
        assert!(yellow.z < yellow.x.min(yellow.y), "450 nm cancelled: {yellow}");
        let purple = cancelled(550.0);
        assert!(purple.y < purple.x.min(purple.z), "550 nm cancelled: {purple}");
        let blue = cancelled(650.0);
        assert!(blue.x < blue.y.min(blue.z), "650 nm cancelled: {blue}");
    }

    #[test]
    fn a_gap_beyond_the_critical_angle_reflects_more_as_it_widens() {
        // Glass, an air gap, glass at 60° (critical 41.8°): frustrated total reflection.
        let cos0 = 0.5;
        let at = |d: f32| ThinFilm { ior: 1.0, thickness_nm: d }.reflectance(cos0, 1.5, 1.5, 550.0);
        assert!(at(0.0) < 1e-6, "no gap, no interface");
        let mut last = 0.0;
        for d in [20.0, 50.0, 100.0, 200.0, 400.0] {
            let r = at(d);
            assert!(r > last, "{d} nm: {r} after {last}");
            last = r;
        }
        assert!(at(2_000.0) > 0.999, "a wide gap reflects totally");
    }
}
