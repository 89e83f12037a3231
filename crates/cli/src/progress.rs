//! Progress bars (stderr, indicatif) for training runs: simulated minutes, the latest tracking
//! error and command nMSE, the number of local models. Hidden when stderr is not a terminal.

use indicatif::{MultiProgress, ProgressBar, ProgressStyle};
use osrl_learn::train::Progress;

/// Bar units per simulated minute (the bar counts hundredths of a minute).
const UNITS: f64 = 100.0;

/// A bar for a training run of `minutes` simulated minutes, labelled `prefix`, added to `multi`
/// when given.
pub fn train_bar(multi: Option<&MultiProgress>, prefix: &str, minutes: f64) -> ProgressBar {
    let bar = ProgressBar::new((minutes * UNITS).round().max(1.0) as u64);
    let bar = match multi {
        Some(m) => m.add(bar),
        None => bar,
    };
    bar.set_style(
        ProgressStyle::with_template("{prefix:>16} [{bar:24}] {elapsed:>4} {msg}")
            .expect("valid template")
            .progress_chars("=> "),
    );
    bar.set_prefix(prefix.to_string());
    bar.set_message(format!("0.0/{minutes:.1} sim min"));
    bar
}

/// Moves `bar` to the progress of a training run.
pub fn update(bar: &ProgressBar, minutes: f64, p: &Progress) {
    bar.set_position((p.sim_minutes * UNITS).round() as u64);
    let eval = p.eval.as_ref().map_or(String::new(), |e| {
        format!(
            " · track {:.2} mm · nMSE {:.3}",
            e.tracking_rms_mm, e.command_nmse
        )
    });
    bar.set_message(format!(
        "{:.1}/{minutes:.1} sim min · {}{eval} · {} local models",
        p.sim_minutes, p.phase, p.n_local_models
    ));
}

/// A plain counter bar for a list of `len` jobs.
pub fn job_bar(multi: Option<&MultiProgress>, prefix: &str, len: u64) -> ProgressBar {
    let bar = ProgressBar::new(len);
    let bar = match multi {
        Some(m) => m.add(bar),
        None => bar,
    };
    bar.set_style(
        ProgressStyle::with_template("{prefix:>16} [{bar:24}] {pos}/{len} {elapsed:>4} {msg}")
            .expect("valid template")
            .progress_chars("=> "),
    );
    bar.set_prefix(prefix.to_string());
    bar
}
