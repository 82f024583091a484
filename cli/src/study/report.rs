//! The study's outputs: the Pareto front, a CSV of every point, a Markdown
//! report (tables, the cheapest settings under the ΔE00 thresholds, the
//! paper's Table 5) and the plot, written into one folder.

use super::{RadiusPlan, StudyResult, StudyRow, plot};
use crate::output::PendingFile;
use anyhow::Result;
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::{Path, PathBuf};

/// Marks the rows no other row beats in both time and ΔE00.
pub fn mark_pareto(rows: &mut [StudyRow]) {
    let key: Vec<(f64, f64)> = rows.iter().map(|r| (r.total_s(), r.error.delta_e)).collect();
    for (i, row) in rows.iter_mut().enumerate() {
        let (t, e) = key[i];
        row.pareto = !key.iter().any(|&(t2, e2)| t2 <= t && e2 <= e && (t2 < t || e2 < e));
    }
}

/// The fastest row whose ΔE00 is below `threshold`.
pub fn cheapest_below(rows: &[StudyRow], threshold: f64) -> Option<&StudyRow> {
    rows.iter().filter(|r| r.error.delta_e < threshold).min_by(|a, b| a.total_s().total_cmp(&b.total_s()))
}

/// The files a study wrote.
pub struct Written {
    /// CSV of every point.
    pub csv: PathBuf,
    /// The Markdown report.
    pub markdown: PathBuf,
    /// The plot.
    pub plot: PathBuf,
}

/// Writes `study.csv`, `study.md` and `study.svg` into `dir` (each file
/// atomically).
pub fn write_all(result: &StudyResult, dir: &Path, machine: &str) -> Result<Written> {
    std::fs::create_dir_all(dir)?;
    let stem = super::converged::sanitize(&result.scene);
    let w = Written {
        csv: dir.join(format!("{stem}.csv")),
        markdown: dir.join(format!("{stem}.md")),
        plot: dir.join(format!("{stem}.svg")),
    };
    let csv = csv(result);
    PendingFile::create(&w.csv)?.commit(|f| Ok(f.write_all(csv.as_bytes())?))?;
    let md = markdown(result, machine, &w.plot);
    PendingFile::create(&w.markdown)?.commit(|f| Ok(f.write_all(md.as_bytes())?))?;
    let title = format!("prismatic study {}: error against time ({machine})", result.scene);
    let svg = plot::draw(&result.rows, &title).map_err(anyhow::Error::msg)?;
    PendingFile::create(&w.plot)?.commit(|f| Ok(f.write_all(svg.as_bytes())?))?;
    Ok(w)
}

fn radius(r: RadiusPlan) -> String {
    match r {
        RadiusPlan::Fixed => "fixed".into(),
        RadiusPlan::Progressive { passes } => format!("progressive/{passes}"),
    }
}

/// Every point, one per line.
pub fn csv(result: &StudyResult) -> String {
    let mut s = String::from(
        "scene,series,bands,wavelengths,estimator,light_tracing,photon_sequence,view_paths,radius,backend,photons,\
         stored,trace_s,total_s,delta_e00,rmse_linear,stripe_error,pareto\n",
    );
    for r in &result.rows {
        let st = &r.setting;
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{},{},{},{},{},{},{:.6},{:.4},{:.6},{},{}",
            result.scene,
            r.setting.label,
            st.bands,
            st.sampling.name(),
            st.estimator.name(),
            st.light_tracing,
            st.sequence.name(),
            st.view_paths.name(),
            radius(st.radius),
            format!("{:?}", st.backend).to_lowercase(),
            r.photons,
            r.stored,
            r.trace_s.map_or(String::new(), |t| format!("{t:.6}")),
            r.total_s(),
            r.error.delta_e,
            r.error.rmse,
            r.error.stripe.map_or(String::new(), |v| format!("{v:.6}")),
            r.pareto
        );
    }
    s
}

fn seconds(s: f64) -> String {
    if s < 0.1 { format!("{:.1} ms", s * 1e3) } else { format!("{s:.2} s") }
}

fn photons(n: u32) -> String {
    if n >= 1_000_000 && n.is_multiple_of(1_000_000) {
        format!("{}M", n / 1_000_000)
    } else if n >= 1000 && n.is_multiple_of(1000) {
        format!("{}k", n / 1000)
    } else {
        n.to_string()
    }
}

