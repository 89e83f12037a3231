//! E9, generalisation over the workspace (`docs/family.md`): controllers trained on the
//! figure-8 only (E3's runs) and on the family of paths, each evaluated on held-out paths drawn
//! with a seed no training used, against issue 27's bounds.

use crate::jobs::JobResult;
use crate::results::ByRobot;
use osrl_learn::eval::EvalResult;
use serde::{Deserialize, Serialize};

/// One controller's evaluation on one path.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct E9Point {
    pub seed: u64,
    pub tracking_rms_mm: f64,
    pub command_nmse: f64,
    /// Share of the evaluation inside trained receptive fields.
    pub support_share: f64,
    pub diverged: bool,
}

impl E9Point {
    /// The point of an evaluation `e` of the controller trained with `seed`.
    pub fn new(seed: u64, e: &EvalResult) -> Self {
        Self {
            seed,
            tracking_rms_mm: e.tracking_rms_mm,
            command_nmse: e.command_nmse,
            support_share: e.support_share,
            diverged: e.diverged,
        }
    }
}

/// One held-out path.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct E9Path {
    pub label: String,
    /// Per seed: the figure-8-only controller and the family-trained one.
    pub figure8_only: Vec<E9Point>,
    pub family: Vec<E9Point>,
    /// Per seed of `family`: whether it met issue 27's bounds here — tracking ≤ 1.5× and
    /// nMSE ≤ 2× the figure-8-only controller's (same seed) on its own figure-8, and ≤ 1 mm,
    /// ≤ 0.05 absolute.
    pub family_within_bounds: Vec<bool>,
}

/// E9 for one robot.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct E9Row {
    /// The E9 seeds that finished both runs.
    pub seeds: Vec<u64>,
    /// Each controller on the default figure-8 (its final evaluation), per seed.
    pub figure8_only_on_figure8: Vec<E9Point>,
    pub family_on_figure8: Vec<E9Point>,
    pub paths: Vec<E9Path>,
    /// Runs that failed, with their errors.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub failed: Vec<String>,
}

/// E9 per robot from the finished jobs (robots without E9 runs are left out).
pub fn e9(done: &[JobResult]) -> ByRobot<E9Row> {
    let mut out = ByRobot::new();
    for robot in crate::analytical::ROBOTS {
        // The family runs (finished or not), and the figure-8-only runs evaluated on the
        // held-out paths.
        let fam: Vec<_> = (done.iter())
            .filter(|j| j.job.robot == robot && j.job.family)
            .collect();
        let f8: Vec<_> = (done.iter())
            .filter(|j| j.job.robot == robot && !j.job.family)
            .filter(|j| j.outcome.as_ref().is_ok_and(|t| t.held_out.is_some()))
            .collect();
        if fam.is_empty() {
            continue;
        }
        let mut row = E9Row {
            seeds: Vec::new(),
            figure8_only_on_figure8: Vec::new(),
            family_on_figure8: Vec::new(),
            paths: Vec::new(),
            failed: (fam.iter())
                .filter_map(|j| {
                    j.outcome
                        .as_ref()
                        .err()
                        .map(|e| format!("{}: {e}", j.job.name()))
                })
                .collect(),
        };
        for f in &fam {
            let Ok(ft) = &f.outcome else { continue };
            let Some(gt) = (f8.iter())
                .find(|g| g.job.seed == f.job.seed)
                .and_then(|g| g.outcome.as_ref().ok())
            else {
                continue;
            };
            let (Some(fh), Some(gh)) = (&ft.held_out, &gt.held_out) else {
                continue;
            };
            let seed = f.job.seed;
            row.seeds.push(seed);
            let own = E9Point::new(seed, &gt.eval);
            row.figure8_only_on_figure8.push(own.clone());
            row.family_on_figure8.push(E9Point::new(seed, &ft.eval));
            for (k, ((label, fe), (_, ge))) in fh.iter().zip(gh).enumerate() {
                if row.paths.len() <= k {
                    row.paths.push(E9Path {
                        label: label.clone(),
                        figure8_only: Vec::new(),
                        family: Vec::new(),
                        family_within_bounds: Vec::new(),
                    });
                }
                let p = &mut row.paths[k];
                let fp = E9Point::new(seed, fe);
                p.family_within_bounds.push(within_bounds(&fp, &own));
                p.family.push(fp);
                p.figure8_only.push(E9Point::new(seed, ge));
            }
        }
        out.insert(robot.to_string(), row);
    }
    out
}

/// Issue 27's bounds: `p` tracks within 1.5× and 1 mm, and its nMSE is within 2× and 0.05,
/// of the figure-8-only controller on its own figure-8 (`own`).
pub fn within_bounds(p: &E9Point, own: &E9Point) -> bool {
    !p.diverged
        && p.tracking_rms_mm <= (1.5 * own.tracking_rms_mm).min(1.0)
        && p.command_nmse <= (2.0 * own.command_nmse).min(0.05)
}
