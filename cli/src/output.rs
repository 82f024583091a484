//! Output files written atomically: a temporary file beside the target,
//! renamed into place only when complete. The temporary file is created
//! before any work starts, so an unwritable path fails early.

use anyhow::{Context, Result};
use prismatic_core::model::color::Display;
use prismatic_core::render::aov::{Features, features};
use prismatic_core::{Image, PhotonMap, PreparedScene};
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU32, Ordering};

/// A file being written: a temporary file that becomes `target` on [`commit`](Self::commit).
pub struct PendingFile {
    target: PathBuf,
    temp: PathBuf,
    file: Option<File>,
}

impl PendingFile {
    /// Creates the temporary file next to `target` (fails now if the place is not writable).
    pub fn create(target: &Path) -> Result<Self> {
        let name = target.file_name().with_context(|| format!("{}: not a file path", target.display()))?;
        let dir = target.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
        // A counter too: a long render rewrites its output while the final one is pending.
        static NEXT: AtomicU32 = AtomicU32::new(0);
        let n = NEXT.fetch_add(1, Ordering::Relaxed);
        let temp = dir.join(format!(".{}.tmp{}-{n}", name.to_string_lossy(), std::process::id()));
        let file = File::create(&temp).with_context(|| format!("{}: cannot write here", target.display()))?;
        Ok(PendingFile { target: target.to_path_buf(), temp, file: Some(file) })
    }

    /// Writes the content with `write` and renames the file into place.
    pub fn commit(mut self, write: impl FnOnce(&mut BufWriter<File>) -> Result<()>) -> Result<()> {
        let file = self.file.take().expect("file is present until commit");
        let mut w = BufWriter::new(file);
        write(&mut w).with_context(|| format!("{}: write failed", self.target.display()))?;
        w.flush()?;
        w.get_ref().sync_all().ok();
        std::fs::rename(&self.temp, &self.target)
            .with_context(|| format!("{}: cannot rename into place", self.target.display()))?;
        Ok(())
    }
}

impl Drop for PendingFile {
    fn drop(&mut self) {
        if self.file.is_some() {
            let _ = std::fs::remove_file(&self.temp);
        }
    }
}

/// Encodes `image` as an 8-bit sRGB PNG, shown as `display` says.
pub fn write_png(w: &mut BufWriter<File>, image: &Image, display: Display) -> Result<()> {
    let buf =
        image::RgbImage::from_raw(image.width, image.height, image.to_srgb8(display)).context("image size mismatch")?;
    buf.write_to(w, image::ImageFormat::Png)?;
    Ok(())
}

/// Encodes `image` as OpenEXR: linear RGB, 32-bit float, no tone mapping.
pub fn write_exr(w: &mut BufWriter<File>, image: &Image) -> Result<()> {
    write_exr_layers(w, image, &ExrLayers::default())
}

/// What an EXR carries beside the image, for denoisers and compositors.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ExrLayers {
    /// The caustic light alone (the image less its view pass): `caustic.R/G/B`.
    pub caustic: Option<Image>,
    /// Albedo, normal and depth at the first hit ([`features`]):
    /// `albedo.R/G/B`, `normal.X/Y/Z`, `Z`.
    pub features: Option<Features>,
}

impl ExrLayers {
    /// Every layer of a render: its features and its caustic (`image`
    /// less `base`, the view pass).
    pub fn of(scene: &PreparedScene, image: &Image, base: &Image) -> Self {
        ExrLayers { caustic: Some(Self::caustic(image, base)), features: Some(features(scene)) }
    }

    /// The caustic light alone: `image` less `base`, its view pass.
    pub fn caustic(image: &Image, base: &Image) -> Image {
        Image { pixels: image.pixels.iter().zip(&base.pixels).map(|(a, b)| *a - *b).collect(), ..base.clone() }
    }
}

