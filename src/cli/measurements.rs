//! Measurement tables for `fairgrasp calibrate`: small CSV files a person writes by hand or
//! exports from a pendant or a marker detector.
//!
//! - Blank lines and lines starting with `#` are skipped; the first other line is the header.
//! - Every column name ends in its unit: lengths `_m` or `_mm`, angles `_deg` or `_rad`
//!   (`world_x_mm`, `j3_deg`, `marker_yaw_rad`); values are converted to metres and radians.
//! - Unknown or repeated columns are refused, naming them; so is a row with a missing, extra or
//!   non-numeric cell (naming the line and the column).
//! - Only a regular file of at most [`MAX_BYTES`] with at most [`MAX_ROWS`] rows is read.

use std::path::Path;

use anyhow::{Context, bail};

/// The largest measurement file read \[bytes\].
pub const MAX_BYTES: u64 = 1 << 20;
/// The most measurement rows read.
pub const MAX_ROWS: usize = 10_000;

/// A parsed table: column names without their unit suffix, values in metres and radians.
#[derive(Debug)]
pub struct Table {
    pub path: String,
    columns: Vec<String>,
    pub rows: Vec<Row>,
}

/// One data row and the file line it came from (1-based).
#[derive(Debug)]
pub struct Row {
    pub line: usize,
    values: Vec<f64>,
}

/// The unit suffixes and what one unit is in metres or radians.
const UNITS: [(&str, f64); 4] = [
    ("_mm", 1e-3),
    ("_m", 1.0),
    ("_deg", std::f64::consts::PI / 180.0),
    ("_rad", 1.0),
];

impl Table {
    /// Reads `path`, accepting only the columns in `allowed` (names without unit suffix).
    pub fn read(path: &Path, allowed: &[&str]) -> anyhow::Result<Table> {
        let shown = path.display().to_string();
        // The rule every input file is read by: a regular file within the cap.
        let text = fairgrasp_types::fs::read_text_bounded(path, MAX_BYTES)
            .with_context(|| format!("{shown}: cannot read it as a measurement table (CSV)"))?;
        Self::parse(&text, &shown, allowed)
    }

    /// Parses the text of a table (see the module docs); `path` names it in errors.
    pub fn parse(text: &str, path: &str, allowed: &[&str]) -> anyhow::Result<Table> {
        let mut lines = text
            .lines()
            .enumerate()
            .map(|(i, l)| (i + 1, l.trim()))
            .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
        let Some((header_line, header)) = lines.next() else {
            bail!("{path}: no header line (and no data): see `fairgrasp calibrate --help`");
        };
        let mut columns = Vec::new();
        let mut factors = Vec::new();
        for cell in header.split(',').map(str::trim) {
            let Some((name, factor)) = UNITS
                .iter()
                .find_map(|(suffix, f)| cell.strip_suffix(suffix).map(|n| (n, *f)))
            else {
                bail!(
                    "{path}:{header_line}: column `{}` has no unit: end its name in _m, _mm, _deg or _rad",
                    excerpt(cell)
                );
            };
            if !allowed.contains(&name) {
                bail!(
                    "{path}:{header_line}: unknown column `{}`; the columns are {} (each with a unit suffix)",
                    excerpt(cell),
                    allowed.join(", ")
                );
            }
            if columns.iter().any(|c| c == name) {
                bail!("{path}:{header_line}: column `{name}` appears twice");
            }
            columns.push(name.to_string());
            factors.push(factor);
        }
        let mut rows = Vec::new();
        for (line, text) in lines {
            if rows.len() == MAX_ROWS {
                bail!("{path}: more than {MAX_ROWS} rows");
            }
            let cells: Vec<&str> = text.split(',').map(str::trim).collect();
            if cells.len() != columns.len() {
                bail!(
                    "{path}:{line}: {} cells, the header has {} columns",
                    cells.len(),
                    columns.len()
                );
            }
            let mut values = Vec::with_capacity(cells.len());
            for ((cell, name), factor) in cells.iter().zip(&columns).zip(&factors) {
                match cell.parse::<f64>() {
                    Ok(v) if v.is_finite() && v.abs() <= 1e6 => values.push(v * factor),
                    _ => bail!(
                        "{path}:{line}: `{name}` is `{}`, not a finite number within ±1e6",
                        excerpt(cell)
                    ),
                }
            }
            rows.push(Row { line, values });
        }
        Ok(Table {
            path: path.to_string(),
            columns,
            rows,
        })
    }

    /// Whether every one of `names` is a column.
    pub fn has_all(&self, names: &[&str]) -> bool {
        names.iter().all(|n| self.columns.iter().any(|c| c == n))
    }

    /// The values of `names` in a row, in that order (metres, radians); the caller has checked
    /// [`Table::has_all`].
    pub fn values<const N: usize>(&self, row: &Row, names: [&str; N]) -> [f64; N] {
        names.map(|n| {
            let i = self.columns.iter().position(|c| c == n);
            i.map_or(f64::NAN, |i| row.values[i])
        })
    }
}

/// At most 40 characters of a cell, for messages.
fn excerpt(s: &str) -> String {
    let mut out: String = s.chars().take(40).collect();
    if out.len() < s.len() {
        out.push('…');
    }
    out
}

#[cfg(test)]
mod tests {
    use super::Table;

    #[test]
    fn units_are_converted_and_mistakes_named() {
        let t = Table::parse(
            "# touches\n\nworld_x_mm, j1_deg\n1000, 90\n",
            "f.csv",
            &["world_x", "j1"],
        )
        .unwrap();
        let [x, j] = t.values(&t.rows[0], ["world_x", "j1"]);
        assert!((x - 1.0).abs() < 1e-12 && (j - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
        assert_eq!(t.rows[0].line, 4);
        let err = |text: &str| {
            Table::parse(text, "f.csv", &["world_x"])
                .unwrap_err()
                .to_string()
        };
        assert!(err("world_x\n1\n").contains("no unit"));
        assert!(err("world_y_m\n1\n").contains("unknown column `world_y_m`"));
        assert!(err("world_x_m,world_x_mm\n1,2\n").contains("twice"));
        assert!(err("world_x_m\n1,2\n").contains("f.csv:2: 2 cells"));
        assert!(err("world_x_m\nnan\n").contains("f.csv:2: `world_x` is `nan`"));
        assert!(err("# only a comment\n").contains("no header"));
    }
}
