//! Parsers of the command line's pass arguments: which passes
//! (`--passes N` or `A..B`), and a time budget (`--time`, `--save-every`).

use std::ops::Range;

/// Parses `N` (passes 0..N) or `A..B` (passes A to B − 1).
pub fn parse_passes(s: &str) -> Result<Range<u32>, String> {
    let number = |t: &str| t.trim().parse::<u32>().map_err(|_| format!("`{t}` is not a pass number"));
    let range = match s.split_once("..") {
        Some((a, b)) => number(a)?..number(b)?,
        None => 0..number(s)?,
    };
    if range.is_empty() {
        return Err(format!("`{s}` names no pass: give N ≥ 1 or A..B with A < B"));
    }
    Ok(range)
}

/// Parses a positive, finite number of seconds.
pub fn parse_seconds(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(t) if t.is_finite() && t > 0.0 => Ok(t),
        _ => Err(format!("`{s}` is not a positive number of seconds")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pass_ranges() {
        assert_eq!(parse_passes("16"), Ok(0..16));
        assert_eq!(parse_passes("8..16"), Ok(8..16));
        assert!(parse_passes("0").is_err());
        assert!(parse_passes("8..8").is_err());
        assert!(parse_passes("9..3").is_err());
        assert!(parse_passes("-1").is_err());
        assert!(parse_passes("a..b").is_err());
        assert!(parse_seconds("0").is_err());
        assert!(parse_seconds("nan").is_err());
        assert_eq!(parse_seconds("1.5"), Ok(1.5));
    }
}
