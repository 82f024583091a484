//! Portable float maps (PFM, colour, little-endian): linear images that
//! keep every bit, for cached references. Most HDR viewers open them.

use anyhow::{Context, Result, bail, ensure};
use prismatic_core::{Image, Vec3};
use std::path::Path;

/// Writes `image` as a colour PFM (rows bottom to top, as the format says).
pub fn write(path: &Path, image: &Image) -> Result<()> {
    let mut bytes = format!("PF\n{} {}\n-1.0\n", image.width, image.height).into_bytes();
    for row in image.pixels.chunks(image.width as usize).rev() {
        for p in row {
            for c in p.to_array() {
                bytes.extend_from_slice(&c.to_le_bytes());
            }
        }
    }
    std::fs::write(path, bytes).with_context(|| format!("{}: cannot write", path.display()))
}

/// Reads a colour PFM written by [`write`] (little-endian only).
pub fn read(path: &Path) -> Result<Image> {
    let bytes = std::fs::read(path).with_context(|| format!("{}: cannot read", path.display()))?;
    // Header: "PF", width, height, scale (negative: little-endian), each
    // ended by whitespace; the pixels start after the scale's one whitespace byte.
    let mut tokens = Vec::new();
    let mut at = 0;
    while tokens.len() < 4 {
        let start = at + bytes[at..].iter().position(|b| !b.is_ascii_whitespace()).context("truncated header")?;
        let len = bytes[start..].iter().position(|b| b.is_ascii_whitespace()).context("truncated header")?;
        tokens.push(std::str::from_utf8(&bytes[start..start + len])?.to_string());
        at = start + len;
    }
    at += 1;
    ensure!(tokens[0] == "PF", "not a colour PFM (magic {:?})", tokens[0]);
    let (width, height): (u32, u32) = (tokens[1].parse()?, tokens[2].parse()?);
    let scale: f32 = tokens[3].parse()?;
    if scale >= 0.0 {
        bail!("big-endian PFM is not supported");
    }
    let expected = width as usize * height as usize * 12;
    ensure!(bytes.len() - at == expected, "{} bytes of pixels, expected {expected}", bytes.len() - at);
    let mut image = Image::new(width, height);
    let floats: Vec<f32> = bytes[at..].chunks_exact(4).map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]])).collect();
    for (y, row) in floats.chunks_exact(width as usize * 3).enumerate() {
        let dest = (height as usize - 1 - y) * width as usize;
        for (x, p) in row.chunks_exact(3).enumerate() {
            image.pixels[dest + x] = Vec3::new(p[0], p[1], p[2]);
        }
    }
    Ok(image)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trip_keeps_every_bit_and_the_row_order() {
        let mut image = Image::new(3, 2);
        for (i, p) in image.pixels.iter_mut().enumerate() {
            *p = Vec3::new(i as f32, -0.1 * i as f32, f32::MIN_POSITIVE * i as f32);
        }
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("x.pfm");
        write(&path, &image).unwrap();
        assert_eq!(read(&path).unwrap(), image);
        std::fs::write(&path, b"PF\n3 2\n-1.0\n\0\0").unwrap();
        assert!(read(&path).unwrap_err().to_string().contains("expected 72"));
    }
}
