//! How each object's surface scatters light, ready for tracing: diffuse
//! albedo (with its checker), mirror, metal, or a dielectric's relative indices of
//! refraction per band and as a function of wavelength, its absorption and
//! the film on its surface.

use crate::model::bands::{BandTable, VISIBLE_NM};
use crate::model::dispersion::Dispersion;
use crate::model::photon::WHITE_BAND;
use crate::model::scene::{Attenuation, Checker, Material, MaterialKind, Texture, ThinFilm};
use crate::optics::absorption::Absorption;
use crate::optics::metal::MetalOptics;
use crate::optics::microfacet::Ggx;
use crate::optics::scatter::Face;
use alloc::vec::Vec;
use glam::{Vec2, Vec3};

/// How an object's surface scatters light, ready for tracing.
#[derive(Clone, Debug, PartialEq)]
pub enum Surface {
    /// Lambertian.
    Diffuse {
        /// Albedo.
        albedo: Vec3,
        /// Optional checker.
        checker: Option<Checker>,
        /// Optional image multiplying the albedo.
        texture: Option<Texture>,
        /// Radiance its front faces emit, per linear RGB channel (what the
        /// camera sees of an area light; its light is in the scene's lights).
        emission: Vec3,
    },
    /// Perfect mirror.
    Mirror,
    /// Metal: coloured Fresnel, polished or rough.
    Metal(MetalOptics),
    /// Dielectric with its indices per band.
    Dielectric(DielectricOptics),
}

/// A dielectric's indices of refraction for the render's band table, and
/// whether white light splits into bands there (the effect plan decides).
#[derive(Clone, Debug, PartialEq)]
pub struct DielectricOptics {
    /// n for each band.
    pub band_ior: Vec<f32>,
    /// n for white light that does not split: the glass's one index when it
    /// has one, else the middle band's.
    pub white_ior: f32,
    /// The bands do not all share one index.
    pub dispersive: bool,
    /// White photons split into bands here.
    pub splits_photons: bool,
    /// White view rays split into bands here.
    pub splits_view_rays: bool,
    /// The relative index as a function of wavelength, for photons traced at
    /// their own wavelength ([`crate::WavelengthSampling::Continuous`]);
    /// `None` when a per-band table gives the index (no wavelength axis).
    pub spectrum: Option<IorCurve>,
    /// Beer–Lambert absorption inside (`None`: clear glass).
    pub absorption: Option<Absorption>,
    /// A thin sheet ([`MaterialKind::Dielectric`]'s `thin`): rays pass
    /// straight through ([`crate::optics::scatter`]).
    pub thin: bool,
    /// The film on its surface, its index relative to the outside
    /// (`None`: bare glass, or a film of no thickness).
    pub film: Option<ThinFilm>,
    /// Its facets' normal distribution; `None`: polished (roughness 0).
    pub ggx: Option<Ggx>,
}

/// A relative index of refraction sampled every nanometre over the visible
/// range, read by linear interpolation (the error of a Sellmeier curve
/// between samples is below 1e-7).
#[derive(Clone, Debug, PartialEq)]
pub struct IorCurve {
    /// n at `VISIBLE_NM.0 + i` nm.
    samples: Vec<f32>,
}

impl IorCurve {
    /// Samples n_inside(λ)/n_outside(λ); `None` when either has no wavelength axis.
    pub fn new(inside: &Dispersion, outside: &Dispersion) -> Option<Self> {
        let (lo, hi) = (VISIBLE_NM.0 as u32, VISIBLE_NM.1 as u32);
        let samples = (lo..=hi)
            .map(|nm| Some(inside.ior_at(nm as f32)? / outside.ior_at(nm as f32)?))
            .collect::<Option<Vec<f32>>>()?;
        Some(IorCurve { samples })
    }

    /// The samples, n at `VISIBLE_NM.0 + i` nm (for backends that upload the curve).
    pub fn samples(&self) -> &[f32] {
        &self.samples
    }

    /// n at `lambda_nm` (clamped to the visible range).
    pub fn at(&self, lambda_nm: f32) -> f32 {
        let x = (lambda_nm - VISIBLE_NM.0).clamp(0.0, (self.samples.len() - 1) as f32);
        let i = (x as usize).min(self.samples.len() - 2);
        let f = x - i as f32;
        self.samples[i] + (self.samples[i + 1] - self.samples[i]) * f
    }
}

