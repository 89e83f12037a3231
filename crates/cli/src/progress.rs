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

/// The progress of `osrl reproduce` (an [`osrl_experiments::Observer`]): notes above the bars,
/// one bar for the analytical runs, one per training run; without a terminal (CI, a log file)
/// one line per finished training run instead of its bar.
pub struct Bars {
    multi: MultiProgress,
    sizes: osrl_experiments::Sizes,
    analytical: std::sync::OnceLock<ProgressBar>,
    /// Each training run's bar and simulated minutes.
    jobs: std::sync::OnceLock<Vec<(ProgressBar, f64)>>,
}

impl Bars {
    pub fn new(sizes: &osrl_experiments::Sizes) -> Self {
        Self {
            multi: MultiProgress::new(),
            sizes: sizes.clone(),
            analytical: std::sync::OnceLock::new(),
            jobs: std::sync::OnceLock::new(),
        }
    }

    fn job(&self, i: usize) -> Option<&(ProgressBar, f64)> {
        self.jobs.get().and_then(|b| b.get(i))
    }
}

/// One line for a finished training run.
fn finished_line(r: &osrl_experiments::JobResult) -> String {
    use osrl_experiments::stats::measured;
    match &r.outcome {
        Ok(t) if measured(&t.eval) => format!(
            "tracking {:.3} mm, command nMSE {:.3}, {} local models, {:.0} s ({:.1}× real time){}",
            t.eval.tracking_rms_mm,
            t.eval.command_nmse,
            t.summary.n_local_models,
            t.summary.wall_seconds,
            t.summary.realtime_factor,
            if t.eval.diverged { ", diverged" } else { "" }
        ),
        Ok(t) => format!(
            "diverged in the evaluation's warm-up, {:.0} s",
            t.summary.wall_seconds
        ),
        Err(e) => format!("failed: {e}"),
    }
}

impl osrl_experiments::Observer for Bars {
    fn note(&self, text: &str) {
        let _ = self.multi.println(text);
    }
    fn analytical_started(&self, count: usize) {
        let _ = (self.analytical).set(job_bar(Some(&self.multi), "analytical E2/E7", count as u64));
    }
    fn analytical_done(&self, _case: &osrl_experiments::analytical::Case) {
        if let Some(b) = self.analytical.get() {
            b.inc(1);
            if b.position() == b.length().unwrap_or(0) {
                b.finish();
            }
        }
    }
    fn planned(&self, jobs: &[osrl_experiments::Job]) {
        let bars = jobs
            .iter()
            .map(|j| {
                let minutes = self.sizes.robot(j.robot).minutes;
                (train_bar(Some(&self.multi), &j.name(), minutes), minutes)
            })
            .collect();
        let _ = self.jobs.set(bars);
    }
    fn progress(&self, index: usize, p: &Progress) {
        if let Some((b, minutes)) = self.job(index) {
            update(b, *minutes, p);
        }
    }
    fn finished(&self, index: usize, r: &osrl_experiments::JobResult) {
        if let Some((b, _)) = self.job(index) {
            if b.is_hidden() {
                eprintln!("{}: {}", b.prefix(), finished_line(r));
            }
            b.finish();
        }
    }
}
