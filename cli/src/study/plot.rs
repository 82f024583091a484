//! The study's plot: error (mean ΔE00) against time, log–log, one curve per
//! series, the Pareto front ringed and joined, ΔE00 = 1 and 2.3 marked.
//! Drawn straight into an RGB raster with an 8×8 bitmap font.

use super::StudyRow;
use font8x8::legacy::BASIC_LEGACY;
use image::{Rgb, RgbImage};

const WIDTH: u32 = 1000;
const HEIGHT: u32 = 640;
/// Plot area: left, top, right, bottom.
const AREA: (i32, i32, i32, i32) = (80, 50, 720, 580);

/// Distinct colours for up to 16 series (then they repeat).
const PALETTE: [[u8; 3]; 16] = [
    [31, 119, 180],
    [255, 127, 14],
    [44, 160, 44],
    [214, 39, 40],
    [148, 103, 189],
    [140, 86, 75],
    [227, 119, 194],
    [127, 127, 127],
    [188, 189, 34],
    [23, 190, 207],
    [57, 59, 121],
    [173, 73, 74],
    [99, 121, 57],
    [140, 109, 49],
    [206, 109, 189],
    [0, 0, 0],
];

/// Draws the plot of `rows` (titled `title`).
pub fn draw(rows: &[StudyRow], title: &str) -> RgbImage {
    let mut img = RgbImage::from_pixel(WIDTH, HEIGHT, Rgb([255, 255, 255]));
    let pts: Vec<(f64, f64)> = rows.iter().map(|r| (r.total_s().max(1e-4), r.error.delta_e.max(1e-3))).collect();
    let decade = |v: f64, up: bool| if up { 10f64.powf(v.log10().ceil()) } else { 10f64.powf(v.log10().floor()) };
    let (x0, x1) = bounds(pts.iter().map(|p| p.0), decade);
    let (y0, y1) = bounds(pts.iter().map(|p| p.1).chain([1.0, 2.3]), decade);
    let (l, t, r, b) = AREA;
    let map = |(x, y): (f64, f64)| -> (i32, i32) {
        let fx = (x.log10() - x0.log10()) / (x1.log10() - x0.log10());
        let fy = (y.log10() - y0.log10()) / (y1.log10() - y0.log10());
        (l + (fx * f64::from(r - l)).round() as i32, b - (fy * f64::from(b - t)).round() as i32)
    };
    // Grid and tick labels at decades, lighter lines at 2 and 5.
    let grid = Rgb([225, 225, 225]);
    for (lo, hi, vertical) in [(x0, x1, true), (y0, y1, false)] {
        let mut d = lo;
        while d <= hi * 1.0001 {
            for m in [1.0, 2.0, 5.0] {
                let v = d * m;
                if v > hi * 1.0001 {
                    break;
                }
                let colour = if m == 1.0 { Rgb([190, 190, 190]) } else { grid };
                if vertical {
                    let (x, _) = map((v, y0));
                    line(&mut img, (x, t), (x, b), colour, false);
                    if m == 1.0 {
                        let label = number(v);
                        text(&mut img, x - 4 * label.len() as i32, b + 8, &label, Rgb([0, 0, 0]));
                    }
                } else {
                    let (_, y) = map((x0, v));
                    line(&mut img, (l, y), (r, y), colour, false);
                    if m == 1.0 || m == 2.0 || m == 5.0 {
                        let label = number(v);
                        text(&mut img, l - 8 - 8 * label.len() as i32, y - 4, &label, Rgb([0, 0, 0]));
                    }
                }
            }
            d *= 10.0;
        }
    }
    // Thresholds: not noticeable (1) and just noticeable (2.3).
    for (v, label) in [(1.0, "dE00 = 1"), (2.3, "dE00 = 2.3")] {
        let (_, y) = map((x0, v));
        line(&mut img, (l, y), (r, y), Rgb([120, 160, 120]), true);
        text(&mut img, r - 8 * label.len() as i32 - 4, y - 11, label, Rgb([60, 120, 60]));
    }
    frame(&mut img);
    text(&mut img, l, 8, title, Rgb([0, 0, 0]));
    text(&mut img, (l + r) / 2 - 100, b + 30, "time per frame, s (trace + render)", Rgb([0, 0, 0]));
    text(&mut img, 8, t - 16, "mean dE00 (caustic pixels)", Rgb([0, 0, 0]));
    // Curves.
    let mut labels: Vec<&str> = Vec::new();
    for row in rows {
        if !labels.contains(&row.setting.label.as_str()) {
            labels.push(&row.setting.label);
        }
    }
    for (k, label) in labels.iter().enumerate() {
        let colour = Rgb(PALETTE[k % PALETTE.len()]);
        let mut curve: Vec<(i32, i32)> =
            rows.iter().zip(&pts).filter(|(r, _)| r.setting.label == *label).map(|(_, p)| map(*p)).collect();
        curve.sort();
        for w in curve.windows(2) {
            thick_line(&mut img, w[0], w[1], colour);
        }
        for &p in &curve {
            dot(&mut img, p, 4, colour);
        }
        let y = t + 10 + 16 * k as i32;
        thick_line(&mut img, (r + 20, y), (r + 44, y), colour);
        dot(&mut img, (r + 32, y), 4, colour);
        text(&mut img, r + 52, y - 4, label, Rgb([0, 0, 0]));
    }
    // Pareto front: ringed points joined by a dashed staircase.
    let mut front: Vec<(i32, i32)> = rows.iter().zip(&pts).filter(|(r, _)| r.pareto).map(|(_, p)| map(*p)).collect();
    front.sort();
    for w in front.windows(2) {
        line(&mut img, w[0], (w[1].0, w[0].1), Rgb([0, 0, 0]), true);
        line(&mut img, (w[1].0, w[0].1), w[1], Rgb([0, 0, 0]), true);
    }
    for &p in &front {
        ring(&mut img, p, 8, Rgb([0, 0, 0]));
    }
    let y = t + 10 + 16 * labels.len() as i32 + 8;
    ring(&mut img, (r + 32, y), 8, Rgb([0, 0, 0]));
    text(&mut img, r + 52, y - 4, "Pareto front", Rgb([0, 0, 0]));
    img
}

