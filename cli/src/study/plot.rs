//! The study's plot: error (mean ΔE00) against time, log–log, one curve per
//! series in its own colour and marker, the Pareto front ringed and joined,
//! ΔE00 = 1 and 2.3 marked; drawn with `plotters` as SVG (text stays text,
//! so it needs no font files and stays sharp at any size).

use super::StudyRow;
use plotters::coord::Shift;
use plotters::element::DynElement;
use plotters::prelude::*;

/// The plot's size in SVG pixels.
pub const SIZE: (u32, u32) = (1100, 660);

/// Width of the legend column right of the chart.
const LEGEND_WIDTH: u32 = 280;

/// Twenty colours no two of which are easily confused (Tableau 20, dark
/// shades first), so that curves next to each other stay apart.
const PALETTE: [RGBColor; 20] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
    RGBColor(174, 199, 232),
    RGBColor(255, 187, 120),
    RGBColor(152, 223, 138),
    RGBColor(255, 152, 150),
    RGBColor(197, 176, 213),
    RGBColor(196, 156, 148),
    RGBColor(247, 182, 210),
    RGBColor(199, 199, 199),
    RGBColor(219, 219, 141),
    RGBColor(158, 218, 229),
];

/// Marker shapes, cycled with a different period than the colours.
const MARKERS: usize = 6;

/// Draws the plot of `rows` (titled `title`) as an SVG document.
pub fn draw(rows: &[StudyRow], title: &str) -> Result<String, String> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        draw_on(&root, rows, title).map_err(|e| format!("cannot draw the plot: {e}"))?;
        root.present().map_err(|e| format!("cannot draw the plot: {e}"))?;
    }
    Ok(svg)
}

fn draw_on(
    root: &DrawingArea<SVGBackend<'_>, Shift>,
    rows: &[StudyRow],
    title: &str,
) -> Result<(), Box<dyn std::error::Error>> {
    root.fill(&WHITE)?;
    let (plot_area, legend_area) = root.split_horizontally(SIZE.0 - LEGEND_WIDTH);
    let point = |r: &StudyRow| (r.total_s().max(1e-4), r.error.delta_e.max(1e-3));
    let (x0, x1) = decades(rows.iter().map(|r| point(r).0));
    let (y0, y1) = decades(rows.iter().map(|r| point(r).1).chain([1.0, 2.3]));
    let mut chart = ChartBuilder::on(&plot_area)
        .caption(title, ("sans-serif", 20))
        .margin(14)
        .x_label_area_size(50)
        .y_label_area_size(64)
        .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())?;
    chart
        .configure_mesh()
        .x_desc("time per frame, s (trace + render)")
        .y_desc("mean ΔE00 over the caustic's pixels")
        .x_labels(12)
        .y_labels(12)
        .x_label_formatter(&|v| number(*v))
        .y_label_formatter(&|v| number(*v))
        .light_line_style(RGBColor(235, 235, 235))
        .draw()?;

    let threshold = RGBColor(60, 130, 60);
    for (v, label) in [(1.0, "ΔE00 = 1: not noticeable"), (2.3, "ΔE00 = 2.3: just noticeable")] {
        chart.draw_series(DashedLineSeries::new([(x0, v), (x1, v)], 8, 5, threshold.stroke_width(1)))?;
        chart.draw_series(std::iter::once(Text::new(
            label,
            (x0 * 1.15, v * 1.04),
            ("sans-serif", 13).into_font().color(&threshold),
        )))?;
    }

    let mut labels: Vec<&str> = Vec::new();
    for row in rows {
        if !labels.contains(&row.setting.label.as_str()) {
            labels.push(&row.setting.label);
        }
    }
    for (k, label) in labels.iter().enumerate() {
        let colour = PALETTE[k % PALETTE.len()];
        let mut curve: Vec<(f64, f64)> = rows.iter().filter(|r| r.setting.label == *label).map(point).collect();
        curve.sort_by(|a, b| a.0.total_cmp(&b.0));
        chart.draw_series(LineSeries::new(curve.iter().copied(), colour.stroke_width(2)))?;
        // Markers in pixels (a boxed element cannot go through draw_series).
        for p in &curve {
            root.draw(&marker(k, chart.backend_coord(p), colour))?;
        }
    }

    // The Pareto front: ringed points joined by a dashed staircase.
    let mut front: Vec<(f64, f64)> = rows.iter().filter(|r| r.pareto).map(point).collect();
    front.sort_by(|a, b| a.0.total_cmp(&b.0));
    let stairs: Vec<(f64, f64)> =
        front.windows(2).flat_map(|w| [w[0], (w[1].0, w[0].1)]).chain(front.last().copied()).collect();
    chart.draw_series(DashedLineSeries::new(stairs, 5, 4, BLACK.stroke_width(1)))?;
    chart.draw_series(front.iter().map(|&p| Circle::new(p, 8, BLACK.stroke_width(1))))?;

    // The legend, in its own column: marker, line and name of every curve.
    let legend = legend_area.margin(60, 10, 4, 10);
    let font = ("sans-serif", 14).into_font();
    let row_y = |i: usize| 8 + 21 * i as i32;
    for (k, label) in labels.iter().enumerate() {
        let (colour, y) = (PALETTE[k % PALETTE.len()], row_y(k));
        legend.draw(&PathElement::new([(0, y), (28, y)], colour.stroke_width(2)))?;
        legend.draw(&marker(k, (14, y), colour))?;
        legend.draw(&Text::new(label.to_string(), (38, y - 7), font.clone()))?;
    }
    let y = row_y(labels.len()) + 6;
    legend.draw(&Circle::new((14, y), 8, BLACK.stroke_width(1)))?;
    legend.draw(&Text::new("Pareto front", (38, y - 7), font))?;
    Ok(())
}

