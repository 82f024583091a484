//! A short fuzzing run of the scene-file reader in every `cargo test`: the
//! body of the cargo-fuzz target (`fuzz/fuzz_targets/scene_file.rs`,
//! `prismatic_cli::scene_file::check_source`) on arbitrary text, on the
//! built-in scenes with hostile values spliced in, and on truncated and
//! shuffled scene files. Any outcome but a panic is fine.

use prismatic_cli::builtin::BUILTIN_SCENES;
use prismatic_cli::scene_file::check_source;
use proptest::prelude::*;
use proptest::test_runner::RngSeed;

/// Values that have broken parsers and validators elsewhere.
const HOSTILE: &[&str] = &[
    "nan",
    "inf",
    "-inf",
    "0",
    "-0.0",
    "-1",
    "1e39",
    "-1e39",
    "1e-45",
    "4294967296",
    "18446744073709551616",
    "9223372036854775807",
    "\"\"",
    "\"x\"",
    "[]",
    "[1, 2]",
    "[nan, nan, nan]",
    "[0, 0, 0]",
    "[1e38, 1e38, 1e38]",
    "{}",
    "true",
    "2026-11-21",
    "[[1, 2, 3]]",
    "\"paper\"",
    "\"unobtainium\"",
    "{ bands = [] }",
    "{ cauchy = [1e30, 1e30] }",
    "{ sellmeier = { b = [1], c = [0.3] } }",
    "{ abbe = [1.5, 0] }",
    "257",
    "0x7fffffff",
];

/// A built-in scene with `edits` applied: (line, what to do, hostile value).
fn mutated(scene: usize, edits: &[(usize, u8, usize)]) -> String {
    let mut lines: Vec<String> = BUILTIN_SCENES[scene].source.lines().map(str::to_string).collect();
    for &(at, op, value) in edits {
        if lines.is_empty() {
            break;
        }
        let i = at % lines.len();
        let value = HOSTILE[value % HOSTILE.len()];
        match op % 4 {
            // Replace the value of a `key = value` line.
            0 => {
                if let Some((key, _)) = lines[i].split_once('=') {
                    lines[i] = format!("{key}= {value}");
                }
            }
            1 => {
                lines.remove(i);
            }
            2 => {
                let copy = lines[i].clone();
                lines.insert(i, copy);
            }
            _ => {
                let j = (i * 7 + 3) % lines.len();
                lines.swap(i, j);
            }
        }
    }
    lines.join("\n")
}

proptest! {
    // A fixed seed keeps CI reproducible; PROPTEST_RNG_SEED=<number> explores other cases.
    #![proptest_config(ProptestConfig {
        cases: 4000,
        rng_seed: std::env::var("PROPTEST_RNG_SEED").ok().and_then(|s| s.parse().ok()).unwrap_or(RngSeed::Fixed(0xf022)),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    #[test]
    fn arbitrary_text_never_panics(source in "\\PC{0,400}") {
        let _ = check_source(&source);
    }

    #[test]
    fn built_in_scenes_with_hostile_values_never_panic(
        scene in 0..BUILTIN_SCENES.len(),
        edits in prop::collection::vec((any::<usize>(), any::<u8>(), any::<usize>()), 1..6),
    ) {
        let _ = check_source(&mutated(scene, &edits));
    }

    #[test]
    fn truncated_scene_files_never_panic(scene in 0..BUILTIN_SCENES.len(), cut in any::<usize>()) {
        let source = BUILTIN_SCENES[scene].source;
        let mut at = cut % (source.len() + 1);
        while !source.is_char_boundary(at) {
            at -= 1;
        }
        let _ = check_source(&source[..at]);
    }
}

/// The mutations reach the validator, not only the TOML parser: some mutated
/// scenes still pass and some fail on a key (a guard against a generator
/// that only ever produces syntax errors).
#[test]
fn the_mutations_reach_the_validator() {
    let (mut valid, mut key_errors) = (0, 0);
    for k in 0..400usize {
        let edits = [(k * 13, (k % 4) as u8, k * 7), (k * 31, 0, k)];
        match check_source(&mutated(k % BUILTIN_SCENES.len(), &edits)) {
            Ok(_) => valid += 1,
            Err(e) if !e.key.is_empty() => key_errors += 1,
            Err(_) => {}
        }
    }
    assert!(valid > 20 && key_errors > 100, "{valid} valid, {key_errors} rejected on a key");
}