/// Encodes `image` as one OpenEXR part of 32-bit float channels: the image
/// as `R`, `G`, `B` (what viewers show) and `layers` as named channels
/// (OpenImageDenoise's albedo and normal, Blender's and Nuke's `Z`).
pub fn write_exr_layers(w: &mut BufWriter<File>, image: &Image, layers: &ExrLayers) -> Result<()> {
    use exr::prelude::{
        AnyChannel, AnyChannels, Encoding, FlatSamples, Layer, LayerAttributes, SmallVec, WritableImage,
    };
    let rgb = |prefix: &str, img: &Image, names: [&str; 3]| -> Vec<AnyChannel<FlatSamples>> {
        (0..3)
            .map(|k| {
                let samples = img.pixels.iter().map(|p| p[k]).collect();
                AnyChannel::new(format!("{prefix}{}", names[k]).as_str(), FlatSamples::F32(samples))
            })
            .collect()
    };
    let mut channels = rgb("", image, ["R", "G", "B"]);
    if let Some(caustic) = &layers.caustic {
        channels.extend(rgb("caustic.", caustic, ["R", "G", "B"]));
    }
    if let Some(f) = &layers.features {
        channels.extend(rgb("albedo.", &f.albedo, ["R", "G", "B"]));
        channels.extend(rgb("normal.", &f.normal, ["X", "Y", "Z"]));
        channels.push(AnyChannel::new("Z", FlatSamples::F32(f.depth.clone())));
    }
    let size = (image.width as usize, image.height as usize);
    let layer = Layer::new(
        size,
        LayerAttributes::default(),
        Encoding::SMALL_LOSSLESS,
        AnyChannels::sort(SmallVec::from_vec(channels)),
    );
    let mut bytes = std::io::Cursor::new(Vec::new());
    exr::prelude::Image::from_layer(layer).write().to_buffered(&mut bytes).context("cannot encode the EXR")?;
    w.write_all(bytes.get_ref())?;
    Ok(())
}

/// Reads an OpenEXR file as a linear image (every bit of an f32 image
/// written by [`write_exr`]).
pub fn read_exr(path: &Path) -> Result<Image> {
    let decoded = image::open(path).with_context(|| format!("{}: cannot read", path.display()))?.into_rgb32f();
    let (width, height) = decoded.dimensions();
    let pixels = decoded.pixels().map(|p| prismatic_core::Vec3::from(p.0)).collect();
    Ok(Image { width, height, pixels })
}

/// Writes `image` as EXR (linear, with `layers`) when `path` ends in
/// `.exr`, else as a tone-mapped sRGB PNG.
pub fn write_image(
    w: &mut BufWriter<File>,
    path: &Path,
    image: &Image,
    display: Display,
    layers: impl FnOnce() -> ExrLayers,
) -> Result<()> {
    if is_exr(path) { write_exr_layers(w, image, &layers()) } else { write_png(w, image, display) }
}

/// True for `.exr` paths (any case).
fn is_exr(path: &Path) -> bool {
    path.extension().is_some_and(|e| e.eq_ignore_ascii_case("exr"))
}

/// The CSV header of `prismatic photons`.
pub const PHOTON_CSV_HEADER: &str = "emission,band,lambda_nm,x,y,z,dir_x,dir_y,dir_z,power";

/// Writes the photon map as CSV in canonical order, positions in world
/// coordinates (the scene's local frame plus `origin`, in f64), each with
/// the wavelength it was traced at. White (unsplit) photons have band -1
/// and an empty wavelength.
pub fn write_photon_csv(w: &mut impl Write, map: &PhotonMap, origin: glam::DVec3) -> Result<()> {
    writeln!(w, "{PHOTON_CSV_HEADER}")?;
    for p in &map.photons {
        let d = p.direction();
        let [x, y, z] = (p.pos().as_dvec3() + origin).to_array();
        match p.wavelength() {
            Some(lambda_nm) => write!(w, "{},{},{lambda_nm},", p.emission, p.band)?,
            None => write!(w, "{},-1,,", p.emission)?,
        }
        writeln!(w, "{x},{y},{z},{},{},{},{}", d.x, d.y, d.z, p.flux)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The reference cache relies on it: EXR keeps every bit of f32 pixels.
    #[test]
    fn exr_round_trip_keeps_every_bit_and_the_row_order() {
        let mut image = Image::new(3, 2);
        for (i, p) in image.pixels.iter_mut().enumerate() {
            *p = prismatic_core::Vec3::new(i as f32 + 0.1, -0.1 * i as f32, f32::MIN_POSITIVE * i as f32);
        }
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("x.exr");
        write_exr(&mut BufWriter::new(File::create(&path).unwrap()), &image).unwrap();
        let back = read_exr(&path).unwrap();
        assert_eq!((back.width, back.height), (3, 2));
        for (a, b) in back.pixels.iter().zip(&image.pixels) {
            assert_eq!(a.to_array().map(f32::to_bits), b.to_array().map(f32::to_bits));
        }
        std::fs::write(&path, b"not an exr").unwrap();
        assert!(read_exr(&path).is_err());
    }
}
