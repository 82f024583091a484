//! CIE 1931 2° colour-matching functions and their integral over a wavelength interval.
//!
//! The table (360–830 nm at 5 nm, public CIE data) is compiled in from
//! `core/data/cie1931_2deg_5nm.csv`, a copy of `shared/data/`.

use glam::DVec3;

const CSV: &str = include_str!("../../data/cie1931_2deg_5nm.csv");
/// The visible range that physically based band tables and the colour of
/// a wavelength cover, in nm.
pub const VISIBLE_NM: (f32, f32) = (380.0, 780.0);

/// Wavelength of the table's first row, in nm.
pub const FIRST_NM: f64 = 360.0;
/// Spacing of the rows, in nm.
pub const STEP_NM: f64 = 5.0;

/// Number of rows in the compiled-in table.
pub const ROWS: usize = 95;

/// Parses the compiled-in CSV once per call; cheap (95 rows) and allocation-free.
fn table() -> [DVec3; ROWS] {
    let mut rows = [DVec3::ZERO; ROWS];
    let mut count = 0;
    for line in CSV.lines() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') || line.starts_with("lambda") {
            continue;
        }
        let mut fields = line.split(',').map(|f| f.trim().parse::<f64>().unwrap_or(f64::NAN));
        let lambda = fields.next().unwrap_or(f64::NAN);
        debug_assert_eq!(lambda, FIRST_NM + STEP_NM * count as f64);
        let xyz = DVec3::new(
            fields.next().unwrap_or(f64::NAN),
            fields.next().unwrap_or(f64::NAN),
            fields.next().unwrap_or(f64::NAN),
        );
        rows[count] = xyz;
        count += 1;
    }
    debug_assert_eq!(count, ROWS);
    rows
}

/// The table's rows: (x̄, ȳ, z̄) at `FIRST_NM + i·STEP_NM`.
pub fn rows() -> [DVec3; ROWS] {
    table()
}

/// The colour-matching functions (x̄, ȳ, z̄) at `lambda_nm`, linearly
/// interpolated; zero outside the table.
pub fn cmf(lambda_nm: f64) -> DVec3 {
    cmf_in(&table(), lambda_nm)
}

fn cmf_in(rows: &[DVec3; ROWS], lambda_nm: f64) -> DVec3 {
    let x = (lambda_nm - FIRST_NM) / STEP_NM;
    if !(0.0..=(ROWS - 1) as f64).contains(&x) {
        return DVec3::ZERO;
    }
    let i = (x as usize).min(ROWS - 2);
    let f = x - i as f64;
    rows[i] * (1.0 - f) + rows[i + 1] * f
}

/// ∫ (x̄, ȳ, z̄) dλ over `[lo_nm, hi_nm]` by the trapezoid rule on a 0.25 nm
/// grid (fine against the 5 nm table, so the result does not depend on how
/// the visible range is cut into bands).
pub fn integrate(lo_nm: f64, hi_nm: f64) -> DVec3 {
    let rows = table();
    let steps = (((hi_nm - lo_nm) / 0.25) as usize).max(1);
    let h = (hi_nm - lo_nm) / steps as f64;
    let mut sum = (cmf_in(&rows, lo_nm) + cmf_in(&rows, hi_nm)) * 0.5;
    for k in 1..steps {
        sum += cmf_in(&rows, lo_nm + h * k as f64);
    }
    sum * h
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_values_at_known_wavelengths() {
        // CIE 1931: ȳ peaks at 555 nm with value 1.0; x̄(600) = 1.0622.
        assert!((cmf(555.0).y - 1.0).abs() < 1e-3);
        assert!((cmf(600.0).x - 1.0622).abs() < 1e-3);
        assert_eq!(cmf(300.0), DVec3::ZERO);
    }

    #[test]
    fn integral_is_additive() {
        let whole = integrate(380.0, 780.0);
        let parts = integrate(380.0, 500.0) + integrate(500.0, 780.0);
        assert!((whole - parts).length() < 1e-9 * whole.length().max(1.0) + 1e-6);
        // ∫ȳ over the visible range is about 106.86 (CIE 1931, 1 nm sums).
        assert!((whole.y - 106.86).abs() < 0.2, "{}", whole.y);
    }
}