/// The Markdown report.
pub fn markdown(result: &StudyResult, machine: &str, plot: &Path) -> String {
    let mut s = String::new();
    let plan = &result.plan;
    let rf = &result.reference;
    let _ = writeln!(s, "### `{}`\n", result.scene);
    let _ = writeln!(
        s,
        "{}×{} pixels, {machine}. Reference: {} physically based bands, {} wavelengths, {}the renderer's \
         progressive photon mapping (`density`, α = {}, first radii holding {} photon paths), {} photons, {} passes \
         × {} photons; the last doubling of passes changed it by ΔE00 {:.2} (threshold {}{}); {} caustic pixels \
         (those the reference caustic changes by ΔE00 > {}).\n",
        plan.size.0,
        plan.size.1,
        plan.reference.bands,
        plan.reference.wavelengths.name(),
        if plan.reference.light_tracing {
            "light tracing where the camera sees the caustic directly and elsewhere "
        } else {
            ""
        },
        plan.reference.alpha,
        plan.reference.neighbours,
        plan.reference.sequence.name(),
        rf.passes,
        photons(plan.reference.photons_per_pass),
        rf.last_change,
        plan.reference.threshold,
        if rf.converged { "" } else { ", not reached: more passes would help" },
        rf.caustic_pixels,
        super::metrics::CAUSTIC_MASK_DELTA_E
    );
    let _ = writeln!(
        s,
        "![error against time]({})\n",
        plot.file_name().map_or(String::new(), |f| f.to_string_lossy().into())
    );
    for (threshold, what) in [(1.0, "not noticeable"), (2.3, "just noticeable")] {
        match cheapest_below(&result.rows, threshold) {
            Some(r) => {
                let _ = writeln!(
                    s,
                    "- Cheapest setting with ΔE00 < {threshold} ({what}): **{}, {} photons**, {} per frame (ΔE00 {:.2}).",
                    r.setting.label,
                    photons(r.photons),
                    seconds(r.total_s()),
                    r.error.delta_e
                );
            }
            None => {
                let _ = writeln!(s, "- No setting reached ΔE00 < {threshold} ({what}).");
            }
        }
    }
    let stripes = result.rows.iter().any(|r| r.error.stripe.is_some());
    let _ = writeln!(
        s,
        "\n| series | photons | photon trace | total | ΔE00 | RMSE (linear) |{} Pareto |",
        if stripes { " stripe error |" } else { "" }
    );
    let _ = writeln!(s, "|---|---:|---:|---:|---:|---:|{}---|", if stripes { "---:|" } else { "" });
    for r in &result.rows {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {:.2} | {:.4} |{} {} |",
            r.setting.label,
            photons(r.photons),
            r.trace_s.map_or("–".into(), seconds),
            seconds(r.total_s()),
            r.error.delta_e,
            r.error.rmse,
            match (stripes, r.error.stripe) {
                (false, _) => String::new(),
                (true, Some(v)) => format!(" {v:.4} |"),
                (true, None) => " – |".into(),
            },
            if r.pareto { "●" } else { "" }
        );
    }
    if !result.skipped.is_empty() {
        let _ = writeln!(s, "\nSkipped (memory): {}.", result.skipped.join("; "));
    }
    let _ = writeln!(
        s,
        "\nThe paper's Table 5 (GTX 260, 400×400, 20k photons) next to this machine (cpu backend, best of 3):\n"
    );
    let _ = writeln!(s, "| method | paper FPS | here | here FPS | ΔE00 |");
    let _ = writeln!(s, "|---|---:|---:|---:|---:|");
    for t in &result.table5 {
        let _ = writeln!(
            s,
            "| {} | {:.1} | {} | {:.0} | {:.2} |",
            t.method,
            t.paper_fps,
            seconds(t.seconds),
            1.0 / t.seconds,
            t.delta_e
        );
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::study::metrics::RenderError;

    fn row(t: f64, e: f64) -> StudyRow {
        let setting = crate::study::series(
            "x",
            prismatic_core::BandSpec::Paper7,
            prismatic_core::WavelengthSampling::Split,
            prismatic_core::Estimator::Paper,
        );
        StudyRow {
            setting,
            photons: 1,
            stored: 0,
            seconds: t,
            trace_s: None,
            error: RenderError { delta_e: e, rmse: 0.0, stripe: None },
            pareto: false,
        }
    }

    #[test]
    fn the_pareto_front_keeps_exactly_the_undominated_points() {
        let mut rows = vec![row(1.0, 5.0), row(2.0, 3.0), row(2.0, 4.0), row(3.0, 3.0), row(4.0, 1.0), row(0.5, 9.0)];
        mark_pareto(&mut rows);
        let front: Vec<bool> = rows.iter().map(|r| r.pareto).collect();
        assert_eq!(front, [true, true, false, false, true, true]);
        assert_eq!(cheapest_below(&rows, 3.5).map(|r| r.seconds), Some(2.0));
        assert!(cheapest_below(&rows, 0.5).is_none());
    }
}
