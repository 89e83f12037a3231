//! The default home posture: a well-conditioned posture inside the joint limits.
//!
//! Candidates are 3,000 seeded samples inside the limits (0.1 rad margin; continuous joints in
//! [−π, π], unlimited prismatic joints at 0). A candidate is admissible when the tip, seen from
//! the first joint along the task axes, is at 40–75 % of the arm's reach and — for an arm whose
//! task has a horizontal and the vertical axis — in front of the base (horizontally at least
//! 35 % of the reach away, vertically within ±35 %), and when gravity needs at most half of every
//! joint's torque limit. Admissible candidates are ranked by
//! `ln(w / Rᵐ) + (1/n) Σ ln(4 (q − q_min)(q_max − q) / (q_max − q_min)²)`
//! (`w = √det(J Jᵀ)` the manipulability of the task rows, `R` the reach, the second term 0 at
//! mid-range and −∞ at a limit), and the best few are refined by a coordinate search.

use crate::error::Result;
use nalgebra::DMatrix;
use osrl_dynamics::{gravity, jacobian, Data, Model};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Samples drawn.
const SAMPLES: usize = 3000;
/// Margin kept from the joint limits while sampling (rad or m).
const MARGIN: f64 = 0.1;
/// Admissible tip distance from the first joint, as fractions of the reach.
const DISTANCE: (f64, f64) = (0.40, 0.75);
/// Smallest horizontal distance and largest height difference of the tip, fractions of reach.
const FRONT: (f64, f64) = (0.35, 0.35);
/// Largest share of a torque limit that gravity may take at home.
const GRAVITY_SHARE: f64 = 0.5;

/// What the search found: admissible postures, best first.
pub(super) struct Homes {
    pub candidates: Vec<Vec<f64>>,
    /// Why the first rejected samples were rejected (for the error when none is admissible).
    pub rejected: String,
}

/// Sampling box of each joint.
fn sampling_box(model: &Model) -> Vec<(f64, f64)> {
    model
        .links()
        .iter()
        .map(|l| {
            let (lo, hi) = (l.limits.q_min, l.limits.q_max);
            let (lo, hi) = match (lo.is_finite(), hi.is_finite()) {
                (true, true) => (lo, hi),
                _ if l.kind == osrl_dynamics::JointKind::Revolute => {
                    (lo.max(-std::f64::consts::PI), hi.min(std::f64::consts::PI))
                }
                _ => (0f64.clamp(lo, hi), 0f64.clamp(lo, hi)),
            };
            if hi - lo > 2.0 * MARGIN {
                (lo + MARGIN, hi - MARGIN)
            } else {
                let mid = 0.5 * (lo + hi);
                (mid, mid)
            }
        })
        .collect()
}

/// Scores postures of one model.
pub(super) struct Scorer<'a> {
    model: &'a Model,
    data: Data,
    tau_max: &'a [f64],
    pub reach: f64,
}

impl<'a> Scorer<'a> {
    pub fn new(model: &'a Model, tau_max: &'a [f64]) -> Self {
        Self {
            model,
            data: model.data(),
            tau_max,
            reach: 0.0,
        }
    }

    /// Tip minus first joint, on the task axes (others 0).
    pub fn offset(&mut self, q: &[f64]) -> Result<nalgebra::Vector3<f64>> {
        jacobian(self.model, &mut self.data, q)?;
        let base = self.model.links()[0].origin.trans;
        let mut d = nalgebra::Vector3::zeros();
        for &a in self.model.task_axes() {
            d[a] = self.data.ee_pos[a] - base[a];
        }
        Ok(d)
    }

    /// The score, or why `q` is not admissible.
    pub fn score(&mut self, q: &[f64]) -> Result<std::result::Result<f64, String>> {
        let d = self.offset(q)?;
        let (r, axes) = (self.reach, self.model.task_axes());
        let dist = d.norm();
        if dist < DISTANCE.0 * r || dist > DISTANCE.1 * r {
            return Ok(Err(format!(
                "tip {:.0} % of the reach away",
                100.0 * dist / r
            )));
        }
        if axes.contains(&2) && (axes.contains(&0) || axes.contains(&1)) {
            let h = (d.x * d.x + d.y * d.y).sqrt();
            if h < FRONT.0 * r || d.z.abs() > FRONT.1 * r {
                return Ok(Err("tip not in front of the base".into()));
            }
        }
        let m = axes.len();
        let j = DMatrix::from_fn(m, self.model.nq(), |row, c| self.data.jac[(axes[row], c)]);
        let det = (&j * j.transpose()).determinant();
        if det.is_nan() || det <= 0.0 {
            return Ok(Err("singular".into()));
        }
        let g = gravity(self.model, &mut self.data, q)?;
        if let Some(i) = (0..q.len()).find(|&i| g[i].abs() > GRAVITY_SHARE * self.tau_max[i]) {
            return Ok(Err(format!(
                "gravity {:.1} at joint '{}' exceeds half its limit {}",
                g[i],
                self.model.links()[i].joint_name,
                self.tau_max[i]
            )));
        }
        let mut limits = 0.0;
        for (l, &v) in self.model.links().iter().zip(q) {
            let (lo, hi) = (l.limits.q_min, l.limits.q_max);
            if lo.is_finite() && hi.is_finite() && hi > lo {
                limits += (4.0 * (v - lo) * (hi - v) / (hi - lo).powi(2)).ln();
            }
        }
        let manip = 0.5 * det.ln() - m as f64 * r.ln();
        Ok(Ok(manip + limits / q.len() as f64))
    }
}