impl DielectricOptics {
    /// The index for `band` ([`WHITE_BAND`]: the white index).
    #[inline]
    pub fn ior(&self, band: u16) -> f32 {
        if band == WHITE_BAND { self.white_ior } else { self.band_ior[usize::from(band)] }
    }

    /// The index for `band` traced at its own wavelength `lambda_nm`: the
    /// band's index moved along the glass's dispersion curve, so that the
    /// band's centre keeps exactly the band's index (and a per-band table,
    /// which has no curve, keeps it everywhere).
    #[inline]
    pub fn ior_at_wavelength(&self, band: u16, lambda_nm: f32, bands: &BandTable) -> f32 {
        let n = self.ior(band);
        match &self.spectrum {
            Some(curve) => n + (curve.at(lambda_nm) - curve.at(bands.band(usize::from(band)).lambda_nm)),
            None => n,
        }
    }

    /// The index a path of `band` sees: at its own wavelength when it has
    /// one ([`DielectricOptics::ior_at_wavelength`]), else the band's.
    #[inline]
    pub fn path_ior(&self, band: u16, lambda_nm: Option<f32>, bands: &BandTable) -> f32 {
        match lambda_nm {
            Some(lambda) => self.ior_at_wavelength(band, lambda, bands),
            None => self.ior(band),
        }
    }

    /// What a path of `band` (at its own wavelength `lambda_nm` when it has
    /// one) meets at this glass's surface: its index there, and the film
    /// seen at its wavelength: its own, else its band's centre, else (a
    /// white path, which the plan splits wherever a film shows) the middle
    /// band's, the band whose index white light takes.
    #[inline]
    pub fn face(&self, band: u16, lambda_nm: Option<f32>, bands: &BandTable) -> Face {
        let ior = self.path_ior(band, lambda_nm, bands);
        let Some(film) = self.film else { return Face::bare(ior, self.thin) };
        let lambda_nm = lambda_nm.unwrap_or_else(|| {
            let b = if band == WHITE_BAND { bands.len() / 2 } else { usize::from(band) };
            bands.band(b).lambda_nm
        });
        Face { ior, thin: self.thin, film: Some(film), lambda_nm }
    }

    /// What a crossing of this thin sheet keeps of a `band` path (white:
    /// the channels' mean): its tint, 1 for clear sheets and solid glass.
    #[inline]
    pub fn sheet_crossing(&self, band: u16) -> f32 {
        match (&self.absorption, self.thin) {
            (Some(a), true) => a.transmittance(band, 1.0),
            _ => 1.0,
        }
    }

    /// What a crossing of this thin sheet keeps of each RGB channel of a
    /// view path of `band` ([`crate::optics::absorption::Absorption::view_transmittance`]).
    #[inline]
    pub fn sheet_crossing_rgb(&self, band: u16) -> Vec3 {
        match (&self.absorption, self.thin) {
            (Some(a), true) => a.view_transmittance(band, 1.0),
            _ => Vec3::ONE,
        }
    }

    /// True when the bands do not all share one index.
    #[inline]
    pub fn is_dispersive(&self) -> bool {
        self.dispersive
    }

    /// True when the bands leave the glass differently, by their index, by
    /// their absorption or by a film's reflectance: white photons split
    /// into bands here.
    #[inline]
    pub fn is_chromatic(&self) -> bool {
        self.dispersive || self.absorption.is_some() || self.film.is_some()
    }

    /// True when view rays of different wavelengths leave the glass
    /// differently, by direction (dispersion) or by weight (a film's
    /// colours): white view rays split into bands here. Coloured glass
    /// tints a white view ray per RGB channel instead.
    #[inline]
    pub fn colours_view_rays(&self) -> bool {
        self.dispersive || self.film.is_some()
    }
}

