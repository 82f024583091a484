//! Keeps the layer table in `src/lib.rs` true: every folder and module on
//! disk is in the table, and no module uses a folder above its own.

use std::collections::BTreeMap;
use std::fs;
use std::path::Path;

/// One row of the table: the layer's number and its modules.
struct Layer {
    number: u32,
    modules: Vec<String>,
}

/// The table's rows, by folder, read from the crate's doc comment.
fn table() -> BTreeMap<String, Layer> {
    let lib = fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("src/lib.rs")).unwrap();
    let mut rows = BTreeMap::new();
    for line in lib.lines().filter_map(|l| l.strip_prefix("//! |")) {
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        let Ok(number) = cells[0].parse() else { continue };
        let folder = cells[1].trim_matches(|c| c == '[' || c == ']' || c == '`').to_string();
        let modules = cells[2].split(',').map(|m| m.trim().trim_matches('`').to_string()).collect();
        rows.insert(folder, Layer { number, modules });
    }
    assert!(!rows.is_empty(), "src/lib.rs has no layer table");
    rows
}

/// The source less its comments, so that doc links do not count as uses.
fn code(text: &str) -> String {
    let mut out = String::new();
    let mut rest = text;
    while let Some(i) = rest.find(['/', '"']) {
        out.push_str(&rest[..i]);
        rest = &rest[i..];
        if rest.starts_with("//") {
            rest = rest.find('\n').map_or("", |j| &rest[j..]);
        } else if rest.starts_with("/*") {
            rest = rest.find("*/").map_or("", |j| &rest[j + 2..]);
        } else if let Some(s) = rest.strip_prefix('"') {
            // A string literal: skipped whole (escapes included).
            let mut chars = s.char_indices();
            let mut end = s.len();
            while let Some((j, c)) = chars.next() {
                match c {
                    '\\' => _ = chars.next(),
                    '"' => {
                        end = j + 1;
                        break;
                    }
                    _ => {}
                }
            }
            rest = &s[end.min(s.len())..];
        } else {
            out.push('/');
            rest = &rest[1..];
        }
    }
    out + rest
}

/// The folders a module's code names: `crate::F::…` and `crate::{F::…, …}`.
fn folders_used(code: &str) -> Vec<String> {
    let mut used = Vec::new();
    for (i, _) in code.match_indices("crate::") {
        let after = &code[i + "crate::".len()..];
        let names: Vec<&str> = match after.strip_prefix('{') {
            Some(group) => group[..group.find('}').unwrap_or(group.len())].split(',').collect(),
            None => vec![after],
        };
        for name in names {
            let name = name.trim();
            let end = name.find(|c: char| !(c.is_alphanumeric() || c == '_')).unwrap_or(name.len());
            used.push(name[..end].to_string());
        }
    }
    used
}

#[test]
fn every_folder_and_module_is_in_the_layer_table() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let table = table();
    let mut on_disk = BTreeMap::new();
    for entry in fs::read_dir(&src).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            let mut modules: Vec<String> = fs::read_dir(&path)
                .unwrap()
                .map(|e| e.unwrap().path().file_stem().unwrap().to_string_lossy().into_owned())
                .filter(|m| m != "mod")
                .collect();
            modules.sort();
            on_disk.insert(path.file_name().unwrap().to_string_lossy().into_owned(), modules);
        } else {
            let name = path.file_name().unwrap().to_string_lossy().into_owned();
            assert_eq!(name, "lib.rs", "src/{name}: a module outside the layer folders");
        }
    }
    let in_table: BTreeMap<String, Vec<String>> = table
        .iter()
        .map(|(folder, layer)| {
            let mut modules = layer.modules.clone();
            modules.sort();
            (folder.clone(), modules)
        })
        .collect();
    assert_eq!(on_disk, in_table, "the folders and modules on disk (left) differ from src/lib.rs's table (right)");
}

#[test]
fn no_module_uses_a_folder_above_its_own() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let table = table();
    let mut upward = Vec::new();
    for (folder, layer) in &table {
        for entry in fs::read_dir(src.join(folder)).unwrap() {
            let path = entry.unwrap().path();
            let text = fs::read_to_string(&path).unwrap();
            for used in folders_used(&code(&text)) {
                // Root items (`crate::Vec3`, re-exports) are not folders.
                let Some(other) = table.get(&used) else { continue };
                if other.number > layer.number {
                    upward.push(format!(
                        "{} (layer {}) uses {used} (layer {})",
                        path.display(),
                        layer.number,
                        other.number
                    ));
                }
            }
        }
    }
    assert!(upward.is_empty(), "modules that use a layer above their own:\n{}", upward.join("\n"));
}

#[test]
fn the_checker_sees_uses_and_ignores_comments() {
    let text = "use crate::plan::prepared::X; // crate::render\n/* crate::photons */ let s = \"crate::optics\";\nuse crate::{model::a, util::b};";
    assert_eq!(folders_used(&code(text)), ["plan", "model", "util"]);
}
