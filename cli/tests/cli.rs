//! The `prismatic` binary end to end: what a user types, what they get back.

use std::path::Path;
use std::process::{Command, Output};

fn prismatic(args: &[&str], dir: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_prismatic")).args(args).current_dir(dir).output().expect("the binary runs")
}

fn text(o: &Output) -> (String, String) {
    (String::from_utf8_lossy(&o.stdout).into_owned(), String::from_utf8_lossy(&o.stderr).into_owned())
}

/// Files in `dir` (to check that nothing, not even a temporary file, was left).
fn files_in(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> =
        std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    v.sort();
    v
}

const SMALL: [&str; 6] = ["--photons", "3000", "--width", "48", "--height", "36"];

#[test]
fn render_writes_a_png_and_reports_what_it_did() {
    let dir = tempfile::tempdir().unwrap();
    let mut args = vec!["render", "sphere", "-o", "out.png"];
    args.extend(SMALL);
    let o = prismatic(&args, dir.path());
    let (out, err) = text(&o);
    assert!(o.status.success(), "{err}");
    // 16 progressive passes (the scene's) of 3000 photons each.
    assert!(out.contains("cpu backend") && out.contains("16 passes (0..16)"), "{out}");
    assert!(out.contains("48000 photons emitted") && out.contains("stored"), "{out}");
    let img = image::open(dir.path().join("out.png")).expect("a readable PNG").to_rgb8();
    assert_eq!(img.dimensions(), (48, 36));
    assert!(img.pixels().any(|p| p.0 != [0, 0, 0]), "not a black image");
    assert_eq!(files_in(dir.path()), vec!["out.png"]);
}

#[test]
fn render_defaults_to_the_spectrum_scene_and_prismatic_png() {
    let o = Command::new(env!("CARGO_BIN_EXE_prismatic")).args(["render", "--help"]).output().unwrap();
    let (out, _) = text(&o);
    assert!(out.contains("[default: spectrum]") && out.contains("[default: prismatic.png]"), "{out}");
}

/// Hue in degrees (0 red, 60 yellow, 120 green, 240 blue, 270 violet) and
/// saturation of an 8-bit sRGB pixel.
fn hue_and_saturation(rgb: [u8; 3]) -> (f32, f32) {
    let [r, g, b] = rgb.map(|c| f32::from(c) / 255.0);
    let (max, min) = (r.max(g).max(b), r.min(g).min(b));
    let chroma = max - min;
    if chroma <= 0.0 {
        return (0.0, 0.0);
    }
    let sextant = if max == r {
        ((g - b) / chroma).rem_euclid(6.0)
    } else if max == g {
        (b - r) / chroma + 2.0
    } else {
        (r - g) / chroma + 4.0
    };
    (60.0 * sextant, chroma / max)
}

/// The first image a user sees shows the whole spectrum at a glance:
/// saturated pixels of every hue from red through yellow, green and blue to
/// violet (the previous first image, `caustic`, had no green).
#[test]
fn the_default_render_shows_red_through_violet() {
    let dir = tempfile::tempdir().unwrap();
    let hue_counts = |scene: Option<&str>| {
        let mut args = vec!["render", "--passes", "4", "-o", "out.png"];
        args.extend(scene);
        let o = prismatic(&args, dir.path());
        assert!(o.status.success(), "{}", text(&o).1);
        let img = image::open(dir.path().join("out.png")).unwrap().to_rgb8();
        let hues: Vec<f32> = img
            .pixels()
            .map(|p| hue_and_saturation(p.0))
            .filter(|&(_, saturation)| saturation > 0.6)
            .map(|(h, _)| h)
            .collect();
        [
            ("red", 345.0, 375.0),
            ("yellow", 45.0, 70.0),
            ("green", 90.0, 150.0),
            ("blue", 200.0, 245.0),
            ("violet", 245.0, 290.0),
        ]
        .map(|(colour, lo, hi)| {
            (colour, hues.iter().filter(|&&h| (lo..hi).contains(&h) || (lo..hi).contains(&(h + 360.0))).count())
        })
    };
    for (colour, count) in hue_counts(None) {
        assert!(count >= 20, "only {count} saturated {colour} pixels in the default render");
    }
    let caustic = hue_counts(Some("caustic"));
    assert!(caustic.iter().any(|&(_, count)| count < 20), "the old first image had every hue too: {caustic:?}");
}