/// Marker `k` (shape by k, filled for the first round of shapes, hollow
/// after) at `at`.
fn marker<'a, DB: DrawingBackend + 'a, C: Clone + 'a>(k: usize, at: C, colour: RGBColor) -> DynElement<'a, DB, C> {
    let style = if (k / MARKERS).is_multiple_of(2) { colour.filled() } else { colour.stroke_width(2) };
    let here = EmptyElement::at(at);
    match k % MARKERS {
        0 => (here + Circle::new((0, 0), 4, style)).into_dyn(),
        1 => (here + Rectangle::new([(-4, -4), (4, 4)], style)).into_dyn(),
        2 => (here + TriangleMarker::new((0, 0), 5, style)).into_dyn(),
        3 => (here + Polygon::new(vec![(0, -5), (5, 0), (0, 5), (-5, 0)], style)).into_dyn(),
        4 => (here + Cross::new((0, 0), 4, colour.stroke_width(2))).into_dyn(),
        _ => (here + Polygon::new(vec![(0, 5), (5, -4), (-5, -4)], style)).into_dyn(),
    }
}

/// The decades around `values` (at least one decade).
fn decades(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values.fold((f64::INFINITY, 0.0f64), |(lo, hi), v| (lo.min(v), hi.max(v)));
    if !lo.is_finite() {
        return (0.1, 10.0);
    }
    let (lo, hi) = (10f64.powf(lo.log10().floor()), 10f64.powf(hi.log10().ceil()));
    if hi <= lo { (lo, lo * 10.0) } else { (lo, hi) }
}

/// A tick label: "0.01", "0.5", "3", "20".
fn number(v: f64) -> String {
    let s = format!("{v:.4}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

#[cfg(test)]
mod tests {
    use super::number;

    #[test]
    fn tick_labels_are_short() {
        assert_eq!(number(0.01), "0.01");
        assert_eq!(number(0.5), "0.5");
        assert_eq!(number(3.0), "3");
        assert_eq!(number(20.0), "20");
    }
}
