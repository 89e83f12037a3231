//! The reference LWPR C library as an oracle: built from `../shared/reference/lwpr-c` with its
//! own `build.sh` (into a folder of ours; the reference folder is only read), linked with our
//! harness `scripts/lwpr_c_harness.c`, and run on a sample file of [`Samples`].

use super::samples::{Measured, Samples};
use anyhow::{ensure, Context, Result};
use std::path::{Path, PathBuf};
use std::process::Command;

/// The harness's source, compiled into the binary so that the command runs from any folder.
const HARNESS_C: &str = include_str!("../../../../../scripts/lwpr_c_harness.c");

/// The compiler flags of the two builds: JSON key and flags.
pub const VARIANTS: [(&str, &str); 2] = [("c_o2", "-O2"), ("c_o3_native", "-O3 -march=native")];

/// One build of the library with the harness linked in.
pub struct Harness {
    pub key: &'static str,
    pub exe: PathBuf,
}

/// Why the reference cannot be built here (`None`: it can): no `build.sh` in `reference`, or
/// no `gcc` (which `build.sh` calls).
pub fn missing(reference: &Path) -> Option<String> {
    if !reference.join("build.sh").is_file() {
        return Some(format!(
            "no reference library at {} (build.sh not found)",
            reference.display()
        ));
    }
    let gcc = Command::new("gcc").arg("--version").output();
    if !gcc.map(|o| o.status.success()).unwrap_or(false) {
        return Some("no C compiler (gcc --version failed)".into());
    }
    None
}

/// Runs `cmd`, failing with its stderr when it does not succeed; its stdout.
fn run(cmd: &mut Command, what: &str) -> Result<String> {
    let out = cmd
        .output()
        .with_context(|| format!("{what}: could not start {cmd:?}"))?;
    ensure!(
        out.status.success(),
        "{what} failed ({}): {}",
        out.status,
        String::from_utf8_lossy(&out.stderr).trim()
    );
    Ok(String::from_utf8_lossy(&out.stdout).into_owned())
}

/// Builds every variant of [`VARIANTS`] under `dir` (`dir/c_o2/`, …).
pub fn build(reference: &Path, dir: &Path) -> Result<Vec<Harness>> {
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    let src = dir.join("lwpr_c_harness.c");
    std::fs::write(&src, HARNESS_C).with_context(|| format!("writing {}", src.display()))?;
    let script = reference.join("build.sh");
    let mut out = Vec::new();
    for (key, flags) in VARIANTS {
        let lib = std::path::absolute(dir.join(key))?;
        let flag_list: Vec<&str> = flags.split(' ').collect();
        run(
            Command::new("bash").arg(&script).arg(&lib).args(&flag_list),
            &format!("building the reference library ({flags})"),
        )?;
        let exe = lib.join("harness");
        run(
            Command::new("gcc")
                .args(&flag_list)
                .arg("-I")
                .arg(lib.join("include"))
                .arg(&src)
                .arg(lib.join("liblwpr.a"))
                .args(["-lm", "-o"])
                .arg(&exe),
            &format!("compiling the harness ({flags})"),
        )?;
        out.push(Harness { key, exe });
    }
    Ok(out)
}

/// Reads the harness's JSON line; fails naming what was wrong.
pub fn parse(stdout: &str) -> Result<Measured> {
    let m: Measured = serde_json::from_str(stdout.trim())
        .with_context(|| format!("the harness printed no result: {:?}", stdout.trim()))?;
    ensure!(
        !m.nmse.is_empty()
            && [
                m.update_us,
                m.predict_us,
                m.update_us_batch,
                m.predict_us_batch
            ]
            .iter()
            .all(|t| t.is_finite()),
        "the harness printed an incomplete result: {stdout:?}"
    );
    Ok(m)
}

impl Harness {
    /// The C library on `file` (written from [`Samples::to_text`]).
    pub fn measure(&self, file: &Path) -> Result<Measured> {
        let out = run(
            Command::new(&self.exe).arg(file),
            &format!("the {} harness", self.key),
        )?;
        parse(&out)
    }
}

/// Writes `s` to `path` for the harness.
pub fn write_samples(s: &Samples, path: &Path) -> Result<()> {
    std::fs::write(path, s.to_text()).with_context(|| format!("writing {}", path.display()))
}
