//! Every relative link and image in the README and the docs book resolves:
//! the file exists (inside the repository), and a `#fragment` names a
//! heading of the page it points to. The repository names nothing outside
//! itself.

use std::fs;
use std::path::{Path, PathBuf};

/// The repository's root.
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).parent().unwrap().to_path_buf()
}

/// The README and every Markdown page under `docs/src`.
fn pages() -> Vec<PathBuf> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        for entry in fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                walk(&path, out);
            } else if path.extension().is_some_and(|e| e == "md") {
                out.push(path);
            }
        }
    }
    let mut pages = vec![root().join("README.md")];
    walk(&root().join("docs/src"), &mut pages);
    pages
}

/// The targets of a page's links and images outside code blocks and code spans.
fn targets(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut fenced = false;
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            continue;
        }
        if fenced {
            continue;
        }
        // Code spans hold code, not links.
        let prose: String = line.split('`').step_by(2).collect::<Vec<_>>().join(" ");
        let mut rest = prose.as_str();
        while let Some(i) = rest.find("](") {
            let after = &rest[i + 2..];
            let end = after.find(')').unwrap_or(after.len());
            out.push(after[..end].trim().to_string());
            rest = &after[end..];
        }
    }
    out
}

/// GitHub's and mdBook's anchor of a heading: lower case, spaces to
/// hyphens, punctuation other than hyphens and underscores dropped.
fn slug(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter_map(|c| match c {
            ' ' => Some('-'),
            c if c.is_alphanumeric() || c == '-' || c == '_' => Some(c),
            _ => None,
        })
        .collect()
}

/// The anchors of a page's headings.
fn anchors(text: &str) -> Vec<String> {
    let mut fenced = false;
    let mut out = Vec::new();
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
        } else if !fenced && line.starts_with('#') {
            out.push(slug(line.trim_start_matches('#')));
        }
    }
    out
}

/// What is wrong with link `target` on `page`, if anything.
fn broken(page: &Path, target: &str) -> Option<String> {
    if target.starts_with("http://") || target.starts_with("https://") || target.starts_with("mailto:") {
        return None;
    }
    let (file, fragment) = target.split_once('#').unwrap_or((target, ""));
    let file = if file.is_empty() { page.to_path_buf() } else { page.parent().unwrap().join(file) };
    let Ok(file) = file.canonicalize() else { return Some("no such file".into()) };
    if !file.starts_with(root().canonicalize().unwrap()) {
        return Some("outside the repository".into());
    }
    if !fragment.is_empty() {
        let text = fs::read_to_string(&file).unwrap_or_default();
        if !anchors(&text).iter().any(|a| a == fragment) {
            return Some(format!("no heading #{fragment}"));
        }
    }
    None
}

#[test]
fn every_relative_link_and_image_in_the_readme_and_the_book_resolves() {
    let mut bad = Vec::new();
    for page in pages() {
        let text = fs::read_to_string(&page).unwrap();
        for target in targets(&text) {
            if let Some(why) = broken(&page, &target) {
                bad.push(format!("{}: ({target}): {why}", page.strip_prefix(root()).unwrap().display()));
            }
        }
        if text.contains("../shared/") {
            bad.push(format!("{}: names ../shared/, outside the repository", page.display()));
        }
    }
    assert!(bad.is_empty(), "broken links:\n{}", bad.join("\n"));
}

#[test]
fn the_summary_lists_every_page_of_the_book() {
    let summary = fs::read_to_string(root().join("docs/src/SUMMARY.md")).unwrap();
    let listed = targets(&summary);
    for page in pages().iter().filter(|p| p.starts_with(root().join("docs/src"))) {
        let rel = page.strip_prefix(root().join("docs/src")).unwrap().to_string_lossy().into_owned();
        assert!(rel == "SUMMARY.md" || listed.contains(&rel), "docs/src/SUMMARY.md does not list {rel}");
    }
}

#[test]
fn the_readme_stays_a_front_page() {
    let lines = fs::read_to_string(root().join("README.md")).unwrap().lines().count();
    assert!(lines <= 250, "README.md has {lines} lines: move the rest to the book (docs/)");
}

#[test]
fn the_checker_finds_links_and_ignores_code() {
    let text = "see [a](x.md#b) and ![i](img.png)\n`[c](code.md)`\n```\n[d](fenced.md)\n```\n";
    assert_eq!(targets(text), ["x.md#b", "img.png"]);
    assert_eq!(slug("Light tracing: the caustics the camera sees"), "light-tracing-the-caustics-the-camera-sees");
}