/// Improves `q` by a coordinate search on the score (admissible postures only, inside the box).
fn refine(scorer: &mut Scorer, q: &mut [f64], boxes: &[(f64, f64)]) -> Result<f64> {
    let mut best = scorer.score(q)?.unwrap_or(f64::NEG_INFINITY);
    for step in [0.2, 0.1, 0.05, 0.02, 0.01] {
        for _ in 0..20 {
            let mut improved = false;
            for i in 0..q.len() {
                for s in [step, -step] {
                    let old = q[i];
                    q[i] = (old + s).clamp(boxes[i].0, boxes[i].1);
                    match scorer.score(q)? {
                        Ok(v) if v > best + 1e-12 => {
                            best = v;
                            improved = true;
                        }
                        _ => q[i] = old,
                    }
                }
            }
            if !improved {
                break;
            }
        }
    }
    Ok(best)
}

/// The seeded samples: the middle of the box, then [`SAMPLES`] uniform draws.
fn samples(boxes: &[(f64, f64)]) -> Vec<Vec<f64>> {
    let mut rng = ChaCha8Rng::seed_from_u64(0);
    let mut samples: Vec<Vec<f64>> = vec![boxes.iter().map(|b| 0.5 * (b.0 + b.1)).collect()];
    samples.extend((0..SAMPLES).map(|_| {
        boxes
            .iter()
            .map(|&(lo, hi)| {
                if hi > lo {
                    rng.random_range(lo..hi)
                } else {
                    lo
                }
            })
            .collect()
    }));
    samples
}

/// The arm's reach (m): the largest distance of the tip from the first joint, along the task
/// axes, over the seeded samples inside the limits.
pub(super) fn reach(model: &Model) -> Result<f64> {
    let tau = vec![f64::INFINITY; model.nq()];
    let mut scorer = Scorer::new(model, &tau);
    let mut reach: f64 = 0.0;
    for q in &samples(&sampling_box(model)) {
        reach = reach.max(scorer.offset(q)?.norm());
    }
    Ok(reach)
}

/// Up to `keep` admissible home postures, best first (module docs). Deterministic.
pub(super) fn search(model: &Model, tau_max: &[f64], keep: usize) -> Result<Homes> {
    let boxes = sampling_box(model);
    let samples = samples(&boxes);
    let mut scorer = Scorer::new(model, tau_max);
    scorer.reach = reach(model)?;
    let mut ranked = Vec::new();
    let mut rejected = std::collections::BTreeMap::<String, usize>::new();
    for q in samples {
        match scorer.score(&q)? {
            Ok(s) => ranked.push((s, q)),
            Err(why) => {
                let key = why.split(" at joint").next().unwrap_or("").to_string();
                if key.starts_with("gravity") {
                    *rejected.entry(why).or_default() += 1;
                } else {
                    *rejected.entry(key).or_default() += 1;
                }
            }
        }
    }
    ranked.sort_by(|a, b| b.0.total_cmp(&a.0));
    let mut candidates: Vec<(f64, Vec<f64>)> = Vec::new();
    for (_, mut q) in ranked.into_iter().take(keep * 3) {
        let s = refine(&mut scorer, &mut q, &boxes)?;
        let distinct = candidates.iter().all(|(_, c)| {
            c.iter()
                .zip(&q)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max)
                > 0.05
        });
        if distinct {
            candidates.push((s, q));
        }
    }
    candidates.sort_by(|a, b| b.0.total_cmp(&a.0));
    candidates.truncate(keep);
    let mut worst: Vec<(usize, String)> = rejected.into_iter().map(|(k, v)| (v, k)).collect();
    worst.sort_by_key(|w| std::cmp::Reverse(w.0));
    let rejected = worst
        .iter()
        .take(3)
        .map(|(n, why)| format!("{n} × {why}"))
        .collect::<Vec<_>>()
        .join("; ");
    Ok(Homes {
        candidates: candidates.into_iter().map(|(_, q)| q).collect(),
        rejected,
    })
}