fn bounds(values: impl Iterator<Item = f64>, decade: impl Fn(f64, bool) -> f64) -> (f64, f64) {
    let (lo, hi) = values.fold((f64::INFINITY, 0.0f64), |(lo, hi), v| (lo.min(v), hi.max(v)));
    if !lo.is_finite() {
        return (0.1, 10.0);
    }
    let (lo, hi) = (decade(lo, false), decade(hi, true));
    if hi <= lo { (lo, lo * 10.0) } else { (lo, hi) }
}

fn number(v: f64) -> String {
    if v >= 1.0 { format!("{v:.0}") } else { format!("{v}").chars().take(8).collect() }
}

fn put(img: &mut RgbImage, x: i32, y: i32, c: Rgb<u8>) {
    if x >= 0 && y >= 0 && (x as u32) < img.width() && (y as u32) < img.height() {
        img.put_pixel(x as u32, y as u32, c);
    }
}

fn line(img: &mut RgbImage, a: (i32, i32), b: (i32, i32), c: Rgb<u8>, dashed: bool) {
    let (dx, dy) = ((b.0 - a.0).abs(), -(b.1 - a.1).abs());
    let (sx, sy) = (if a.0 < b.0 { 1 } else { -1 }, if a.1 < b.1 { 1 } else { -1 });
    let (mut x, mut y, mut err, mut n) = (a.0, a.1, dx + dy, 0);
    loop {
        if !dashed || (n / 5) % 2 == 0 {
            put(img, x, y, c);
        }
        n += 1;
        if (x, y) == b {
            break;
        }
        let e2 = 2 * err;
        if e2 >= dy {
            err += dy;
            x += sx;
        }
        if e2 <= dx {
            err += dx;
            y += sy;
        }
    }
}

fn thick_line(img: &mut RgbImage, a: (i32, i32), b: (i32, i32), c: Rgb<u8>) {
    for (ox, oy) in [(0, 0), (1, 0), (0, 1)] {
        line(img, (a.0 + ox, a.1 + oy), (b.0 + ox, b.1 + oy), c, false);
    }
}

fn dot(img: &mut RgbImage, p: (i32, i32), r: i32, c: Rgb<u8>) {
    for y in -r..=r {
        for x in -r..=r {
            if x * x + y * y <= r * r {
                put(img, p.0 + x, p.1 + y, c);
            }
        }
    }
}

fn ring(img: &mut RgbImage, p: (i32, i32), r: i32, c: Rgb<u8>) {
    for y in -r - 1..=r + 1 {
        for x in -r - 1..=r + 1 {
            let d2 = x * x + y * y;
            if d2 <= (r + 1) * (r + 1) && d2 >= (r - 1) * (r - 1) {
                put(img, p.0 + x, p.1 + y, c);
            }
        }
    }
}

fn frame(img: &mut RgbImage) {
    let (l, t, r, b) = AREA;
    let k = Rgb([0, 0, 0]);
    for (a, z) in [((l, t), (r, t)), ((r, t), (r, b)), ((r, b), (l, b)), ((l, b), (l, t))] {
        line(img, a, z, k, false);
    }
}

/// Writes `s` with its top-left corner at (x, y), 8 pixels a character.
fn text(img: &mut RgbImage, x: i32, y: i32, s: &str, c: Rgb<u8>) {
    for (i, ch) in s.chars().enumerate() {
        let glyph = BASIC_LEGACY.get(ch as usize).copied().unwrap_or(BASIC_LEGACY[b'?' as usize]);
        for (row, bits) in glyph.iter().enumerate() {
            for col in 0..8 {
                if bits & (1 << col) != 0 {
                    put(img, x + 8 * i as i32 + col, y + row as i32, c);
                }
            }
        }
    }
}
