//! `prismatic study --quick` end to end: it writes its CSV, report and plot,
//! error falls as photons and bands grow, light tracing with hero
//! wavelengths beats the fixed-radius gather, the scalar reference backend
//! measures the same error as the CPU backend, and a second run reuses the
//! cached reference.

use std::collections::BTreeMap;
use std::path::Path;
use std::process::Command;

fn prismatic() -> Command {
    Command::new(env!("CARGO_BIN_EXE_prismatic"))
}

/// The CSV as rows of column name → value.
fn read_csv(path: &Path) -> Vec<BTreeMap<String, String>> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    lines.map(|l| header.iter().map(|h| h.to_string()).zip(l.split(',').map(String::from)).collect()).collect()
}

fn delta_e(rows: &[BTreeMap<String, String>], series: &str) -> Vec<(u32, f64)> {
    rows.iter()
        .filter(|r| r["series"] == series)
        .map(|r| (r["photons"].parse().unwrap(), r["delta_e00"].parse().unwrap()))
        .collect()
}

/// Monotone within noise: a later value may exceed an earlier one by 10 %
/// (the quick study's 96-pixel images have a few hundred caustic pixels; the
/// run-to-run spread of their mean ΔE00 is a few per cent).
fn falls(values: &[f64]) -> bool {
    values.windows(2).all(|w| w[1] <= w[0] * 1.10)
}

#[test]
fn quick_study_writes_its_report_and_error_falls_with_photons_and_bands() {
    let dir = tempfile::tempdir().unwrap();
    let (out, cache) = (dir.path().join("out"), dir.path().join("cache"));
    let run = || {
        prismatic().args(["study", "sphere", "--quick", "-o"]).arg(&out).arg("--cache").arg(&cache).output().unwrap()
    };
    let first = run();
    let stderr = String::from_utf8_lossy(&first.stderr);
    assert!(first.status.success(), "study failed: {stderr}");
    for file in ["sphere.csv", "sphere.md", "sphere.svg"] {
        assert!(out.join(file).is_file(), "{file} missing");
    }

    let rows = read_csv(&out.join("sphere.csv"));
    assert!(rows.len() >= 20, "{} rows", rows.len());
    for r in &rows {
        let e: f64 = r["delta_e00"].parse().unwrap();
        let t: f64 = r["total_s"].parse().unwrap();
        assert!(e.is_finite() && e >= 0.0 && t > 0.0, "{r:?}");
    }
    // More photons: less error, on every curve swept over photon counts.
    // Curves that trace one band a photon (random band, continuous) carry
    // 16× fewer band paths than a 16-band split: at these counts their
    // colour noise is where a split reaches at 10k photons (ΔE00 ≈ 5),
    // where ΔE00 saturates and wanders by ±10 %; they must end no worse
    // than they start.
    let mut series: Vec<&str> = rows.iter().map(|r| r["series"].as_str()).collect();
    series.dedup();
    for s in &series {
        let e: Vec<f64> = delta_e(&rows, s).into_iter().map(|(_, e)| e).collect();
        let one_band_a_photon = s.contains("random band") || s.contains("continuous");
        let ok = if one_band_a_photon { falls(&[e[0], e[e.len() - 1]]) } else { falls(&e) };
        assert!(ok, "{s}: ΔE00 {e:?} does not fall as photons grow");
    }
    // More bands: less error, at the largest photon count.
    let at_most_photons = |s: &str| delta_e(&rows, s).last().unwrap().1;
    let physical: Vec<f64> = ["3 bands", "7 bands", "16 bands"].map(at_most_photons).into();
    assert!(falls(&physical), "ΔE00 {physical:?} does not fall from 3 to 7 to 16 bands");
    let paper: Vec<f64> = ["paper3", "paper7"].map(at_most_photons).into();
    assert!(falls(&paper), "ΔE00 {paper:?} does not fall from paper3 to paper7");
    // Light tracing with hero wavelengths (this wave's estimators) ends below
    // every curve that gathers everywhere at a fixed radius: the gather
    // disc's blur stays, the light-traced caustic converges.
    let hero = at_most_photons("LT 16 hero");
    for s in series.iter().filter(|s| !s.starts_with("LT") && !s.contains("progressive")) {
        assert!(hero < at_most_photons(s), "LT 16 hero's ΔE00 {hero} is not below {s}'s {}", at_most_photons(s));
    }
    // The scalar reference backend renders the same image: the same error.
    let (scalar, cpu) = (delta_e(&rows, "paper7 reference backend"), delta_e(&rows, "paper7"));
    assert_eq!(scalar[0], cpu[0]);
    // The Pareto front is non-empty and no point on it is beaten in both time and error.
    let key =
        |r: &BTreeMap<String, String>| (r["total_s"].parse::<f64>().unwrap(), r["delta_e00"].parse::<f64>().unwrap());
    let front: Vec<_> = rows.iter().filter(|r| r["pareto"] == "true").map(key).collect();
    assert!(!front.is_empty());
    for (t, e) in &front {
        assert!(!rows.iter().map(key).any(|(t2, e2)| t2 < *t && e2 < *e), "({t}, {e}) is dominated");
    }
    // The plot names every curve and the Pareto front in its legend.
    let svg = std::fs::read_to_string(out.join("sphere.svg")).unwrap();
    assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"), "not an SVG document");
    for s in series.iter().copied().chain(["Pareto front", "ΔE00 = 1: not noticeable"]) {
        assert!(svg.contains(&format!("\n{s}\n")), "the plot does not show {s:?}");
    }
    let md = std::fs::read_to_string(out.join("sphere.md")).unwrap();
    assert!(md.contains("Table 5"), "{md}");
    assert!(md.contains("Cheapest setting") || md.contains("No setting reached"), "{md}");

    // The second run finds the reference in the cache.
    let second = run();
    assert!(second.status.success());
    assert!(
        String::from_utf8_lossy(&second.stderr).contains("reference: cached"),
        "{}",
        String::from_utf8_lossy(&second.stderr)
    );

    // --series runs only the curves it names; a name no curve has is an error.
    let only = |name: &str, out: &Path| {
        let args = ["study", "sphere", "--quick", "--series", name, "--cache"];
        prismatic().args(args).arg(&cache).arg("-o").arg(out).output().unwrap()
    };
    let hero_out = dir.path().join("hero");
    assert!(only("LT 16 hero (hero", &hero_out).status.success());
    let hero_rows = read_csv(&hero_out.join("sphere.csv"));
    assert_eq!(hero_rows.len(), 3);
    assert!(
        hero_rows.iter().all(|r| r["series"] == "LT 16 hero (hero view)"
            && r["wavelengths"] == "hero"
            && r["view_paths"] == "hero")
    );
    let none_out = dir.path().join("none");
    let none = only("no such curve", &none_out);
    assert!(!none.status.success());
    assert!(String::from_utf8_lossy(&none.stderr).contains("--series no such curve"));
    assert!(!none_out.exists(), "nothing written");
}

#[test]
fn study_of_an_unknown_scene_is_a_clear_error() {
    let dir = tempfile::tempdir().unwrap();
    let out = prismatic().args(["study", "nosuchscene", "--quick", "-o"]).arg(dir.path()).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("nosuchscene") && stderr.contains("built-in scenes are"), "{stderr}");
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0, "nothing written");
}