impl Surface {
    /// The surface of `material` (its film, if any, as its film map
    /// varies it; its metal's layer coloured by its specular map) for the
    /// render's band table. Whether white light splits into bands at a
    /// dielectric is left unset: the effect plan decides it
    /// ([`crate::plan::prepared::PreparedScene::new`]).
    pub fn new(material: &Material, bands: &BandTable) -> Self {
        let film_map = material.film_map.as_ref();
        let unless_bare = |film: &Option<ThinFilm>| film.filter(|f| !f.is_bare(film_map));
        match &material.kind {
            MaterialKind::Diffuse { albedo, checker, texture, emission } => Surface::Diffuse {
                albedo: *albedo,
                checker: checker.clone(),
                texture: texture.clone(),
                emission: *emission,
            },
            MaterialKind::Mirror => Surface::Mirror,
            MaterialKind::Metal { color, roughness, texture, film, metalness } => Surface::Metal(MetalOptics {
                textured: texture.is_some(),
                layer_textured: material.specular_map.as_ref().is_some_and(|m| m.color.is_some()),
                film: unless_bare(film),
                metalness: *metalness,
                ..MetalOptics::new(*color, *roughness)
            }),
            MaterialKind::Dielectric { dispersion, outside, attenuation, thin, film, roughness } => {
                // Snell's law and Fresnel depend only on the ratio of the
                // indices, so the optics carry the relative index n/n_outside.
                let per_band =
                    |d: &Dispersion| -> Vec<f32> { (0..bands.len()).map(|b| d.ior_for_band(bands, b)).collect() };
                let (inside_ior, outside_ior) = (per_band(dispersion), per_band(outside));
                let band_ior: Vec<f32> = inside_ior.iter().zip(&outside_ior).map(|(n, m)| n / m).collect();
                let constant = dispersion.is_constant() && outside.is_constant();
                // A sheet sends every band on in the one direction it came:
                // only Fresnel differs, so white light does not split there.
                let dispersive = !constant && !thin && band_ior.iter().any(|&n| n != band_ior[0]);
                let outside_white = white_index(outside, &outside_ior);
                let white_ior = white_index(dispersion, &inside_ior) / outside_white;
                Surface::Dielectric(DielectricOptics {
                    band_ior,
                    white_ior,
                    dispersive,
                    splits_photons: false,
                    splits_view_rays: false,
                    spectrum: IorCurve::new(dispersion, outside),
                    // A sheet's crossing keeps the colour: its absorption is
                    // that of a unit length ([`DielectricOptics::sheet_crossing`]).
                    absorption: attenuation
                        .as_ref()
                        .map(|a| if *thin { Attenuation { distance: 1.0, ..*a } } else { *a })
                        .and_then(|a| Absorption::new(&a, bands)),
                    thin: *thin,
                    film: unless_bare(film).map(|f| ThinFilm { ior: f.ior / outside_white, ..f }),
                    ggx: (*roughness > 0.0).then(|| Ggx::from_roughness(*roughness)),
                })
            }
        }
    }

    /// Whether photons are stored on it and the camera gathers them there:
    /// a diffuse surface, or a blended metal (its diffuse part,
    /// [`crate::optics::metal`]).
    #[inline]
    pub fn stores_photons(&self) -> bool {
        match self {
            Surface::Diffuse { .. } => true,
            Surface::Metal(metal) => metal.is_blended(),
            _ => false,
        }
    }

    /// Whether the light it reflects or passes forms caustics worth aiming
    /// photons at (the effect plan's specular objects): a mirror, glass or
    /// a metal, but not a diffuse surface, nor a diffuse base under a
    /// dielectric's specular layer alone (glTF's non-metals: glTF's
    /// default layer reflects 4 % head on). Photons that reach such a
    /// base still reflect off its layer.
    #[inline]
    pub fn focuses_light(&self) -> bool {
        match self {
            Surface::Diffuse { .. } => false,
            Surface::Metal(metal) => metal.metalness.factor > 0.0,
            _ => true,
        }
    }

    /// Its GGX facets before any roughness map: a rough metal's (a
    /// blended metal's specular part's) or rough glass's; `None` where it
    /// is polished and on other surfaces.
    #[inline]
    pub fn facets(&self) -> Option<Ggx> {
        match self {
            Surface::Metal(metal) => metal.ggx,
            Surface::Dielectric(glass) => glass.ggx,
            _ => None,
        }
    }

    /// Radiance it emits toward a viewer on the side of `facing` (a ray's
    /// direction): its emission where the ray meets a front face (against
    /// the outward normal `outward`), else zero.
    #[inline]
    pub fn emitted(&self, facing: Vec3, outward: Vec3) -> Vec3 {
        match self {
            Surface::Diffuse { emission, .. } if facing.dot(outward) < 0.0 => *emission,
            _ => Vec3::ZERO,
        }
    }

