//! E8's table on the page: per robot and change, the learned controller on the unchanged arm,
//! frozen on the changed one, eq. 7 with the true and the stale model, and the re-adapting
//! controller's recovery times after the change and after its removal.

use crate::page::{num, table as html_table};
use osrl_experiments::analytical::ROBOTS;
use osrl_experiments::results::Results;

/// Minutes to a bound: `never` within the timeline for none.
pub fn minutes(v: Option<f64>) -> String {
    v.map_or("never".into(), |m| format!("{m:.2}"))
}

/// A tracking number of E8, `diverged` for none (its evaluation's error passed 0.2 m).
pub fn or_diverged(v: Option<f64>) -> String {
    v.map_or("diverged".into(), |x| num(Some(x)))
}

/// E8's table: per robot and change, the three controllers and the recovery times.
pub(crate) fn table(r: &Results) -> String {
    let mut rows = Vec::new();
    for rb in ROBOTS {
        for (k, v) in r.e8.get(rb).into_iter().flatten() {
            let a = v.after_removal.as_ref();
            rows.push(vec![
                rb.into(),
                format!("{k} ({})", v.change),
                or_diverged(v.nominal_tracking_rms_mm),
                or_diverged(v.frozen_tracking_rms_mm),
                match v.observer_frozen_tracking_rms_mm {
                    None if !v
                        .diverged
                        .iter()
                        .any(|d| d == "observer_frozen_tracking_rms_mm") =>
                    {
                        "—".into()
                    }
                    x => or_diverged(x),
                },
                format!(
                    "{} / {}",
                    or_diverged(v.eq7_nominal_tracking_rms_mm),
                    or_diverged(v.eq7_stale_tracking_rms_mm)
                ),
                format!(
                    "{} / {}",
                    minutes(v.minutes_to_1mm),
                    minutes(v.minutes_to_1mm_stable)
                ),
                format!(
                    "{} / {}",
                    minutes(v.minutes_to_2x_nominal),
                    minutes(v.minutes_to_2x_nominal_stable)
                ),
                format!(
                    "{} / {}",
                    or_diverged(v.adapted_tracking_rms_mm),
                    or_diverged(v.adapted_command_nmse)
                ),
                a.map_or("—".into(), |a| minutes(a.minutes_to_1mm)),
                a.map_or("—".into(), |a| minutes(a.minutes_to_2x_nominal)),
                a.map_or("—".into(), |a| or_diverged(a.tracking_rms_mm)),
                format!(
                    "{} / {} / {}",
                    v.aborted_episodes, v.braked_episodes, v.rollbacks
                ),
            ]);
        }
    }
    let head = [
        "robot",
        "change",
        "learned, unchanged arm [mm]",
        "frozen, changed [mm]",
        "frozen + observer, changed [mm]",
        "eq. 7 true / stale model [mm]",
        "re-adapting: to ≤ 1 mm, first / for good [min]",
        "to ≤ 2× nominal, first / for good [min]",
        "at the end of the change [mm] / nMSE",
        "after removal: to ≤ 1 mm [min]",
        "to ≤ 2× nominal [min]",
        "at the end [mm]",
        "aborted / braked episodes / rollbacks",
    ];
    html_table(&head, &rows)
}
