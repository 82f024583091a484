//! Tabulated n(λ) from a CSV file: two columns, wavelength and index, an
//! optional header row, `#` comments; wavelengths in nm or µm.

use std::path::Path;

/// Wavelengths (nm) and indices as the file lists them.
pub type IorTable = (Vec<f32>, Vec<f32>);

/// Reads `path`; the error names the file and line.
pub fn load(path: &Path) -> Result<IorTable, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("cannot read index table {}: {e}", path.display()))?;
    parse(&text).map_err(|(line, reason)| format!("{}:{line}: {reason}", path.display()))
}

/// Which unit the wavelength column is in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Unit {
    Nanometre,
    Micrometre,
}

/// Parses CSV text. The unit comes from the header (`nm`, or `um`/`µm`
/// in the wavelength column's name), else from the values: a visible
/// wavelength is below 10 in µm and above 100 in nm. Errors carry the
/// 1-based line.
pub fn parse(text: &str) -> Result<IorTable, (u64, String)> {
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(false)
        .comment(Some(b'#'))
        .trim(csv::Trim::All)
        .flexible(true)
        .from_reader(text.as_bytes());
    let (mut unit, mut rows) = (None, Vec::new());
    for (i, record) in reader.records().enumerate() {
        let record = record.map_err(|e| (e.position().map_or(0, |p| p.line()), e.to_string()))?;
        let line = record.position().map_or(0, |p| p.line());
        if record.len() != 2 {
            return Err((line, format!("needs two columns (wavelength, n), got {}", record.len())));
        }
        let number = |k: usize| record[k].parse::<f64>().ok().filter(|x| x.is_finite());
        match (number(0), number(1)) {
            (Some(lambda), Some(n)) => rows.push((line, lambda, n)),
            _ if i == 0 => unit = header_unit(&record[0]),
            _ => {
                let bad = if number(0).is_none() { &record[0] } else { &record[1] };
                return Err((line, format!("\"{bad}\" is not a finite number")));
            }
        }
    }
    let Some(&(last_line, ..)) = rows.last() else {
        return Err((1, "has no rows of wavelength, n".into()));
    };
    let unit = match unit {
        Some(u) => u,
        None if rows.iter().all(|&(_, l, _)| l < 10.0) => Unit::Micrometre,
        None if rows.iter().all(|&(_, l, _)| l > 100.0) => Unit::Nanometre,
        None => return Err((last_line, "wavelengths mix µm and nm (name the unit in a header: wavelength_nm)".into())),
    };
    let scale = if unit == Unit::Micrometre { 1000.0 } else { 1.0 };
    if let Some(w) = rows.windows(2).find(|w| w[1].1 <= w[0].1) {
        return Err((w[1].0, format!("wavelengths must increase: {} after {}", w[1].1, w[0].1)));
    }
    Ok(rows.into_iter().map(|(_, l, n)| ((l * scale) as f32, n as f32)).unzip())
}

/// The unit a header names for the wavelength column, if it names one.
fn header_unit(name: &str) -> Option<Unit> {
    let name = name.to_ascii_lowercase();
    if name.contains("nm") {
        Some(Unit::Nanometre)
    } else if name.contains("um") || name.contains("µm") || name.contains("micro") {
        Some(Unit::Micrometre)
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn units_come_from_the_header_or_the_values() {
        let nm = "# my glass\nwavelength_nm, n\n400, 1.53\n700, 1.51\n";
        assert_eq!(parse(nm).unwrap(), (vec![400.0, 700.0], vec![1.53, 1.51]));
        let um = "wl,n\n0.4,1.53\n0.7,1.51\n";
        assert_eq!(parse(um).unwrap(), (vec![400.0, 700.0], vec![1.53, 1.51]));
        let header_um = "lambda (um),n\n0.4,1.53\n0.7,1.51\n";
        assert_eq!(parse(header_um).unwrap().0, vec![400.0, 700.0]);
    }

    #[test]
    fn bad_tables_name_their_line() {
        let cases = [
            ("400,1.5\n300,1.6\n", 2, "must increase"),
            ("400,1.5\n500\n", 2, "two columns"),
            ("400,1.5\n500,abc\n", 2, "\"abc\" is not a finite number"),
            ("wavelength,n\n400,1.5\nnan,1.5\n", 3, "\"nan\" is not a finite number"),
            ("# nothing\n", 1, "no rows"),
            ("0.5,1.5\n500,1.5\n", 2, "mix"),
        ];
        for (text, line, reason) in cases {
            let (l, r) = parse(text).unwrap_err();
            assert_eq!(l, line, "{text:?}: {r}");
            assert!(r.contains(reason), "{text:?}: {r}");
        }
    }
}