#[test]
fn photons_writes_the_caustic_map_as_csv_in_canonical_order() {
    let dir = tempfile::tempdir().unwrap();
    let o = prismatic(&["photons", "prism", "--photons", "300", "-o", "p.csv"], dir.path());
    assert!(o.status.success(), "{}", text(&o).1);
    let csv = std::fs::read_to_string(dir.path().join("p.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(lines.next(), Some("emission,band,lambda_nm,x,y,z,dir_x,dir_y,dir_z,power"));
    let keys: Vec<(u32, i32)> = lines
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            assert_eq!(f.len(), 10, "{l}");
            assert!(f[3..].iter().all(|x| x.parse::<f32>().unwrap().is_finite()), "{l}");
            (f[0].parse().unwrap(), f[1].parse().unwrap())
        })
        .collect();
    assert!(keys.len() > 300, "the prism splits most photons into 24 bands: {}", keys.len());
    assert!(keys.windows(2).all(|w| w[0] < w[1]), "canonical (emission, band) order");
}

#[test]
fn scenes_lists_the_built_ins_and_scene_prints_one() {
    let dir = tempfile::tempdir().unwrap();
    let (out, _) = text(&prismatic(&["scenes"], dir.path()));
    for name in ["sphere", "prism", "recombine", "rainbow"] {
        assert!(out.lines().any(|l| l.starts_with(name)), "{name} missing from {out}");
    }
    let (toml, _) = text(&prismatic(&["scene", "rainbow"], dir.path()));
    assert!(toml.contains("ior = \"water\""));
    // The printed scene is a working template.
    std::fs::write(dir.path().join("mine.toml"), toml).unwrap();
    let o = prismatic(&["photons", "mine.toml", "--photons", "100", "-o", "m.csv"], dir.path());
    assert!(o.status.success(), "{}", text(&o).1);
}

#[test]
fn a_bad_scene_file_exits_2_with_file_line_key_and_reason_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let (scene, _) = text(&prismatic(&["scene", "sphere"], dir.path()));
    let bad = scene.replace("radius = 1.0", "radius = -1.0");
    std::fs::write(dir.path().join("bad.toml"), &bad).unwrap();
    let line = bad.lines().position(|l| l == "radius = -1.0").unwrap() + 1;
    let o = prismatic(&["render", "bad.toml", "-o", "bad.png"], dir.path());
    let (_, err) = text(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains(&format!("bad.toml:{line}: object[1].radius: must be greater than 0")), "{err}");
    assert_eq!(files_in(dir.path()), vec!["bad.toml"], "no output file, not even a temporary one");
}

#[test]
fn unknown_scenes_and_bad_flags_exit_2() {
    let dir = tempfile::tempdir().unwrap();
    let o = prismatic(&["render", "teapot"], dir.path());
    assert_eq!(o.status.code(), Some(2));
    assert!(text(&o).1.contains(
        "built-in scenes are: spectrum, caustic, sphere, softbox, room, prism, lamps, recombine, rainbow, coated, frosted, dispersion-test, sunlit-glass, ring, pool"
    ));
    let o = prismatic(&["render", "sphere", "--bands", "0"], dir.path());
    assert_eq!(o.status.code(), Some(2));
    assert!(text(&o).1.contains("--bands: must be"), "{}", text(&o).1);
    let o = prismatic(&["render", "sphere", "--estimator", "guess"], dir.path());
    assert_eq!(o.status.code(), Some(2));
    assert!(files_in(dir.path()).is_empty());
}

#[test]
fn an_unwritable_output_fails_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    let o = prismatic(&["render", "rainbow", "-o", "no/such/dir/x.png"], dir.path());
    let (out, err) = text(&o);
    assert!(!o.status.success());
    assert!(err.contains("no/such/dir/x.png") && err.contains("cannot write"), "{err}");
    assert!(!out.contains("photons emitted"), "it must not have traced: {out}");
}

/// The binary with wgpu limited to OpenGL, which the gpu backend does not
/// use: a machine without any Vulkan, Metal or DX12 adapter.
fn prismatic_without_gpu(args: &[&str], dir: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_prismatic"))
        .args(args)
        .env("WGPU_BACKEND", "gl")
        .current_dir(dir)
        .output()
        .expect("the binary runs")
}

#[test]
fn without_an_adapter_gpu_fails_naming_the_cpu_backend_and_auto_picks_the_cpu() {
    let dir = tempfile::tempdir().unwrap();
    let o = prismatic_without_gpu(&["render", "sphere", "--backend", "gpu", "-o", "x.png"], dir.path());
    let (_, err) = text(&o);
    assert!(!o.status.success());
    assert!(err.contains("no GPU adapter found") && err.contains("--backend cpu"), "{err}");
    let mut args = vec!["render", "prism", "--backend", "auto", "-o", "a.png"];
    args.extend(SMALL);
    let o = prismatic_without_gpu(&args, dir.path());
    assert!(o.status.success());
    assert!(text(&o).1.contains("auto picked the cpu backend"), "{}", text(&o).1);
    assert!(text(&o).0.contains("cpu backend"));
    assert_eq!(files_in(dir.path()), vec!["a.png"]);
}

