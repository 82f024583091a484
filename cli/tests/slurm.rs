//! The Slurm recipe (`scripts/slurm`) end to end, with a stand-in `sbatch`
//! that runs each job at once on this machine (an array job once per
//! index, in reverse order, the way a cluster may finish them): the merged
//! image is the bytes of one `prismatic render` of all the passes.

use std::path::{Path, PathBuf};
use std::process::Command;

/// `sbatch` for the test: records its arguments, runs the script now
/// (`--array=A-B`: once per index, last first) and prints a job id.
const FAKE_SBATCH: &str = r#"#!/usr/bin/env bash
set -euo pipefail
echo "$*" >> "$SBATCH_LOG"
array=""; script=""
for a in "$@"; do
    case $a in
        --array=*) array=${a#--array=} ;;
        --*) ;;
        *) script=$a ;;
    esac
done
if [ -n "$array" ]; then
    for i in $(seq "${array#*-}" -1 "${array%-*}"); do SLURM_ARRAY_TASK_ID=$i bash "$script" > /dev/null; done
else
    bash "$script" > /dev/null
fi
echo $((1000 + $(wc -l < "$SBATCH_LOG")))
"#;

fn scripts() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../scripts/slurm")
}

#[test]
fn an_array_of_pass_ranges_merged_is_one_render_bit_for_bit() {
    let dir = tempfile::tempdir().unwrap();
    let bin = dir.path().join("bin");
    std::fs::create_dir(&bin).unwrap();
    let sbatch = bin.join("sbatch");
    std::fs::write(&sbatch, FAKE_SBATCH).unwrap();
    std::fs::set_permissions(&sbatch, std::os::unix::fs::PermissionsExt::from_mode(0o755)).unwrap();
    let path = format!("{}:{}", bin.display(), std::env::var("PATH").unwrap_or_default());
    let flags = ["--photons", "3000", "--width", "40", "--height", "30", "--backend", "cpu"];

    // 7 passes in ranges of 2: tasks 0..2, 2..4, 4..6 and a short last one, 6..7.
    let o = Command::new(scripts().join("submit.sh"))
        .args(["sphere", "7", "2", "merged.exr"])
        .args(flags)
        .current_dir(dir.path())
        .env("PATH", &path)
        .env("PRISMATIC", env!("CARGO_BIN_EXE_prismatic"))
        .env("PARTS", dir.path().join("parts"))
        .env("SBATCH_LOG", dir.path().join("sbatch.log"))
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("4 tasks of 2 passes"), "{stdout}");
    let log = std::fs::read_to_string(dir.path().join("sbatch.log")).unwrap();
    assert!(log.contains("--array=0-3") && log.contains("--dependency=afterok:1001"), "{log}");
    let mut parts: Vec<String> = std::fs::read_dir(dir.path().join("parts"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    parts.sort();
    assert_eq!(
        parts,
        ["passes-000000-000002", "passes-000002-000004", "passes-000004-000006", "passes-000006-000007"]
            .map(|p| format!("{p}.partial"))
    );

    let one = Command::new(env!("CARGO_BIN_EXE_prismatic"))
        .args(["render", "sphere", "--passes", "7", "-o", "one.exr"])
        .args(flags)
        .current_dir(dir.path())
        .output()
        .unwrap();
    assert!(one.status.success(), "{}", String::from_utf8_lossy(&one.stderr));
    let merged = std::fs::read(dir.path().join("merged.exr")).unwrap();
    let one = std::fs::read(dir.path().join("one.exr")).unwrap();
    assert!(merged == one, "the merged image differs from one render of the 7 passes");
}

#[test]
fn submit_without_its_arguments_says_how_to_call_it() {
    let o = Command::new(scripts().join("submit.sh")).arg("sphere").output().unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("usage:"));
}
