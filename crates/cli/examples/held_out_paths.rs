//! Writes E9's held-out paths of a robot's family as `[trajectory]` files that
//! `osrl eval --model M --config F` evaluates (`docs/family.md`):
//!
//! ```sh
//! cargo run --release -p osrl-cli --example held_out_paths -- planar3 2 /tmp/paths
//! osrl eval --model planar3.osrl --config /tmp/paths/planar3-0.toml --json
//! ```
//!
//! Arguments: robot (`planar3`, `sarcos7`), paths per kind, output folder (created; existing
//! files of the same names are replaced).

use anyhow::{bail, Context, Result};
use osrl_experiments::family::{held_out, label};
use osrl_experiments::Setup;

fn main() -> Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [robot, per_kind, out] = args.as_slice() else {
        bail!("usage: held_out_paths ROBOT PATHS_PER_KIND OUT_DIR");
    };
    let per_kind: usize = per_kind
        .parse()
        .ok()
        .filter(|n| (1..=20).contains(n))
        .context("PATHS_PER_KIND: a whole number from 1 to 20")?;
    let setup = Setup::new(robot)?;
    let out = std::path::Path::new(out);
    std::fs::create_dir_all(out).with_context(|| out.display().to_string())?;
    for (i, p) in held_out(&setup, per_kind)?.iter().enumerate() {
        #[derive(serde::Serialize)]
        struct File<'a> {
            trajectory: &'a osrl_control::TrajectoryConfig,
        }
        let text = format!(
            "# {}\n{}",
            label(p),
            toml::to_string(&File {
                trajectory: &p.config
            })?
        );
        let file = out.join(format!("{robot}-{i}.toml"));
        osrl_files::write_atomic(&file, text.as_bytes())?;
        println!("{}\t{}", file.display(), label(p));
    }
    Ok(())
}
