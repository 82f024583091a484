//! The stored photon (32 bytes, GPU-ready), the photon map and trace statistics.

use alloc::vec::Vec;
use bytemuck::{Pod, Zeroable};
use glam::{Vec2, Vec3};

/// Band id of a photon that has not been split (white light, all bands).
pub const WHITE_BAND: u16 = u16::MAX;

/// A caustic photon stored on a diffuse surface (or met on a rough one,
/// [`ON_ROUGH_SURFACE`]).
///
/// `#[repr(C)]` and `Pod` so that it can be copied to and from GPU buffers
/// as is; its WGSL twin is `Photon` in the GPU backend's shaders.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct Photon {
    /// Where it landed.
    pub position: [f32; 3],
    /// Its flux in W (a band photon carries 1/N of its white photon's flux).
    pub flux: f32,
    /// Direction of travel when stored, octahedron-encoded in two signed
    /// 16-bit fractions (see [`oct_pack`]; within 0.004° of the traced direction).
    pub direction_oct: u32,
    /// The wavelength it was traced at, in nm: its own with continuous and
    /// hero sampling, its band's with split and random-band sampling; 0
    /// for white light ([`WHITE_BAND`]).
    pub lambda_nm: f32,
    /// Index of the emitted white photon this photon came from.
    pub emission: u32,
    /// Band id, or [`WHITE_BAND`].
    pub band: u16,
    /// Surfaces its path met before this one (specular interactions for a
    /// caustic photon; diffuse bounces too for indirect light's), and in
    /// its top bit [`ON_ROUGH_SURFACE`].
    pub bounces: u16,
}

/// The bit of [`Photon::bounces`] that marks a caustic photon met on a rough
/// metal or rough glass (not a diffuse surface): light tracing connects it
/// to the camera through the surface's BSDF
/// ([`crate::photons::light_tracing`]); gathers, which estimate what
/// diffuse surfaces reflect, pass it by.
pub const ON_ROUGH_SURFACE: u16 = 1 << 15;

const _: () = assert!(core::mem::size_of::<Photon>() == 32);

impl Photon {
    /// Position as a vector.
    #[inline]
    pub fn pos(&self) -> Vec3 {
        Vec3::from(self.position)
    }

    /// Unit direction of travel when stored.
    #[inline]
    pub fn direction(&self) -> Vec3 {
        oct_unpack(self.direction_oct)
    }

    /// Whether it was met on a rough metal or glass ([`ON_ROUGH_SURFACE`]).
    #[inline]
    pub fn on_rough_surface(&self) -> bool {
        self.bounces & ON_ROUGH_SURFACE != 0
    }

    /// The wavelength it was traced at, `None` for white light.
    #[inline]
    pub fn wavelength(&self) -> Option<f32> {
        (self.band != WHITE_BAND).then_some(self.lambda_nm)
    }

    /// The canonical sort key: (emission, band, bounces), a photon met on
    /// a rough surface after one stored at the same bounce (a blended
    /// metal keeps both). A caustic emission stores once per band (and
    /// meets rough surfaces on its way); an indirect one may store several
    /// times: path order (bounces increase along a path).
    #[inline]
    pub fn key(&self) -> (u32, u16, u16) {
        (self.emission, self.band, self.bounces.rotate_left(1))
    }
}

/// Octahedral encoding of a unit vector into [-1, 1]² (Cigolle et al. 2014).
#[inline]
pub fn oct_encode(n: Vec3) -> Vec2 {
    let n = n / (n.x.abs() + n.y.abs() + n.z.abs());
    let p = Vec2::new(n.x, n.y);
    if n.z >= 0.0 {
        p
    } else {
        Vec2::new((1.0 - p.y.abs()) * sign_not_zero(p.x), (1.0 - p.x.abs()) * sign_not_zero(p.y))
    }
}

/// Inverse of [`oct_encode`].
#[inline]
pub fn oct_decode(e: Vec2) -> Vec3 {
    let z = 1.0 - e.x.abs() - e.y.abs();
    let (x, y) = if z < 0.0 {
        ((1.0 - e.y.abs()) * sign_not_zero(e.x), (1.0 - e.x.abs()) * sign_not_zero(e.y))
    } else {
        (e.x, e.y)
    };
    Vec3::new(x, y, z).normalize()
}

/// [`oct_encode`] of unit `n` in two signed 16-bit fractions, x in the
/// low half: each coordinate c becomes ⌊0.5 + 32767·c⌋, as WGSL's
/// `pack2x16snorm` rounds.
#[inline]
pub fn oct_pack(n: Vec3) -> u32 {
    let e = oct_encode(n);
    let q = |c: f32| (crate::util::math::floor(0.5 + 32767.0 * c.clamp(-1.0, 1.0)) as i16) as u16;
    u32::from(q(e.x)) | (u32::from(q(e.y)) << 16)
}

