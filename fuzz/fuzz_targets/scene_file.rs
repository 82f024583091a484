//! Fuzzes the scene-file reader: any bytes are parsed, validated and
//! prepared; the reader may reject them but must never panic. The same body
//! runs under proptest in `cargo test` (tests/tests/fuzz_scene_file.rs).

#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(source) = std::str::from_utf8(data) {
        let _ = prismatic_cli::scene_file::check_source(source);
    }
});