#[test]
fn gpu_backend_renders_and_names_its_adapter() {
    let dir = tempfile::tempdir().unwrap();
    let mut args = vec!["render", "prism", "--backend", "gpu", "-o", "g.png"];
    args.extend(SMALL);
    let o = prismatic(&args, dir.path());
    let (out, err) = text(&o);
    if !o.status.success() && err.contains("no GPU adapter") && std::env::var_os("CI").is_none() {
        eprintln!("SKIPPING: no GPU adapter on this machine: {err}");
        return;
    }
    assert!(o.status.success(), "{err}");
    assert!(err.contains("gpu backend on "), "{err}");
    assert!(out.contains("gpu backend"), "{out}");
    assert_eq!(files_in(dir.path()), vec!["g.png"]);
}

#[test]
fn the_reference_and_cpu_backends_write_the_same_photon_map() {
    let dir = tempfile::tempdir().unwrap();
    for backend in ["reference", "cpu"] {
        let o = prismatic(
            &["photons", "sphere", "--photons", "2000", "--backend", backend, "-o", &format!("{backend}.csv")],
            dir.path(),
        );
        assert!(o.status.success(), "{}", text(&o).1);
    }
    let read = |name: &str| std::fs::read_to_string(dir.path().join(name)).unwrap();
    assert_eq!(read("reference.csv"), read("cpu.csv"));
}

#[test]
fn bad_flag_values_are_reported_against_the_flag() {
    let dir = tempfile::tempdir().unwrap();
    let o = prismatic(&["render", "sphere", "--radius", "0", "-o", "x.png"], dir.path());
    let (_, err) = text(&o);
    assert_eq!(o.status.code(), Some(2));
    assert!(err.contains("command line: --radius: must be greater than 0"), "{err}");
    assert!(files_in(dir.path()).is_empty());
}

/// Partial renders of passes 0..4 and 4..8, merged, are the bytes of one
/// render of 8 passes, PNG and EXR: on the CPU and on the GPU (whose sums
/// are fixed point on the device too).
#[test]
fn partial_renders_merge_into_the_image_of_one_run_bit_for_bit() {
    for backend in ["cpu", "gpu"] {
        let dir = tempfile::tempdir().unwrap();
        let run = |extra: &[&str]| {
            let mut args = vec!["render", "sphere", "--backend", backend];
            args.extend(SMALL);
            args.extend(extra);
            let o = prismatic(&args, dir.path());
            o.status.success().then(|| text(&o).0).ok_or_else(|| text(&o).1)
        };
        let out = match run(&["--passes", "8", "-o", "whole.png"]) {
            Err(err) if backend == "gpu" && err.contains("no GPU adapter") && std::env::var_os("CI").is_none() => {
                eprintln!("SKIPPING the gpu backend: no GPU adapter on this machine: {err}");
                continue;
            }
            out => out.unwrap_or_else(|err| panic!("{backend}: {err}")),
        };
        assert!(out.contains("8 passes (0..8)"), "{backend}: {out}");
        for extra in [
            &["--passes", "8", "-o", "whole.exr"][..],
            &["--passes", "0..4", "--partial", "a.partial"],
            &["--passes", "4..8", "--partial", "b.partial"],
        ] {
            run(extra).unwrap_or_else(|err| panic!("{backend}: {err}"));
        }
        for (merged, whole) in [("merged.png", "whole.png"), ("merged.exr", "whole.exr")] {
            let o = prismatic(&["merge", "b.partial", "a.partial", "-o", merged], dir.path());
            let (out, err) = text(&o);
            assert!(o.status.success(), "{backend}: {err}");
            assert!(out.contains("8 passes: 0..8"), "{backend}: {out}");
            let read = |f: &str| std::fs::read(dir.path().join(f)).unwrap();
            assert!(read(merged) == read(whole), "{backend}: {merged} differs from {whole}");
        }
        // The EXR is linear float RGB of the image's size.
        let exr = image::open(dir.path().join("whole.exr")).expect("a readable EXR").to_rgb32f();
        assert_eq!(exr.dimensions(), (48, 36));
        assert!(exr.pixels().any(|p| p.0[0] > 1.0), "{backend}: the caustic is brighter than white in linear RGB");
    }
}

