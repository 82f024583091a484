//! Partial renders: the raw sums of a range of progressive passes, written
//! by `render --passes A..B --partial FILE` and combined by `merge`. The sums
//! are integers, so merging partials gives the image of one run bit for bit.
//!
//! Format (little endian): the magic line `PRISMATIC-PARTIAL 1\n`; the
//! scene's fingerprint (u64); the backend's name (u8 length, bytes); width,
//! height (u32); display (u8: the tone map's index in `ToneMap::ALL`, 0 clamp,
//! 1 reinhard, 2 pbr_neutral, 3 agx, plus 128 with automatic exposure); the pass ranges (u32
//! count, then u32 start and end each); the image without caustics (3 f32
//! per pixel); the features an EXR carries (albedo, normal: 3 f32 each per
//! pixel; depth: 1 f32 per pixel); the caustic sums (3 i64 per pixel); an
//! FNV-1a checksum (u64) of everything before it.

use crate::scene_file::SceneFileError;
use prismatic_core::Accumulation;
use prismatic_core::model::color::{Display, ToneMap};
use prismatic_core::render::aov::{Features, features};
use prismatic_core::{Image, PreparedScene, Render, Vec3};
use std::io::Write;
use std::path::Path;

const MAGIC: &[u8] = b"PRISMATIC-PARTIAL 2\n";

/// Bytes a pixel takes: base and features (10 f32), sums (3 i64).
const PIXEL_BYTES: usize = 10 * 4 + 3 * 8;

/// A partial render as stored in a file.
#[derive(Clone, Debug, PartialEq)]
pub struct Partial {
    /// Which scene and settings it belongs to ([`fingerprint`]).
    pub fingerprint: u64,
    /// The backend that rendered it.
    pub backend: String,
    /// How the image is displayed.
    pub display: Display,
    /// The image without caustics.
    pub base: Image,
    /// Albedo, normal and depth at the first hit, for an EXR's layers.
    pub features: Features,
    /// The passes' sums.
    pub sums: Accumulation,
}

/// A fingerprint of everything that decides a pass's result: the scene and
/// its settings, except the number of passes.
pub fn fingerprint(scene: &PreparedScene) -> u64 {
    let mut s = scene.scene.clone();
    s.render.passes = 0;
    fnv1a(format!("{s:?}").as_bytes())
}

fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325u64, |h, &b| (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3))
}

impl Partial {
    /// The partial of `render`'s passes: its base and `sums`.
    pub fn of(render: &dyn Render, base: Image, sums: Accumulation) -> Partial {
        let scene = render.scene();
        Partial {
            fingerprint: fingerprint(scene),
            backend: render.backend().to_string(),
            display: scene.scene.render.display(),
            base,
            features: features(scene),
            sums,
        }
    }

