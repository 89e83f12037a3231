//! The sizes of the experiments (`osrl reproduce`): one struct with the full and the `--quick`
//! values, recorded in `results.json` under `config.sizes`.

use serde::{Deserialize, Serialize};

/// Training size of one robot.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RobotSizes {
    /// Simulated training minutes, babbling included.
    pub minutes: f64,
    /// Babbling minutes; `None` = the training driver's default.
    pub babble_minutes: Option<f64>,
    /// Evaluate (learning-curve point) every this many simulated minutes.
    pub eval_every_minutes: f64,
}

/// Everything the experiments scale.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Sizes {
    /// Seeds per case of the RWR toy problem (E1).
    pub toy_seeds: u64,
    /// Training seeds of the learned controller per robot (E3, E5; E4 shows seed 0).
    pub learned_seeds: u64,
    /// Training seeds per ablation variant and robot (E6) and per payload run (E7).
    pub ablation_seeds: u64,
    /// Simulated seconds of each analytical run (E2, E7), whole periods, the first a warm-up.
    pub analytical_seconds: f64,
    /// Evaluated periods of the trajectory per evaluation of a learned controller (after one
    /// warm-up period).
    pub eval_periods: usize,
    /// Unmodelled payload of E7 (kg).
    pub payload_kg: f64,
    /// Postures drawn along the figure-8 in the arm drawing (Fig. 2a).
    pub arm_instants: usize,
    /// Training sizes of the 3-DOF planar arm.
    pub planar3: RobotSizes,
    /// Training sizes of the 7-DOF SARCOS arm.
    pub sarcos7: RobotSizes,
    /// The timeline of E8 (absent in files written before E8: the quick size's).
    #[serde(default = "ChangeSizes::quick")]
    pub e8: ChangeSizes,
    /// The generalisation experiment (E9).
    #[serde(default)]
    pub e9: E9Sizes,
}

/// Sizes of E9: family-trained controllers (and the figure-8-only ones of the same seeds, E3's)
/// evaluated on held-out paths. Default: none (E9 off).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct E9Sizes {
    /// Seeds trained on the family (and evaluated on the held-out paths) per robot: planar3's
    /// and sarcos7's, at most `learned_seeds`.
    pub planar3_seeds: u64,
    pub sarcos7_seeds: u64,
    /// Held-out paths per kind (figure-8, circle, minimum-jerk).
    pub paths_per_kind: usize,
}

impl E9Sizes {
    /// The E9 seeds of a robot by name.
    pub fn seeds(&self, robot: &str) -> u64 {
        if robot == "sarcos7" {
            self.sarcos7_seeds
        } else {
            self.planar3_seeds
        }
    }
}

/// The timeline of E8 (a controller trained on the unchanged arm keeps tracking while the robot
/// changes): simulated minutes.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ChangeSizes {
    /// Tracking on the unchanged arm before the change.
    pub nominal_minutes: f64,
    /// With the change (the payload is removed after them; masses and friction stay changed).
    pub changed_minutes: f64,
    /// After the payload is removed.
    pub after_minutes: f64,
    /// Evaluate every this many simulated minutes (issue 26: at least 4 points a minute).
    pub eval_every_minutes: f64,
}

impl ChangeSizes {
    /// The full run: the 10 minutes of adaptation, 3 after the removal.
    pub fn full() -> Self {
        Self {
            nominal_minutes: 1.0,
            changed_minutes: 10.0,
            after_minutes: 3.0,
            eval_every_minutes: 0.25,
        }
    }

    /// `--quick`: half a minute nominal, 1.5 with the change, 1 after.
    pub fn quick() -> Self {
        Self {
            nominal_minutes: 0.5,
            changed_minutes: 1.5,
            after_minutes: 1.0,
            eval_every_minutes: 0.25,
        }
    }
}

impl Sizes {
    /// The full run (the paper's training times: 30 min planar3, 60 min sarcos7; issue 6's
    /// three seeds).
    pub fn full() -> Self {
        Self {
            toy_seeds: 30,
            learned_seeds: 3,
            ablation_seeds: 1,
            analytical_seconds: 12.0,
            eval_periods: 2,
            payload_kg: 0.5,
            arm_instants: 6,
            planar3: RobotSizes {
                minutes: 30.0,
                babble_minutes: None,
                eval_every_minutes: 2.0,
            },
            sarcos7: RobotSizes {
                minutes: 60.0,
                babble_minutes: None,
                eval_every_minutes: 4.0,
            },
            e8: ChangeSizes::full(),
            e9: E9Sizes {
                planar3_seeds: 3,
                sarcos7_seeds: 3,
                paths_per_kind: 2,
            },
        }
    }

    /// `--quick`: everything small (CI, under 3 minutes on 2 cores).
    pub fn quick() -> Self {
        Self {
            toy_seeds: 5,
            learned_seeds: 2,
            ablation_seeds: 1,
            analytical_seconds: 8.0,
            eval_periods: 1,
            payload_kg: 0.5,
            arm_instants: 6,
            planar3: RobotSizes {
                minutes: 5.0,
                babble_minutes: Some(2.0),
                eval_every_minutes: 1.0,
            },
            sarcos7: RobotSizes {
                minutes: 8.0,
                babble_minutes: None,
                eval_every_minutes: 1.0,
            },
            e8: ChangeSizes::quick(),
            e9: E9Sizes {
                planar3_seeds: 1,
                sarcos7_seeds: 0,
                paths_per_kind: 1,
            },
        }
    }

    /// The sizes of a robot by name (`sarcos7`; any other name: `planar3`'s).
    pub fn robot(&self, name: &str) -> &RobotSizes {
        if name == "sarcos7" {
            &self.sarcos7
        } else {
            &self.planar3
        }
    }
}
