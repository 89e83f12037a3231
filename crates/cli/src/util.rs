//! Small helpers shared by the commands: robot lookup, flag values, JSON output.

use anyhow::{bail, Context, Result};
use osrl_control::TrajectoryKind;
use osrl_dynamics::Model;
use std::path::Path;

/// A built-in robot by name (`planar3`, `sarcos7`) or a URDF file path.
pub fn load_robot(spec: &str) -> Result<Model> {
    Ok(osrl_learn::load_robot(spec)?)
}

/// Parses a `--trajectory` value (checked by clap: `figure8`, `circle`, `min_jerk`, `family`).
pub fn trajectory_kind(t: &str) -> TrajectoryKind {
    match t {
        "circle" => TrajectoryKind::Circle,
        "min_jerk" => TrajectoryKind::MinJerk,
        "family" => TrajectoryKind::Family,
        _ => TrajectoryKind::Figure8,
    }
}

/// Parses `v1,v2,...` into exactly `n` finite numbers; the error names the flag.
pub fn parse_vec(flag: &str, text: &str, n: usize) -> Result<Vec<f64>> {
    let vals = text
        .split(',')
        .map(|s| {
            let s = s.trim();
            s.parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .with_context(|| format!("--{flag}: '{s}' is not a finite number"))
        })
        .collect::<Result<Vec<f64>>>()?;
    if vals.len() != n {
        bail!(
            "--{flag}: expected {n} comma-separated values (one per joint), got {}",
            vals.len()
        );
    }
    Ok(vals)
}

/// Prints `value` as one JSON line (the last line of a command's stdout).
pub fn print_json(value: &serde_json::Value) {
    println!(
        "{}",
        serde_json::to_string(value).expect("JSON values serialise")
    );
}

/// A matrix as a list of rows.
pub fn rows<R: nalgebra::Dim, C: nalgebra::Dim, S: nalgebra::RawStorage<f64, R, C>>(
    m: &nalgebra::Matrix<f64, R, C, S>,
) -> Vec<Vec<f64>> {
    (0..m.nrows())
        .map(|i| (0..m.ncols()).map(|j| m[(i, j)]).collect())
        .collect()
}

/// Population standard deviation of column `col` of `rows` (NaN without rows).
pub fn std_dev(rows: &[Vec<f64>], col: usize) -> f64 {
    let n = rows.len() as f64;
    let mean = rows.iter().map(|r| r[col]).sum::<f64>() / n;
    (rows.iter().map(|r| (r[col] - mean).powi(2)).sum::<f64>() / n).sqrt()
}

/// Largest config file read (16 MiB).
pub const MAX_CONFIG_BYTES: u64 = 16 << 20;

/// Checks, before any work, that `flag`'s `path` can be written as a file
/// ([`osrl_files::check_output`]) and is none of the run's `inputs`; a missing folder is
/// created.
pub fn check_out_file(flag: &str, path: &Path, inputs: &[Option<&Path>]) -> Result<()> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        if std::fs::symlink_metadata(dir).is_err() {
            std::fs::create_dir_all(dir)
                .with_context(|| format!("{flag} {}: creating its folder", path.display()))?;
        }
    }
    osrl_files::check_output(path).context(flag.to_string())?;
    osrl_files::check_not_input(path, inputs).context(flag.to_string())
}

/// Checks, before any work, that `flag`'s folder `dir` can hold `files`
/// ([`osrl_files::check_output_dir`]; a missing folder is created) and that none of them is one
/// of the run's `inputs`.
pub fn check_out_dir(
    flag: &str,
    dir: &Path,
    files: &[&str],
    inputs: &[Option<&Path>],
) -> Result<()> {
    osrl_files::check_output_dir(dir, files).context(flag.to_string())?;
    files.iter().try_for_each(|f| {
        osrl_files::check_not_input(&dir.join(f), inputs).context(flag.to_string())
    })
}

/// The extensions of the files a report page is made of (`osrl reproduce`, `osrl report`).
pub const PAGE_EXTENSIONS: [&str; 6] = ["html", "json", "csv", "svg", "png", "osrl"];

/// The path of a `--robot` that names a file (not a built-in robot), as an input to protect.
pub fn robot_file(robot: Option<&str>) -> Option<&Path> {
    robot.map(Path::new).filter(|p| p.is_file())
}

/// Writes `bytes`, the result of a long run, to `path`, or else next to it under a fresh name
/// ([`osrl_files::write_or_fallback`]). A fallback is an error that says where the result is.
pub fn save_result(what: &str, path: &Path, bytes: &[u8]) -> Result<()> {
    let w = osrl_files::write_or_fallback(path, bytes)
        .with_context(|| format!("saving the {what} to {}", path.display()))?;
    match w.failed {
        None => Ok(()),
        Some(e) => bail!(
            "saving the {what}: {e}; it was written to {} instead",
            w.path.display()
        ),
    }
}

/// Reads a TOML file into `T`. A syntax or type error reads
/// ``FILE:LINE:COLUMN: `that line`: message`` (one line; the position of the offending value).
pub fn read_toml<T: serde::de::DeserializeOwned>(path: &Path) -> Result<T> {
    let text = osrl_files::read_text_limited(path, MAX_CONFIG_BYTES)?;
    parse_toml(path, &text)
}

/// Parses TOML `text` into `T`, with errors as [`read_toml`] gives them (`path` names it).
pub fn parse_toml<T: serde::de::DeserializeOwned>(path: &Path, text: &str) -> Result<T> {
    toml::from_str(text).map_err(|e| {
        let at = e.span().map(|s| {
            let mut start = s.start.min(text.len());
            while !text.is_char_boundary(start) {
                start -= 1;
            }
            let line_start = text[..start].rfind('\n').map_or(0, |i| i + 1);
            let line_end = text[start..].find('\n').map_or(text.len(), |i| start + i);
            let line = text[..start].matches('\n').count() + 1;
            let col = text[line_start..start].chars().count() + 1;
            let src = text[line_start..line_end].trim();
            format!(":{line}:{col}: `{src}`")
        });
        anyhow::anyhow!(
            "{}{}: {}",
            path.display(),
            at.unwrap_or_default(),
            e.message().trim().replace('\n', " ")
        )
    })
}

/// Median (mean of the middle two for an even count; NaN when empty).
pub use lwpr::datasets::median;
