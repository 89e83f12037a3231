//! `osrl report --from DIR/results.json [--out DIR]`: draws the page of a finished
//! `osrl reproduce` run again — every figure and `index.html` — from the data its folder holds
//! (`results.json`, `figures.json`, the time series as CSV), without running anything.

use anyhow::{bail, Context, Result};
use osrl_report::{render, Page};
use std::path::PathBuf;

#[derive(clap::Args, Debug)]
pub struct Args {
    /// The `results.json` of a report folder written by `osrl reproduce`.
    #[arg(long)]
    pub from: PathBuf,
    /// Where to draw the page (default: the folder of `--from`).
    #[arg(long)]
    pub out: Option<PathBuf>,
}

pub fn run(a: Args) -> Result<()> {
    if a.from.file_name().is_none_or(|n| n != "results.json") {
        bail!(
            "--from {}: give the results.json of a report folder",
            a.from.display()
        );
    }
    let dir = a.from.parent().map_or(PathBuf::from("."), |d| {
        if d.as_os_str().is_empty() {
            PathBuf::from(".")
        } else {
            d.to_path_buf()
        }
    });
    let page =
        Page::load(&dir).with_context(|| format!("reading the report folder {}", dir.display()))?;
    let out = a.out.unwrap_or(dir);
    crate::util::check_out_dir("--out", &out, &["index.html"], &[Some(&a.from)])?;
    osrl_files::check_output_tree(&out, &crate::util::PAGE_EXTENSIONS).context("--out")?;
    render(&out, &page)?;
    println!("wrote {}", out.join("index.html").display());
    Ok(())
}