    /// Albedo at world point `p` with unit normal `n` and texture
    /// coordinates `uv` (read only with a texture; the checker is evaluated
    /// a hair below the surface so that planes through a cell border do not flicker).
    #[inline]
    pub fn albedo_at(&self, p: Vec3, n: Vec3, uv: Vec2) -> Vec3 {
        let Surface::Diffuse { albedo, checker, texture, .. } = self else { return Vec3::ZERO };
        let base = match checker {
            None => *albedo,
            Some(ch) => {
                let q = (p + ch.offset - n * (ch.size * 1e-3)) / ch.size;
                let parity = (crate::util::math::floor(q.x)
                    + crate::util::math::floor(q.y)
                    + crate::util::math::floor(q.z)) as i64;
                if parity.rem_euclid(2) == 0 { *albedo } else { ch.albedo }
            }
        };
        match texture {
            None => base,
            Some(t) => base * crate::geometry::texture::sample(t, uv),
        }
    }
}

/// n for white light: the model's one index when it has one, else the
/// middle band's of `band_ior`.
fn white_index(dispersion: &Dispersion, band_ior: &[f32]) -> f32 {
    match dispersion {
        Dispersion::Constant(n) => *n,
        _ => band_ior[band_ior.len() / 2],
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::bands::BandSpec;
    use crate::model::scene::{FilmMap, Sampler};

    fn glass(film: Option<ThinFilm>, outside: f32) -> DielectricOptics {
        let material = MaterialKind::Dielectric {
            dispersion: Dispersion::Constant(1.5),
            outside: Dispersion::Constant(outside),
            attenuation: None,
            thin: false,
            film,
            roughness: 0.0,
        };
        glass_under(&material, None)
    }

    fn glass_under(material: &MaterialKind, map: Option<&FilmMap>) -> DielectricOptics {
        let material = Material { film_map: map.cloned(), ..Material::new("glass", material.clone()) };
        let Surface::Dielectric(g) = Surface::new(&material, &BandTable::new(BandSpec::Paper7)) else { unreachable!() };
        g
    }

    #[test]
    fn a_film_is_seen_at_the_paths_wavelength_its_bands_or_the_middle_bands() {
        let bands = BandTable::new(BandSpec::Paper7);
        let g = glass(Some(ThinFilm::new(1.38, 120.0)), 1.0);
        assert!(g.is_chromatic() && g.colours_view_rays(), "one index, but the film colours the light");
        assert_eq!(g.face(2, Some(432.5), &bands).lambda_nm, 432.5);
        assert_eq!(g.face(2, None, &bands).lambda_nm, bands.band(2).lambda_nm);
        assert_eq!(g.face(WHITE_BAND, None, &bands).lambda_nm, bands.band(3).lambda_nm);
        assert_eq!(g.face(WHITE_BAND, None, &bands).ior, g.white_ior);
        // In water the film's index, like the glass's, is relative to the outside.
        let film = glass(Some(ThinFilm::new(1.38, 120.0)), 1.33).film.unwrap();
        assert!((film.ior - 1.38 / 1.33).abs() < 1e-6, "{film:?}");
    }

    #[test]
    fn a_film_of_no_thickness_or_no_factor_is_bare_glass() {
        for film in [ThinFilm::new(2.0, 0.0), ThinFilm { factor: 0.0, ..ThinFilm::new(2.0, 300.0) }] {
            let g = glass(Some(film), 1.0);
            assert_eq!(g, glass(None, 1.0), "{film:?}");
            assert!(!g.is_chromatic() && !g.colours_view_rays());
        }
    }

    /// glTF's `iridescenceThicknessMinimum` above a maximum of 0: the film
    /// is min · (1 − g) thick where the map's green is g, so not bare.
    #[test]
    fn a_film_of_no_thickness_under_a_map_of_a_positive_minimum_is_kept() {
        let material = MaterialKind::Dielectric {
            dispersion: Dispersion::Constant(1.5),
            outside: Dispersion::Constant(1.0),
            attenuation: None,
            thin: false,
            film: Some(ThinFilm::new(1.3, 0.0)),
            roughness: 0.0,
        };
        // One texel of green 0: the film is the minimum thick.
        let texels = Texture {
            name: "thickness".into(),
            width: 1,
            height: 1,
            texels: alloc::vec![0u32].into(),
            sampler: Sampler::default(),
        };
        let map = |min_nm: f32, thickness: Option<Texture>| FilmMap { thickness, min_nm, factor: None };
        assert!(glass_under(&material, Some(&map(250.0, Some(texels.clone())))).film.is_some());
        for bare in [map(0.0, Some(texels.clone())), map(250.0, None)] {
            assert_eq!(glass_under(&material, Some(&bare)).film, None, "{bare:?}");
        }
    }
}