    /// The file's bytes.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(MAGIC.len() + self.base.pixels.len() * PIXEL_BYTES + 64);
        out.extend_from_slice(MAGIC);
        out.extend_from_slice(&self.fingerprint.to_le_bytes());
        out.push(self.backend.len().min(255) as u8);
        out.extend_from_slice(&self.backend.as_bytes()[..self.backend.len().min(255)]);
        out.extend_from_slice(&self.base.width.to_le_bytes());
        out.extend_from_slice(&self.base.height.to_le_bytes());
        let tone_map = ToneMap::ALL.iter().position(|&t| t == self.display.tone_map).unwrap_or(0) as u8;
        out.push(tone_map | u8::from(self.display.auto_exposure) << 7);
        out.extend_from_slice(&(self.sums.passes.len() as u32).to_le_bytes());
        for &(a, b) in &self.sums.passes {
            out.extend_from_slice(&a.to_le_bytes());
            out.extend_from_slice(&b.to_le_bytes());
        }
        let f = &self.features;
        for image in [&self.base, &f.albedo, &f.normal] {
            for c in image.pixels.iter().flat_map(|p| p.to_array()) {
                out.extend_from_slice(&c.to_le_bytes());
            }
        }
        for d in &f.depth {
            out.extend_from_slice(&d.to_le_bytes());
        }
        for s in &self.sums.sums {
            for c in s {
                out.extend_from_slice(&c.to_le_bytes());
            }
        }
        let sum = fnv1a(&out);
        out.extend_from_slice(&sum.to_le_bytes());
        out
    }

    /// Writes the file.
    pub fn write(&self, w: &mut impl Write) -> anyhow::Result<()> {
        w.write_all(&self.to_bytes())?;
        Ok(())
    }

    /// Reads a partial file; `file` names it in errors.
    pub fn read(path: &Path) -> Result<Partial, SceneFileError> {
        let file = path.display().to_string();
        let bytes = std::fs::read(path).map_err(|e| bad(&file, format!("cannot read: {e}")))?;
        Self::from_bytes(&bytes).map_err(|reason| bad(&file, reason))
    }

    /// Parses a partial file's bytes.
    pub fn from_bytes(bytes: &[u8]) -> Result<Partial, String> {
        if !bytes.starts_with(MAGIC) {
            return Err("not a prismatic partial render (written by `prismatic render --partial`)".into());
        }
        if bytes.len() < MAGIC.len() + 8 {
            return Err("truncated".into());
        }
        let (body, tail) = bytes.split_at(bytes.len() - 8);
        let mut r = Reader { bytes: body, at: MAGIC.len() };
        let fingerprint = r.u64()?;
        let name_len = usize::from(r.take(1)?[0]);
        let backend = String::from_utf8_lossy(r.take(name_len)?).into_owned();
        let (width, height) = (r.u32()?, r.u32()?);
        let shown = r.take(1)?[0];
        let tone_map =
            *ToneMap::ALL.get(usize::from(shown & 0x7f)).ok_or(format!("unknown tone map {}", shown & 0x7f))?;
        let display = Display { tone_map, auto_exposure: shown & 0x80 != 0 };
        let ranges = r.u32()? as usize;
        let pixels = width as usize * height as usize;
        let expected = r.at + ranges * 8 + pixels * PIXEL_BYTES;
        if body.len() != expected {
            return Err(format!(
                "{} bytes where a {width}x{height} partial with {ranges} pass ranges has {} (truncated or damaged)",
                bytes.len(),
                expected + 8
            ));
        }
        if fnv1a(body).to_le_bytes() != tail {
            return Err("checksum mismatch (damaged)".into());
        }
        let mut passes = Vec::with_capacity(ranges);
        for _ in 0..ranges {
            passes.push((r.u32()?, r.u32()?));
        }
        let mut images = [Image::new(width, height), Image::new(width, height), Image::new(width, height)];
        for image in &mut images {
            for p in &mut image.pixels {
                *p = Vec3::new(r.f32()?, r.f32()?, r.f32()?);
            }
        }
        let [base, albedo, normal] = images;
        let mut depth = vec![0.0; pixels];
        for d in &mut depth {
            *d = r.f32()?;
        }
        let features = Features { albedo, normal, depth };
        let mut raw = vec![[0i64; 3]; pixels];
        for s in &mut raw {
            *s = [r.i64()?, r.i64()?, r.i64()?];
        }
        let sums = Accumulation::from_parts(width, height, &passes, raw).map_err(|e| format!("pass ranges: {e}"))?;
        Ok(Partial { fingerprint, backend, display, base, features, sums })
    }

    /// Adds `other` (same scene, backend and size; disjoint passes).
    pub fn merge(&mut self, other: &Partial, file: &str) -> Result<(), SceneFileError> {
        let size = |p: &Partial| (p.base.width, p.base.height);
        if size(other) != size(self) {
            return Err(bad(
                file,
                format!(
                    "a {}x{} image; the first partial is {}x{}",
                    other.base.width, other.base.height, self.base.width, self.base.height
                ),
            ));
        }
        if other.fingerprint != self.fingerprint {
            return Err(bad(file, "rendered from a different scene or settings than the first partial".into()));
        }
        if other.backend != self.backend {
            return Err(bad(
                file,
                format!(
                    "rendered by the {} backend, the first partial by {} (backends agree within tolerances, not \
                     bit for bit: render every range on one)",
                    other.backend, self.backend
                ),
            ));
        }
        if other.base != self.base || other.features != self.features {
            return Err(bad(file, "its image without caustics differs from the first partial's".into()));
        }
        self.sums.merge(&other.sums).map_err(|e| bad(file, e.to_string()))
    }

    /// The image of the passes summed.
    pub fn image(&self) -> Image {
        self.sums.image(&self.base)
    }
}

fn bad(file: &str, reason: String) -> SceneFileError {
    SceneFileError { file: file.to_string(), line: None, key: String::new(), reason }
}

struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl<'a> Reader<'a> {
    fn take(&mut self, n: usize) -> Result<&'a [u8], String> {
        let s = self.bytes.get(self.at..self.at + n).ok_or("truncated")?;
        self.at += n;
        Ok(s)
    }
    fn u32(&mut self) -> Result<u32, String> {
        Ok(u32::from_le_bytes(self.take(4)?.try_into().expect("4 bytes")))
    }
    fn u64(&mut self) -> Result<u64, String> {
        Ok(u64::from_le_bytes(self.take(8)?.try_into().expect("8 bytes")))
    }
    fn i64(&mut self) -> Result<i64, String> {
        Ok(i64::from_le_bytes(self.take(8)?.try_into().expect("8 bytes")))
    }
    fn f32(&mut self) -> Result<f32, String> {
        Ok(f32::from_le_bytes(self.take(4)?.try_into().expect("4 bytes")))
    }
}
