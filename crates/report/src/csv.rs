//! Numeric CSV files with a header row: data for `osrl lwpr`, and the report's time series
//! (written with every number's shortest exact decimal, so reading them back gives the same
//! numbers bit for bit). Every error names the file and line, and for a bad cell its column
//! (number and name) and its text.

use crate::error::{ReportError, Result};
use std::io::Write;
use std::path::{Path, PathBuf};

macro_rules! bail {
    ($($t:tt)*) => {
        return Err(ReportError::Csv(format!($($t)*)))
    };
}

/// A CSV file's column names and rows (every row has one finite number per column).
#[derive(Debug)]
pub struct Table {
    /// The file read.
    pub path: PathBuf,
    /// Column names, from the header row.
    pub names: Vec<String>,
    /// Data rows.
    pub rows: Vec<Vec<f64>>,
    /// The file's line number (from 1) of each data row.
    pub lines: Vec<usize>,
}

impl Table {
    /// Reads `path`: a header row of distinct, non-empty names (not numbers; quotes around a
    /// name are dropped), then at least one row of finite numbers, comma-separated. Blank lines
    /// are skipped; `\n` or `\r\n` line ends, a UTF-8 byte-order mark and spaces around cells
    /// are allowed.
    pub fn read(path: &Path) -> Result<Table> {
        Self::read_with(path, true)
    }

    /// As [`Table::read`], but cells may also be `NaN`, `inf` or `-inf` (a time series of a
    /// run that diverged).
    pub fn read_series(path: &Path) -> Result<Table> {
        Self::read_with(path, false)
    }

    fn read_with(path: &Path, finite_only: bool) -> Result<Table> {
        let bytes = osrl_files::read_limited(path, crate::error::MAX_READ_BYTES)
            .map_err(|e| ReportError::Csv(format!("reading {e}")))?;
        Self::parse(path, &bytes, finite_only)
    }

    /// The table in `bytes`, as [`Table::read`] (or [`Table::read_series`] unless
    /// `finite_only`) reads a file; `path` names it in errors.
    ///
    /// # Errors
    /// [`ReportError::Csv`] naming the line, and for a bad cell its column and text.
    pub fn parse(path: &Path, bytes: &[u8], finite_only: bool) -> Result<Table> {
        let file = path.display();
        let text = std::str::from_utf8(bytes).map_err(|e| {
            let line = bytes[..e.valid_up_to()]
                .iter()
                .filter(|&&b| b == b'\n')
                .count()
                + 1;
            ReportError::Csv(format!(
                "{file}:{line}: not UTF-8 text (save the CSV as UTF-8)"
            ))
        })?;
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        if text.contains('\r') && !text.contains('\n') {
            bail!("{file}: lines end in a lone carriage return: convert them to \\n or \\r\\n");
        }
        let mut lines = text
            .lines()
            .enumerate()
            .map(|(i, l)| (i + 1, l))
            .filter(|(_, l)| !l.trim().is_empty());
        let (hl, header) = lines.next().ok_or_else(|| {
            ReportError::Csv(format!(
                "{file}: empty file (need a header row and data rows)"
            ))
        })?;
        // Names may be quoted (as R's write.csv writes them).
        let names: Vec<String> = header
            .split(',')
            .map(|s| {
                let s = s.trim();
                let q = s.len() >= 2 && s.starts_with('"') && s.ends_with('"');
                (if q { &s[1..s.len() - 1] } else { s }).to_string()
            })
            .collect();
        if names.iter().all(|n| n.parse::<f64>().is_ok()) {
            bail!("{file}:{hl}: the first line holds numbers: the CSV needs a header row of column names");
        }
        // Linear in the number of columns (a hostile header may have millions).
        let mut seen = std::collections::HashMap::with_capacity(names.len());
        for (j, n) in names.iter().enumerate() {
            if n.is_empty() {
                bail!("{file}:{hl}: column {} has no name", j + 1);
            }
            if let Some(k) = seen.insert(n.as_str(), j) {
                bail!(
                    "{file}:{hl}: columns {} and {} are both named '{n}'",
                    k + 1,
                    j + 1
                );
            }
        }
        let (mut rows, mut row_lines) = (Vec::new(), Vec::new());
        for (ln, line) in lines {
            let cells: Vec<&str> = line.split(',').map(str::trim).collect();
            if cells.len() != names.len() {
                bail!(
                    "{file}:{ln}: {} columns, the header has {}",
                    cells.len(),
                    names.len()
                );
            }
            let mut row = Vec::with_capacity(cells.len());
            for (j, cell) in cells.iter().enumerate() {
                let at = || format!("{file}:{ln}: column {} ({})", j + 1, names[j]);
                match cell.parse::<f64>() {
                    Ok(v) if v.is_finite() || !finite_only => row.push(v),
                    Ok(_) => bail!("{}: '{cell}' is not finite", at()),
                    Err(_) if cell.contains([';', '\t']) => {
                        bail!(
                            "{}: '{cell}' is not a number (the separator must be a comma)",
                            at()
                        )
                    }
                    Err(_) => bail!("{}: '{cell}' is not a number", at()),
                }
            }
            rows.push(row);
            row_lines.push(ln);
        }
        if rows.is_empty() {
            bail!("{file}: no data rows after the header");
        }
        Ok(Table {
            path: path.to_path_buf(),
            names,
            rows,
            lines: row_lines,
        })
    }

    /// Fails unless `other` has the same column names in the same order (a test file for a
    /// model trained on this one).
    pub fn check_same_columns(&self, other: &Table) -> Result<()> {
        let (a, b) = (self.path.display(), other.path.display());
        if self.names.len() != other.names.len() {
            bail!(
                "{b} has {} columns, {a} has {}",
                other.names.len(),
                self.names.len()
            );
        }
        if let Some(j) = (0..self.names.len()).find(|&j| self.names[j] != other.names[j]) {
            bail!(
                "{b}: column {} is '{}', in {a} it is '{}' (the files need the same columns in the same order)",
                j + 1,
                other.names[j],
                self.names[j]
            );
        }
        Ok(())
    }

    /// The column named `name`.
    pub fn column(&self, name: &str) -> Option<usize> {
        self.names.iter().position(|n| n == name)
    }
}

/// Writes `head` and `rows` to `path` (creating its folder), every number as Rust writes an
/// `f64` (the shortest decimal that reads back exactly; `NaN`, `inf`).
pub fn write(path: &Path, head: &[String], rows: impl Iterator<Item = Vec<f64>>) -> Result<()> {
    if let Some(dir) = path.parent() {
        crate::error::create_dir(dir)?;
    }
    let io = |e| ReportError::io(path, e);
    // Streamed (a long run's series is large): checked first, as `osrl_files` writes.
    osrl_files::check_output(path)?;
    let file = std::fs::File::create(path).map_err(io)?;
    let mut w = std::io::BufWriter::new(file);
    writeln!(w, "{}", head.join(",")).map_err(io)?;
    for row in rows {
        let row: Vec<String> = row.iter().map(|v| format!("{v}")).collect();
        writeln!(w, "{}", row.join(",")).map_err(io)?;
    }
    w.flush().map_err(io)
}
