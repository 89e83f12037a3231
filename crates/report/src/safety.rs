//! The learning-safety table of the page (E5): per robot and seed, the aborted and braked
//! episodes, clipped and rate-limited commands, fallbacks, the largest command step and torque
//! rate next to eq. 7's, and the minutes to 1 mm and to command nMSE 0.05.

use crate::page::num;
use osrl_experiments::analytical::ROBOTS;
use osrl_experiments::results::Results;
use osrl_experiments::stats::Outcome;

/// The table of every E3 run's [`SafetyRow`](osrl_experiments::results::SafetyRow).
pub(crate) fn table(r: &Results) -> String {
    let mut rows = Vec::new();
    for rb in ROBOTS {
        let Some(row) = r.e3.get(rb).and_then(Outcome::done) else {
            continue;
        };
        for (i, s) in row.summary.safety.iter().enumerate() {
            let seed = r.seeds.get(i).map_or("—".into(), |s| s.to_string());
            rows.push(vec![
                rb.to_string(),
                seed,
                s.aborted_episodes.to_string(),
                s.braked_episodes.to_string(),
                s.clipped_on_policy.to_string(),
                s.fallbacks.to_string(),
                s.rate_limited.to_string(),
                format!(
                    "{} ({})",
                    num(Some(s.max_command_step)),
                    num(Some(s.max_command_step_analytical))
                ),
                num(Some(s.max_torque_rate)),
                num(s.minutes_to_1mm),
                num(s.minutes_to_nmse_0_05),
            ]);
        }
    }
    let head = [
        "robot",
        "seed",
        "aborted episodes",
        "braked episodes",
        "clipped on-policy",
        "fallbacks to u0",
        "rate-limited",
        "largest command step [N·m] (eq. 7's)",
        "largest torque rate [N·m/s]",
        "minutes to 1 mm",
        "minutes to nMSE 0.05",
    ];
    crate::page::table(&head, &rows)
}
