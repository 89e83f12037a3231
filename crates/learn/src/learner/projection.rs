//! The command projection (`controllers.command_projection`, `docs/decisions.md` D20): the
//! learned part `ū` of the command loses the share `κ_c` of its part in the null space of the
//! blended `Â`, `ū ← ū − κ_c (I − Â⁺Â) ū` — the same task acceleration to first order, in the
//! minimum-norm form of eq. 7's `u* − u0`. `Â` is blended with the command's own weights
//! (`Models::command_gain`, D32), so the projector moves continuously as fields enter the blend.

use super::metric::project_scratch_z;
use super::{Learner, State};

impl Learner {
    /// The command projection (`controllers.command_projection`): the learned part `ū` in `u`
    /// loses the share `κ_c` of its part in the null space of the `Â` blended at `q` with the
    /// command's weights (active fields in `ws.acts`); unchanged without an `Â` or with a
    /// singular `Â Âᵀ`.
    pub(super) fn project_command(&mut self, q: &[f64], u: &mut [f64]) {
        let kc = self.cfg.controllers.command_projection;
        if kc <= 0.0 || !self.cfg.experimental.residual || !self.command_gains(q).0 {
            return;
        }
        let State::Ready(models) = &self.state else {
            return;
        };
        let ws = &mut self.ws;
        ws.z.copy_from_slice(u);
        if project_scratch_z(models.metric.as_ref(), ws) {
            for (v, z) in u.iter_mut().zip(&ws.z) {
                *v -= kc * z;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::learner::fixture;

    /// `Â (u − u0)`, the null-space part under `Â` (the command's blend of it) of `u − u0` and
    /// `|u − u0|` for the command (no exploration) of `learner` at its last state with `κ_c = kc`.
    fn task_and_null(
        learner: &mut crate::Learner,
        last: &osrl_dynamics::Measurement,
        kc: f64,
    ) -> (Vec<f64>, f64, f64) {
        learner.cfg.controllers.command_projection = kc;
        let (q, qd) = (last.q.as_slice().to_vec(), last.qd.as_slice().to_vec());
        let (mut u, mut u0, mut a) = ([0.0; 3], [0.0; 3], [0.0; 6]);
        learner.start_episode(None).unwrap();
        learner
            .command::<rand_chacha::ChaCha8Rng>(&q, &qd, &[0.3, -0.2], None, &mut u)
            .unwrap();
        learner.nominal(&q, &qd, &mut u0).unwrap();
        let weights = (
            learner.cfg.partition.activation_cutoff,
            learner.cfg.controllers.trained_ess,
        );
        let features = learner.features;
        let models = fixture::models(learner);
        let mut acts = Vec::new();
        models
            .forward
            .activations(&q, &qd, weights.0, &mut acts)
            .unwrap();
        assert!(models.command_gain(&features, &acts, &q, weights, &mut a));
        let du: Vec<f64> = (0..3).map(|j| u[j] - u0[j]).collect();
        let task: Vec<f64> = (0..2)
            .map(|k| (0..3).map(|j| a[k * 3 + j] * du[j]).sum())
            .collect();
        // The null space of a 2×3 Â is spanned by the cross product of its rows.
        let (r0, r1) = (&a[..3], &a[3..]);
        let nv = [
            r0[1] * r1[2] - r0[2] * r1[1],
            r0[2] * r1[0] - r0[0] * r1[2],
            r0[0] * r1[1] - r0[1] * r1[0],
        ];
        let nn: f64 = nv.iter().map(|v| v * v).sum::<f64>().sqrt();
        let null = (0..3).map(|j| du[j] * nv[j] / nn).sum::<f64>();
        let norm = du.iter().map(|v| v * v).sum::<f64>().sqrt();
        (task, null.abs(), norm)
    }

    /// With `κ_c = 1` the learned part has no component in the null space of `Â` and the same
    /// `Â (u − u0)` as the plain blend (`κ_c = 0`) at the same state of the same learner: the
    /// projection changes the redundancy resolution, not the task.
    #[test]
    fn the_projected_command_keeps_the_task_part_and_drops_the_null_part() {
        let (mut learner, _, last) = fixture::ready(fixture::config(), 200, 2000);
        let (task0, null0, norm0) = task_and_null(&mut learner, &last, 0.0);
        let (task1, null1, norm1) = task_and_null(&mut learner, &last, 1.0);
        assert!(
            null0 > 1e-6 * norm0,
            "the plain blend has a null part: {null0}"
        );
        assert!(null1 <= 1e-9 * (1.0 + norm1), "{null1} vs |du| {norm1}");
        for (a, b) in task0.iter().zip(&task1) {
            assert!(
                (a - b).abs() <= 1e-9 * (1.0 + a.abs()),
                "{task0:?} vs {task1:?}"
            );
        }
    }

    /// The projection's `Â` has the command's weights: a field entering at the activation
    /// cutoff (`w = cutoff + δ`, where LWPR starts to report it and the command's blend gives it
    /// weight `δ`) moves it by O(δ), where the plain activation-weighted blend jumps by O(cutoff)
    /// — the step D32 removed; and a field whose controller is untrained (confidence 0) has no
    /// say in it at any activation.
    #[test]
    fn a_field_enters_the_projections_gain_continuously() {
        let (mut learner, _, last) = fixture::ready(fixture::config(), 200, 2000);
        let q = last.q.as_slice().to_vec();
        let cut = learner.cfg.partition.activation_cutoff;
        let weights = (cut, learner.cfg.controllers.trained_ess);
        let features = learner.features;
        let models = fixture::models(&mut learner);
        let mut acts = Vec::new();
        models
            .forward
            .activations(&q, last.qd.as_slice(), cut, &mut acts)
            .unwrap();
        // Two trained fields with fitted dynamics that are not active here.
        let far: Vec<_> = (models.locals.map.iter())
            .filter(|(id, l)| {
                l.dynamics_updates > 0
                    && crate::local::confidence(l.ess, weights.1) > 0.0
                    && !acts.iter().any(|a| a.id == **id)
            })
            .map(|(id, _)| *id)
            .take(2)
            .collect();
        assert_eq!(far.len(), 2, "two trained fields elsewhere");
        let gains = |models: &crate::learner::Models, acts: &[lwpr::Activation]| {
            let (mut a, mut b) = ([0.0; 6], [0.0; 6]);
            assert!(models.command_gain(&features, acts, &q, weights, &mut a));
            assert!(models.blended_gain(&features, acts, &q, &mut b));
            (a, b)
        };
        let diff = |x: &[f64; 6], y: &[f64; 6]| {
            (x.iter().zip(y))
                .map(|(u, v)| (u - v).abs())
                .fold(0.0, f64::max)
        };
        let (a0, b0) = gains(models, &acts);
        let size = a0.iter().map(|x| x.abs()).fold(0.0, f64::max);
        let delta = 1e-9;
        let mut entering = acts.clone();
        entering.push(lwpr::Activation {
            id: far[0],
            w: cut + delta,
        });
        let (a1, b1) = gains(models, &entering);
        assert!(diff(&a0, &a1) <= 1e-6 * size, "{a0:?} → {a1:?}");
        assert!(
            diff(&b0, &b1) > 1e-3 * size,
            "activation weights jump by {} (|Â| {size})",
            diff(&b0, &b1)
        );
        // An untrained controller's field, fully active: no say in the projection's Â.
        models.locals.map.get_mut(&far[1]).unwrap().ess = 0.0;
        let mut untrained = acts.clone();
        untrained.push(lwpr::Activation { id: far[1], w: 1.0 });
        let (a2, b2) = gains(models, &untrained);
        assert_eq!(a0, a2, "an untrained controller's field");
        assert!(diff(&b0, &b2) > 1e-3 * size);
    }

    /// The projected command (`κ_c` = 0.5, no exploration) along a straight line in `q`
    /// through the partition, in steps of 1e-5 rad, while fields enter and leave the blend:
    /// it changes by no more than the line's own slope allows — no step where a field joins
    /// the projector. (With the plain activation weights of D31 the largest step on this line
    /// is 0.086 N·m.)
    #[test]
    fn the_projected_command_is_continuous_where_fields_enter() {
        let (mut learner, _, last) = fixture::ready(fixture::config(), 200, 2000);
        assert_eq!(learner.cfg.controllers.command_projection, 0.5);
        let (q0, qd) = (last.q.as_slice().to_vec(), last.qd.as_slice().to_vec());
        let cut = learner.cfg.partition.activation_cutoff;
        let xdd = [0.3, -0.2];
        let (h, steps) = (1e-5, 20_000);
        let (mut u, mut prev) = ([0.0; 3], None::<[f64; 3]>);
        let (mut largest, mut changes, mut active) = (0.0_f64, 0, Vec::new());
        let mut acts = Vec::new();
        for k in 0..steps {
            let q: Vec<f64> = (0..3)
                .map(|j| q0[j] + [1.0, -0.6, 0.8][j] * h * k as f64)
                .collect();
            learner.start_episode(None).unwrap(); // no rate limit between the points
            learner
                .command::<rand_chacha::ChaCha8Rng>(&q, &qd, &xdd, None, &mut u)
                .unwrap();
            let models = fixture::models(&mut learner);
            models.forward.activations(&q, &qd, cut, &mut acts).unwrap();
            let mut ids: Vec<_> = acts.iter().map(|a| a.id).collect();
            ids.sort();
            if k > 0 && ids != active {
                changes += 1;
            }
            active = ids;
            if let Some(p) = prev {
                let d = (0..3).map(|j| (u[j] - p[j]).abs()).fold(0.0, f64::max);
                largest = largest.max(d);
            }
            prev = Some(u);
        }
        assert!(changes >= 2, "the line crosses {changes} field boundaries");
        // 0.2 rad of line: a slope of 500 N·m/rad would allow 5e-3 N·m per step.
        assert!(
            largest <= 5e-3,
            "largest step {largest} N·m over {changes} crossings"
        );
    }
}