/// Inverse of [`oct_pack`] (WGSL's `unpack2x16snorm`, then [`oct_decode`]).
#[inline]
pub fn oct_unpack(packed: u32) -> Vec3 {
    let c = |bits: u32| (f32::from(bits as u16 as i16) / 32767.0).max(-1.0);
    oct_decode(Vec2::new(c(packed & 0xffff), c(packed >> 16)))
}

#[inline]
fn sign_not_zero(x: f32) -> f32 {
    if x >= 0.0 { 1.0 } else { -1.0 }
}

/// What a photon pass did, for reports and for energy bookkeeping.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TraceStats {
    /// White photons emitted.
    pub emitted: u64,
    /// Paths traced: one per emitted photon, plus N − 1 per split.
    pub paths: u64,
    /// Ray segments traced (intersection queries that hit something or escaped).
    pub segments: u64,
    /// Photons that took part in at least one specular interaction.
    pub specular_paths: u64,
    /// Photons stored (those met on rough surfaces too, [`ON_ROUGH_SURFACE`]).
    pub stored: u64,
    /// Flux of the photons traced (W); with projection maps, their weighted flux.
    pub flux_emitted: f64,
    /// Flux of the stored photons (not of those met on rough surfaces,
    /// whose paths go on: their flux is tallied where they end).
    pub flux_stored: f64,
    /// Flux that left the scene.
    pub flux_escaped: f64,
    /// Flux absorbed at diffuse surfaces reached directly from a light (not caustic).
    pub flux_direct: f64,
    /// Flux of paths ended by the depth limit.
    pub flux_depth_limited: f64,
    /// Flux absorbed inside coloured glass.
    pub flux_absorbed: f64,
}

impl TraceStats {
    /// Tallies one stored photon of `flux`.
    #[inline]
    pub fn count_stored(&mut self, flux: f32) {
        self.stored += 1;
        self.flux_stored += f64::from(flux);
    }

    /// Adds another pass's statistics (for backends that trace in chunks).
    pub fn merge(&mut self, o: &TraceStats) {
        self.emitted += o.emitted;
        self.paths += o.paths;
        self.segments += o.segments;
        self.specular_paths += o.specular_paths;
        self.stored += o.stored;
        self.flux_emitted += o.flux_emitted;
        self.flux_stored += o.flux_stored;
        self.flux_escaped += o.flux_escaped;
        self.flux_direct += o.flux_direct;
        self.flux_depth_limited += o.flux_depth_limited;
        self.flux_absorbed += o.flux_absorbed;
    }
}

/// The dispersion caustic map: stored photons in canonical (emission, band, bounces) order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PhotonMap {
    /// The photons.
    pub photons: Vec<Photon>,
    /// What the pass did.
    pub stats: TraceStats,
}

impl PhotonMap {
    /// Puts the photons in canonical (emission, band, bounces) order.
    pub fn sort_canonical(&mut self) {
        self.photons.sort_unstable_by_key(Photon::key);
    }

    /// True when the photons are in canonical order.
    pub fn is_canonical(&self) -> bool {
        self.photons.windows(2).all(|w| w[0].key() < w[1].key())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn octahedral_round_trip() {
        for d in [Vec3::X, -Vec3::Y, Vec3::Z, -Vec3::Z, Vec3::new(0.3, -0.5, -0.8), Vec3::new(-1.0, 2.0, 0.1)] {
            let d = d.normalize();
            let back = oct_decode(oct_encode(d));
            assert!((back - d).length() < 1e-6, "{d} -> {back}");
        }
    }

    #[test]
    fn packed_directions_keep_four_thousandths_of_a_degree() {
        let mut worst = 0.0f32;
        for i in 0..20_000u32 {
            // A spiral over the sphere.
            let z = 1.0 - 2.0 * (i as f32 + 0.5) / 20_000.0;
            let phi = i as f32 * 2.399_963;
            let r = (1.0 - z * z).max(0.0).sqrt();
            let d = Vec3::new(r * phi.cos(), r * phi.sin(), z);
            // The chord, not f32's acos (which is ±0.02° near 1).
            worst = worst.max((oct_unpack(oct_pack(d)) - d).length().to_degrees());
        }
        assert!(worst < 0.004, "{worst}°");
        for axis in [Vec3::X, Vec3::NEG_X, Vec3::Y, Vec3::NEG_Y, Vec3::Z, Vec3::NEG_Z] {
            assert_eq!(oct_unpack(oct_pack(axis)), axis);
        }
    }
}