/// Partials of different backends are refused: the backends agree within
/// the parity tolerances, not bit for bit.
#[test]
fn partials_of_different_backends_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    for (backend, passes, file) in [("reference", "0..1", "r.partial"), ("cpu", "1..2", "c.partial")] {
        let mut args = vec!["render", "prism", "--backend", backend, "--passes", passes, "--partial", file];
        args.extend(SMALL);
        let o = prismatic(&args, dir.path());
        assert!(o.status.success(), "{}", text(&o).1);
    }
    let o = prismatic(&["merge", "r.partial", "c.partial", "-o", "m.png"], dir.path());
    assert_eq!(o.status.code(), Some(2));
    assert!(
        text(&o).1.contains("c.partial: rendered by the cpu backend, the first partial by reference"),
        "{}",
        text(&o).1
    );
    assert!(!dir.path().join("m.png").exists());
}

/// `--time` without `--passes` renders until the time is up (not the
/// scene's pass count).
#[test]
fn a_time_budget_alone_runs_passes_until_it_is_spent() {
    let dir = tempfile::tempdir().unwrap();
    let mut args = vec!["render", "prism", "--time", "1", "-o", "t.png"];
    args.extend(SMALL);
    let o = prismatic(&args, dir.path());
    let (out, err) = text(&o);
    assert!(o.status.success(), "{err}");
    let passes: u32 = out.split(" passes (").next().and_then(|s| s.rsplit(' ').next()).unwrap().parse().unwrap();
    // The prism's 16 passes of 3000 photons take well under a second.
    assert!(passes > 16, "{passes} passes in a second: {out}");
}

#[test]
fn a_time_budget_stops_after_the_pass_that_crosses_it() {
    let dir = tempfile::tempdir().unwrap();
    let mut args = vec!["render", "sphere", "--passes", "100000", "--time", "0.2", "-o", "t.png"];
    args.extend(SMALL);
    let o = prismatic(&args, dir.path());
    let (out, err) = text(&o);
    assert!(o.status.success(), "{err}");
    let passes: u32 = out.split(" passes (").next().and_then(|s| s.rsplit(' ').next()).unwrap().parse().unwrap();
    assert!((1..100_000).contains(&passes), "{out}");
    assert_eq!(files_in(dir.path()), vec!["t.png"]);
}

#[test]
fn bad_passes_time_and_partial_files_exit_2_and_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    for bad in [["--passes", "0"], ["--passes", "5..2"], ["--passes", "x"], ["--time", "soon"], ["--save-every", "0"]] {
        let o = prismatic(&["render", "sphere", bad[0], bad[1], "-o", "x.png"], dir.path());
        assert_eq!(o.status.code(), Some(2), "{bad:?}: {}", text(&o).1);
        assert!(text(&o).1.contains(bad[0]), "{bad:?}: {}", text(&o).1);
    }
    assert!(files_in(dir.path()).is_empty());
    let partial = |scene: &str, size: &str, file: &str| {
        let args = ["render", scene, "--photons", "500", "--width", size, "--height", size, "--passes", "1"];
        let o = prismatic(&[&args[..], &["--partial", file]].concat(), dir.path());
        assert!(o.status.success(), "{}", text(&o).1);
    };
    partial("prism", "24", "prism.partial");
    partial("sphere", "24", "sphere.partial");
    partial("prism", "20", "small.partial");
    let bytes = std::fs::read(dir.path().join("prism.partial")).unwrap();
    std::fs::write(dir.path().join("cut.partial"), &bytes[..bytes.len() / 2]).unwrap();
    std::fs::write(dir.path().join("text.partial"), "hello").unwrap();
    let before = files_in(dir.path());
    for (files, reason) in [
        (["prism.partial", "sphere.partial"], "sphere.partial: rendered from a different scene"),
        (["prism.partial", "small.partial"], "small.partial: a 20x20 image; the first partial is 24x24"),
        (["prism.partial", "cut.partial"], "cut.partial: "),
        (["text.partial", "prism.partial"], "text.partial: not a prismatic partial render"),
        (["prism.partial", "prism.partial"], "prism.partial: pass 0 is in both"),
    ] {
        let o = prismatic(&["merge", files[0], files[1], "-o", "m.png"], dir.path());
        let err = text(&o).1;
        assert_eq!(o.status.code(), Some(2), "{files:?}: {err}");
        assert!(err.contains(reason), "{files:?}: {err}");
    }
    let o = prismatic(&["merge", "cut.partial", "-o", "m.png"], dir.path());
    assert!(text(&o).1.contains("truncated"), "{}", text(&o).1);
    assert_eq!(files_in(dir.path()), before, "nothing written");
}
