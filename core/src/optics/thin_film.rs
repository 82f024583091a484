//! Thin-film interference, the scalar reference for iridescence (soap
//! films, oil on water, coated lenses; glTF's `KHR_materials_iridescence`):
//! the reflectance of a film of index n₁ and thickness d between an outside
//! medium n₀ and a base n₂, at one wavelength, from the Airy sum of the
//! film's multiple reflections, r = (r₀₁ + r₁₂ e^{iδ}) / (1 + r₀₁ r₁₂ e^{iδ}),
//! δ = 4π n₁ d cos θ₁ / λ, for each polarisation, then their mean. Beyond
//! the critical angle into the film cos θ₁ is imaginary and the film's wave
//! decays (frustrated total reflection), which the same sum carries. Over
//! a metal the base's index is complex, n₂ + ik₂, and so are its amplitudes.

use crate::model::scene::{FilmMap, ThinFilm};
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

    /// The principal square root (real part ≥ 0; on the negative real
    /// axis i√−x, the root whose wave decays, as [`Complex::sqrt_of`]).
    fn sqrt(self) -> Self {
        let r = sqrt(self.norm2());
        let re = sqrt(0.5 * (r + self.re).max(0.0));
        let im = sqrt(0.5 * (r - self.re).max(0.0));
        Complex { re, im: if self.im < 0.0 { -im } else { im } }
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
    /// A whole film (factor 1) of index `ior`, `thickness_nm` thick.
    pub const fn new(ior: f32, thickness_nm: f32) -> Self {
        ThinFilm { ior, thickness_nm, factor: 1.0 }
    }

    /// True when it leaves its surface's reflection as it is everywhere
    /// under its material's film map `map`: no share of the surface, or no
    /// thickness (the Airy sum is the bare Fresnel) unless a thickness map
    /// of a positive minimum thickens it wherever the map's green is below
    /// 1 (a factor map only scales the factor, so no factor stays none).
    pub fn is_bare(&self, map: Option<&FilmMap>) -> bool {
        let thickened = map.is_some_and(|m| m.thickness.is_some() && m.min_nm > 0.0);
        self.factor <= 0.0 || (self.thickness_nm <= 0.0 && !thickened)
    }

    /// The unpolarised reflectance for light of wavelength `lambda_nm`
    /// arriving with cosine `cos0` from a medium of index `n0` at this film
    /// over a base of index `n2` (a total reflection at the base is 1).
    /// The film's own light is not absorbed, so what is not reflected is
    /// transmitted into the base.
    pub fn reflectance(&self, cos0: f32, n0: f32, n2: f32, lambda_nm: f32) -> f32 {
        self.reflectance_on(cos0, n0, (n2, 0.0), lambda_nm)
    }

    /// [`ThinFilm::reflectance`] over an absorbing base of complex index
    /// n₂ + ik₂ (`base`; a metal's, [`crate::model::metals`]): its Fresnel
    /// amplitudes are complex, so the film's reflections meet the base's
    /// phase shift, which is neither 0 nor π, and what is not reflected is
    /// absorbed by the base. k₂ = 0 is a dielectric base. Below a factor
    /// of 1 it is the mix of the Airy sum and the bare base's Fresnel,
    /// glTF's mix of the iridescence and the base Fresnel.
    pub fn reflectance_on(&self, cos0: f32, n0: f32, base: (f32, f32), lambda_nm: f32) -> f32 {
        let n1 = self.ior;
        let cos0 = cos0.clamp(0.0, 1.0);
        let sin2 = 1.0 - cos0 * cos0;
        let c0 = Complex::real(cos0);
        let c1 = Complex::sqrt_of(1.0 - (n0 / n1) * (n0 / n1) * sin2);
        // The base's n₂ cos θ₂ = √(N₂² − n₀² sin²θ₀), the root whose wave decays.
        let n2 = Complex { re: base.0, im: base.1 };
        let q2 = (n2 * n2 - Complex::real(n0 * n0 * sin2)).sqrt();
        let (n0, n1c) = (Complex::real(n0), Complex::real(n1));
        // δ = 4π n₁ d cos θ₁ / λ; e^{iδ} decays where cos θ₁ is imaginary.
        let phase = (c1 * Complex::real(4.0 * core::f32::consts::PI * n1 * self.thickness_nm / lambda_nm)).exp_i();
        let airy = |r01: Complex, r12: Complex| ((r01 + r12 * phase) / (Complex::ONE + r01 * r12 * phase)).norm2();
        // Amplitudes between media a and b, each as (n, n cos θ): s (na ca − nb cb)/(na ca + nb cb),
        // p (nb ca − na cb)/(nb ca + na cb) multiplied through by nb (cb = qb/nb).
        let s = |(_, qa): (Complex, Complex), (_, qb): (Complex, Complex)| (qa - qb) / (qa + qb);
        let p = |(na, qa): (Complex, Complex), (nb, qb): (Complex, Complex)| {
            (nb * nb * qa - na * na * qb) / (nb * nb * qa + na * na * qb)
        };
        let (top, film, base) = ((n0, n0 * c0), (n1c, n1c * c1), (n2, q2));
        let rs = airy(s(top, film), s(film, base));
        let rp = airy(p(top, film), p(film, base));
        let filmed = 0.5 * (rs + rp);
        let r = match self.factor < 1.0 {
            true => {
                let bare = 0.5 * (s(top, base).norm2() + p(top, base).norm2());
                bare + (filmed - bare) * self.factor
            }
            false => filmed,
        };
        r.clamp(0.0, 1.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::cie::cmf;
    use crate::model::color::xyz_to_linear_srgb;
    use crate::optics::fresnel::fresnel;
    use crate::optics::microfacet::conductor_fresnel;

    /// A complex number in f64 for the matrix method below (re, im).
    #[derive(Clone, Copy)]
    struct C(f64, f64);

    impl C {
        fn mul(self, o: C) -> C {
            C(self.0 * o.0 - self.1 * o.1, self.0 * o.1 + self.1 * o.0)
        }
        fn div(self, o: C) -> C {
            let d = o.0 * o.0 + o.1 * o.1;
            C((self.0 * o.0 + self.1 * o.1) / d, (self.1 * o.0 - self.0 * o.1) / d)
        }
        fn add(self, o: C) -> C {
            C(self.0 + o.0, self.1 + o.1)
        }
        fn sub(self, o: C) -> C {
            C(self.0 - o.0, self.1 - o.1)
        }
        /// The principal root (its imaginary part has the argument's sign).
        fn sqrt(self) -> C {
            let r = self.0.hypot(self.1);
            let im = ((r - self.0) / 2.0).sqrt();
            C(((r + self.0) / 2.0).sqrt(), if self.1 < 0.0 { -im } else { im })
        }
    }

    /// The reflectance of a film on a base of complex index n₂ + ik₂ by
    /// Born & Wolf's characteristic matrix (§1.6, time as e^{−iωt}, so an
    /// absorbing index is n + ik): r = ((m₁₁ + m₁₂ p₂) p₀ − (m₂₁ + m₂₂ p₂)) /
    /// ((m₁₁ + m₁₂ p₂) p₀ + (m₂₁ + m₂₂ p₂)) with p = n cos θ (s) or cos θ / n
    /// (p), M = [[cos β, −i sin β / p₁], [−i p₁ sin β, cos β]], in f64.
    fn on_conductor_by_matrix(cos0: f64, n0: f64, n1: f64, (n2, k2): (f64, f64), d: f64, lambda: f64) -> f64 {
        let sin2 = 1.0 - cos0 * cos0;
        let cos1 = (1.0 - (n0 / n1).powi(2) * sin2).sqrt();
        let big_n2 = C(n2, k2);
        let q2 = big_n2.mul(big_n2).sub(C(n0 * n0 * sin2, 0.0)).sqrt(); // N₂ cos θ₂
        let beta = 2.0 * core::f64::consts::PI * n1 * d * cos1 / lambda;
        let (cb, sb) = (beta.cos(), beta.sin());
        let r = |p0: C, p1: C, p2: C| {
            let b = C(cb, 0.0).add(C(0.0, -sb).mul(p2.div(p1)));
            let c = C(0.0, -sb).mul(p1).add(p2.mul(C(cb, 0.0)));
            let r = b.mul(p0).sub(c).div(b.mul(p0).add(c));
            r.0 * r.0 + r.1 * r.1
        };
        let s = r(C(n0 * cos0, 0.0), C(n1 * cos1, 0.0), q2);
        let p = r(C(cos0 / n0, 0.0), C(cos1 / n1, 0.0), q2.div(big_n2.mul(big_n2)));
        0.5 * (s + p)
    }

    #[test]
    fn a_film_on_a_metal_is_the_characteristic_matrix_at_ten_wavelengths() {
        // Oxide on titanium, on steel, on gold and on aluminium (optical constants near 550 nm).
        for (n1, base, d) in
            [(2.4, (2.5, 3.4), 60.0), (1.9, (2.9, 3.0), 250.0), (1.3, (0.35, 2.6), 400.0), (1.5, (1.0, 6.6), 120.0)]
        {
            for cos0 in [1.0, 0.8, 0.5, 0.2] {
                for k in 0..10 {
                    let lambda = 400.0 + 30.0 * f64::from(k);
                    let film = ThinFilm::new(n1 as f32, d as f32);
                    let got = film.reflectance_on(cos0 as f32, 1.0, (base.0 as f32, base.1 as f32), lambda as f32);
                    let want = on_conductor_by_matrix(cos0, 1.0, n1, base, d, lambda);
                    assert!(
                        (f64::from(got) - want).abs() < 2e-5,
                        "n {n1} on {base:?}, d {d}, cos {cos0}, λ {lambda}: {got} vs {want}"
                    );
                }
            }
            // A film of no thickness, or of the outside's index, is the bare metal.
            for cos0 in [1.0f32, 0.6, 0.1] {
                let bare = conductor_fresnel(cos0, base.0 as f32, base.1 as f32);
                for film in [ThinFilm::new(n1 as f32, 0.0), ThinFilm::new(1.0, d as f32)] {
                    let got = film.reflectance_on(cos0, 1.0, (base.0 as f32, base.1 as f32), 550.0);
                    assert!((got - bare).abs() < 1e-5, "{film:?} on {base:?} at cos {cos0}: {got} vs bare {bare}");
                }
            }
        }
    }

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
                    let film = ThinFilm::new(n1 as f32, d as f32);
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
            for film in [ThinFilm::new(1.33, 0.0), ThinFilm::new(1.0, 450.0)] {
                let got = film.reflectance(cos, 1.0, 1.5, 550.0);
                assert!((got - bare).abs() < 1e-5, "{film:?}, cos {cos}: {got} vs {bare}");
            }
        }
    }

    #[test]
    fn a_partial_film_mixes_the_airy_sum_with_the_bare_fresnel() {
        // glTF's iridescenceFactor: F = mix(F_bare, F_film, factor), over glass and over gold.
        let gold = (0.47f32, 2.4f32);
        for cos in [1.0f32, 0.6, 0.2] {
            for lambda in [420.0f32, 550.0, 680.0] {
                let whole = ThinFilm::new(1.38, 300.0);
                let on_glass = |f: ThinFilm| f.reflectance(cos, 1.0, 1.5, lambda);
                let on_gold = |f: ThinFilm| f.reflectance_on(cos, 1.0, gold, lambda);
                let (glass, metal) = (fresnel(cos, 1.0, 1.5), conductor_fresnel(cos, gold.0, gold.1));
                for factor in [0.0f32, 0.25, 0.7] {
                    let part = ThinFilm { factor, ..whole };
                    let want = glass + (on_glass(whole) - glass) * factor;
                    assert!((on_glass(part) - want).abs() < 2e-6, "glass, {factor}, cos {cos}, λ {lambda}");
                    let want = metal + (on_gold(whole) - metal) * factor;
                    assert!((on_gold(part) - want).abs() < 2e-6, "gold, {factor}, cos {cos}, λ {lambda}");
                }
            }
        }
    }

    #[test]
    fn a_quarter_wave_coating_cancels_its_wavelengths_reflection() {
        // n₁ = √(n₀n₂), d = λ/4n₁: the two reflections cancel at λ, at normal incidence.
        let n1 = 1.5f32.sqrt();
        let film = ThinFilm::new(n1, 550.0 / (4.0 * n1));
        assert!(film.reflectance(1.0, 1.0, 1.5, 550.0) < 1e-6);
        // Away from λ it reflects, less than the bare glass's 4 %.
        let blue = film.reflectance(1.0, 1.0, 1.5, 400.0);
        assert!(blue > 2e-3 && blue < fresnel(1.0, 1.0, 1.5), "{blue}");
    }

    #[test]
    fn a_soap_film_is_black_when_thin_and_brightest_a_quarter_wave_thick() {
        let (n, lambda) = (1.33f32, 550.0f32);
        let thin = ThinFilm::new(n, 1.0);
        assert!(thin.reflectance(1.0, 1.0, 1.0, lambda) < 1e-3, "Newton's black film");
        // At d = λ/4n, e^{iδ} = −1 and r = 2r₀₁/(1 + r₀₁²).
        let r = (1.0 - n) / (1.0 + n);
        let want = 4.0 * r * r / ((1.0 + r * r) * (1.0 + r * r));
        let quarter = ThinFilm::new(n, lambda / (4.0 * n));
        let got = quarter.reflectance(1.0, 1.0, 1.0, lambda);
        assert!((got - want).abs() < 1e-6, "{got} vs {want}");
    }

    /// The CIE XYZ a soap film `d` nm thick reflects of equal-energy white
    /// at normal incidence (CIE 1931, 5 nm steps), white itself of Y = 1.
    fn soap_film_xyz(d: f32) -> glam::DVec3 {
        let film = ThinFilm::new(1.33, d);
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
        let at = |d: f32| ThinFilm::new(1.0, d).reflectance(cos0, 1.5, 1.5, 550.0);
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
