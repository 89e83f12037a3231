"""Type stubs of the native module ``osrl._osrl`` (crates/py). Import from ``osrl``.

Array arguments are float64 numpy arrays of the documented shape (any strides) or lists of
numbers; another dtype, shape or a non-finite value raises ``ValueError`` and changes nothing.
Results are new float64 arrays.
"""

from os import PathLike
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

ArrayLike1 = Union[npt.NDArray[np.float64], Sequence[float]]
ArrayLike2 = Union[npt.NDArray[np.float64], Sequence[Sequence[float]]]
Array = npt.NDArray[np.float64]
Path = Union[str, "PathLike[str]"]

__version__: str
MAX_NORMALISED: float
"""Largest magnitude of a normalised input or output that ``Lwpr.update`` accepts (1e40)."""
MAX_BATCH_VALUES: int
"""Most values (rows × columns) of a batch's copy or result that ``Lwpr.update_batch`` and
``Lwpr.predict_batch`` take: 2**31 float64 values, 16 GiB. A larger batch (e.g. a broadcast view
``np.broadcast_to(x, (10**12, n))``) raises ``ValueError`` before anything is allocated, and an
allocation within it that fails raises ``MemoryError``; split large batches."""

class NoSupportError(ValueError):
    """No trustworthy receptive field is active at this input (for some output)."""

class Lwpr:
    """An incremental LWPR model mapping ``n_in`` inputs to ``n_out`` outputs (the Rust crate
    ``lwpr``: the reference library's algorithm, plus shared receptive fields and kernels on a
    subset of the inputs).

    Keyword arguments are the crate's config keys (``lwpr::LwprConfig``; defaults are the
    reference library's): ``init_d`` (number, list for a diagonal, or list of rows),
    ``init_alpha``, ``diag_only``, ``update_d``, ``meta``, ``meta_rate``, ``penalty``,
    ``w_gen``, ``w_prune``, ``prune_rule`` ("wider" | "narrower"), ``init_lambda``,
    ``final_lambda``, ``tau_lambda``, ``init_s2``, ``add_threshold``, ``kernel``
    ("gaussian" | "bisquare"), ``norm_in``, ``norm_out`` (number or one per dimension; "std"
    must be resolved by the caller, e.g. ``norm_in=X.std(axis=0)``), ``cutoff``,
    ``shared_rfs``, ``kernel_dims``, ``regression_dims``. An unknown key raises ``TypeError``,
    a bad value ``ValueError``. A config value nested more than 64 lists or dicts deep (a list
    that contains itself) raises ``ValueError`` naming its key path. ``n_in`` and ``n_out`` are
    integers ≥ 0 (``ValueError`` naming the argument for a negative one, ``TypeError`` for a
    float).

    Single-sample calls hold the GIL (about a microsecond each); batches, ``save`` and
    ``load`` release it. Not for concurrent use from several threads (a second call while one
    runs raises ``RuntimeError``).
    """

    def __init__(self, n_in: int, n_out: int, **config: Any) -> None: ...
    def update(self, x: ArrayLike1, y: ArrayLike1) -> Array:
        """Learns from one sample (``x``: ``(n_in,)``, ``y``: ``(n_out,)``); returns the
        prediction of the receptive fields this sample updated, after their update, ``(n_out,)``
        (the reference library's ``lwpr_update`` ``yp``: each trustworthy updated field's
        prediction once its regression has learned from the sample, blended by the activations;
        NaN for an output where no trustworthy receptive field was updated). It is not the
        prediction before learning (``predict(x)`` before the call): it is already pulled
        towards ``y``. Raises ``ValueError`` (nothing learned) on a
        bad shape or dtype, a non-finite value, or a value beyond ``MAX_NORMALISED`` once
        divided by its normalisation."""
    def update_batch(self, X: ArrayLike2, Y: ArrayLike2) -> Array:
        """Learns from the rows of ``X`` ``(N, n_in)`` and ``Y`` ``(N, n_out)`` (a 1-D ``Y``
        when ``n_out == 1``) in order, the same as ``update`` row by row; returns each update's
        prediction as ``update`` does, ``(N, n_out)``. The whole batch is checked first: an
        error learns nothing. At most ``MAX_BATCH_VALUES`` values per batch."""
    def predict(self, x: ArrayLike1, *, strict: bool = True) -> Array:
        """The prediction at ``x``, ``(n_out,)``. Raises ``NoSupportError`` where no
        trustworthy receptive field is active, unless ``strict=False`` (then 0 for that
        output, as the reference library does)."""
    def predict_batch(self, X: ArrayLike2, *, strict: bool = True) -> Array:
        """``predict`` of every row of ``X`` ``(N, n_in)``: ``(N, n_out)``. At most
        ``MAX_BATCH_VALUES`` values per batch (its copy and its result)."""
    def predict_conf(self, x: ArrayLike1) -> Tuple[Array, Array]:
        """``(y, conf)``: the prediction and its confidence bound per output (output units,
        the reference library's ``sqrt(Σ w σ²_k + Σ w (ŷ_k − ŷ)²) / Σ w``)."""
    def jacobian(self, x: ArrayLike1) -> Array:
        """The Jacobian ``∂ŷ/∂x`` at ``x``, ``(n_out, n_in)``."""
    @property
    def n_rfs(self) -> List[int]:
        """Receptive fields per sub-model (one per output, or one when ``shared_rfs``)."""
    @property
    def n_in(self) -> int: ...
    @property
    def n_out(self) -> int: ...
    @property
    def n_updates(self) -> int: ...
    @property
    def config(self) -> Dict[str, Any]:
        """Every config key with its value (``Lwpr(n_in, n_out, **m.config)`` is the same
        config)."""
    @property
    def warnings(self) -> Dict[str, int]:
        """How often the update's numerical guards stepped in: ``metric_skipped``,
        ``removed_non_finite``."""
    def save(self, path: Path) -> None:
        """Writes the model (bit-exact; the format of ``osrl lwpr fit --save``) through a new
        file renamed into place. Refuses to replace a folder, a link or a device
        (``OSError``)."""
    @staticmethod
    def load(path: Path) -> "Lwpr":
        """Reads a saved model; ``ValueError`` for a corrupted or truncated file, ``OSError``
        (``FileNotFoundError``, ...) for the file system."""
    def to_bytes(self) -> bytes:
        """The model in the file format of ``save``."""
    @staticmethod
    def from_bytes(data: bytes) -> "Lwpr": ...

class Robot:
    """A serial robot arm of revolute joints (the Rust crate ``osrl-dynamics``): a built-in
    robot or a URDF, with its dynamics on numpy arrays. World frame z up, gravity 9.81 m/s²
    along −z; ``M(q) q̈ + h(q, q̇) = u`` with ``h = C q̇ + g + τ_f``. The end effector is the
    task point; ``task_axes`` are the world axes of its position that form the task space.

    Every method raises ``ValueError`` for a result that is not finite (inputs so large that the
    computation overflows float64, e.g. ``rnea(q, np.full(n, 1e200), qdd)``), naming the method
    and the input most likely to blame, instead of returning NaN or inf.
    """

    @staticmethod
    def builtin(name: str) -> "Robot":
        """A built-in robot (``Robot.builtins()``: planar3, sarcos7); ``ValueError`` for
        another name."""
    @staticmethod
    def builtins() -> List[str]: ...
    @staticmethod
    def from_urdf(path: Path, tip: Optional[str] = None) -> "Robot":
        """A robot from a URDF file: the serial chain from the root to the end-effector link
        ``tip`` (its origin is the task point; the joints beyond it and off the chain are held
        rigid). ``tip=None``: the loader's naming rule chooses it (``tcp``, ``ee_link``,
        ``tool0``, ... as in ``osrl robot --urdf F``; else the link moved by the last joint),
        as ``osrl``'s ``--tip`` does. ``ValueError`` naming the file for an invalid URDF or a
        ``tip`` that is not one of its links; ``OSError`` for the file system."""
    @staticmethod
    def from_urdf_string(text: str, tip: Optional[str] = None) -> "Robot":
        """``from_urdf`` of URDF text."""
    def to_urdf(self) -> str:
        """The model as URDF (what ``osrl robot --robot NAME --urdf`` prints)."""
    @property
    def name(self) -> str: ...
    @property
    def dof(self) -> int:
        """Number of joints ``n``."""
    @property
    def task_dim(self) -> int: ...
    @property
    def task_axes(self) -> List[int]: ...
    @property
    def joint_names(self) -> List[str]: ...
    @property
    def q_min(self) -> Array:
        """Lower joint limits (rad; −inf: none)."""
    @property
    def q_max(self) -> Array: ...
    @property
    def tau_max(self) -> Array:
        """Torque limits (N·m; inf: none)."""
    @property
    def q_start(self) -> Array: ...
    @property
    def q_rest(self) -> Array: ...
    @property
    def total_mass(self) -> float: ...
    def fk(self, q: ArrayLike1) -> Array:
        """End-effector position in the world (m), ``(3,)``."""
    def kinematics(self, q: ArrayLike1, qd: ArrayLike1) -> Tuple[Array, Array, Array]:
        """``(x, xd, jdot_qd)``: end-effector position, velocity ``J q̇`` and ``J̇ q̇``, each
        ``(3,)``."""
    def jacobian(self, q: ArrayLike1) -> Array:
        """End-effector point Jacobian ``∂x/∂q``, ``(3, n)``."""
    def mass_matrix(self, q: ArrayLike1) -> Array:
        """``M(q)`` (kg·m²), ``(n, n)``."""
    def gravity(self, q: ArrayLike1) -> Array:
        """``g(q)`` (N·m), ``(n,)``."""
    def nonlinear_effects(self, q: ArrayLike1, qd: ArrayLike1) -> Array:
        """``h(q, q̇) = C q̇ + g + τ_f`` (N·m), friction included."""
    def friction(self, qd: ArrayLike1) -> Array:
        """``τ_f(q̇)`` (N·m)."""
    def rnea(self, q: ArrayLike1, qd: ArrayLike1, qdd: ArrayLike1) -> Array:
        """Inverse dynamics ``M q̈ + C q̇ + g`` (N·m; rigid body, no friction)."""
    def aba(self, q: ArrayLike1, qd: ArrayLike1, tau: ArrayLike1) -> Array:
        """Forward dynamics ``M⁻¹(τ − C q̇ − g)`` (rad/s²; rigid body, no friction)."""
    def forward_dynamics(self, q: ArrayLike1, qd: ArrayLike1, u: ArrayLike1) -> Array:
        """Forward dynamics with friction, ``M⁻¹(u − h)`` (rad/s²)."""

class LearnedController:
    """A learned operational space controller (the Rust ``osrl_learn::LearnedController``, the
    controller of ``osrl simulate --controller learned:MODEL``): the reference acceleration of
    eq. 2 with the training's task gains, then the learned command (eq. 34) without
    exploration, within the torque and torque-rate limits. Gives the Rust controller's commands
    bit for bit. Stateful: the torque-rate limit and the counts follow the commands, so call
    ``command`` once per control period."""

    @staticmethod
    def load(path: Path) -> "LearnedController":
        """Reads a model saved by ``osrl train`` or ``save`` (``OSError`` for a missing file,
        ``ValueError`` naming the file and field for a corrupt or inconsistent one)."""
        ...
    def save(self, path: Path) -> None:
        """Writes the model (temporary file, then rename; creates its folder)."""
        ...
    def command(self, measurement: Any, x_d: ArrayLike1, xd_d: ArrayLike1,
                xdd_d: ArrayLike1) -> Array:
        """The command ``u`` (N·m, shape ``(dof,)``) for ``measurement`` (an
        ``osrl.Measurement``, or any object with ``q``, ``qd`` of shape ``(dof,)`` and ``x``,
        ``xd`` of shape ``(task_dim,)``, and ``xdd``, the measured task acceleration under the
        last command, when ``observer`` is on) and the target position, velocity and acceleration
        on the task axes (each ``(task_dim,)``). Bad inputs raise ``ValueError`` and change
        nothing; a ``measurement`` without one of those attributes raises ``ValueError`` (the
        ``AttributeError`` as its cause), and an exception raised while getting one (a failing
        property) propagates as it is. Allocation-free in Rust (only the returned array is
        new)."""
        ...
    def reset(self) -> None:
        """Forgets the disturbance observer's estimate (before a new run from rest)."""
        ...
    @property
    def observer(self) -> bool:
        """Whether the task-space disturbance observer runs (a controller saved by ``osrl
        adapt``: its re-adaptation is on); ``command`` then reads ``measurement.xdd``."""
        ...
    @property
    def dof(self) -> int: ...
    @property
    def task_dim(self) -> int: ...
    @property
    def task_axes(self) -> List[int]:
        """World axes (0 = x, 1 = y, 2 = z) of the task coordinates."""
        ...
    @property
    def control_period(self) -> float:
        """Control period (s) it was trained at."""
        ...
    @property
    def robot(self) -> str:
        """The robot it was trained on: a built-in name or a URDF path."""
        ...
    @property
    def home(self) -> Array:
        """Home posture (rad): at rest on the start of the training path."""
        ...
    @property
    def gains(self) -> Tuple[float, float]:
        """Task gains ``(kp, kd)`` of eq. 2."""
        ...
    @property
    def sim_training_minutes(self) -> float: ...
    @property
    def n_local_models(self) -> int: ...
    @property
    def counts(self) -> Tuple[int, int, int]:
        """Commands so far by source: ``(learned, extrapolated, fallback)``."""
        ...
    @property
    def stats(self) -> Dict[str, Any]:
        """The learner's counters."""
        ...
    @property
    def training(self) -> Optional[Dict[str, Any]]:
        """The training summary (learning curve, episodes, ...) of ``osrl.train``; ``None``
        for a loaded model."""
        ...

class Learner:
    """The learner of the learned controller (``osrl_learn::Learner``) as a stepping object:
    ``command`` for a reference acceleration, ``learn`` from each transition. ``robot`` (a
    built-in name or URDF path) fills the config's data-sheet fields (nominal gains, rest
    posture, torque limits); ``config`` is a dict of ``[learner]`` keys (``osrl train``'s TOML
    section, nested dicts for its groups, e.g. ``{"guards": {"warmup_samples": 200}}``;
    unknown keys raise ``ValueError``); ``seed`` seeds the exploration noise.

    Checked at construction (``ValueError`` naming the argument or key): ``dof`` and
    ``task_dim`` integers (0 < task_dim ≤ dof), ``control_period`` within 1e-4–0.1 s (the range
    a saved model accepts), ``seed`` in [0, 2**64), and every config key, including the LWPR
    sections ``partition.lwpr`` and ``gravity.lwpr`` (built as the learner builds its models,
    e.g. ``init_d`` positive definite)."""

    def __init__(self, dof: int, task_dim: int, control_period: float,
                 robot: Optional[str] = None, config: Optional[Dict[str, Any]] = None,
                 seed: int = 0) -> None: ...
    def command(self, q: ArrayLike1, qd: ArrayLike1, xdd_ref: ArrayLike1,
                explore: bool = False, seed: Optional[int] = None) -> Array:
        """The command ``u`` (N·m) for the reference task acceleration ``xdd_ref`` at
        ``(q, qd)``: the nominal command until ``ready``, the learned blend after; with
        ``explore``, exploration noise (``seed`` reseeds it first)."""
        ...
    def learn(self, prev: Any, cur: Any) -> None:
        """Learns from the transition ``prev → cur`` (``osrl.Measurement``s; ``cur.u`` was
        the command held in between). ``cur`` must be the measurement one control period after
        ``prev``: ``cur.t − prev.t`` within ±50 % of ``control_period`` (enough for a real
        robot's timing jitter and for times summed from rounded periods; it tells the next
        measurement from the same one, an older one or one after a missed step), else
        ``ValueError`` and nothing is learned. After a ``reset`` of the robot, ``prev`` is the
        reset's measurement. A rejected measurement raises ``ValueError`` (the rejection is
        counted in ``stats``). A measurement without one of the attributes raises
        ``ValueError``; an exception raised while getting one propagates."""
        ...
    def start_episode(self, last_sent: Optional[ArrayLike1] = None) -> None:
        """Starts a new sequence of commands: ``last_sent`` is the command the robot holds
        (``None``: unknown, the next command is not rate limited); the noise restarts at 0."""
        ...
    @property
    def ready(self) -> bool:
        """Whether the warm-up is over and the local models exist."""
        ...
    @property
    def n_local_models(self) -> int: ...
    @property
    def n_trained(self) -> int: ...
    @property
    def dof(self) -> int: ...
    @property
    def task_dim(self) -> int: ...
    @property
    def control_period(self) -> float: ...
    @property
    def stats(self) -> Dict[str, Any]: ...
    @property
    def config(self) -> Dict[str, Any]: ...

def train(robot: Any, trajectory: Optional[str] = None, minutes: Optional[float] = None,
          seed: Optional[int] = None, config: Optional[Dict[str, Any]] = None,
          model: Optional[str] = None) -> LearnedController:
    """Trains a learned controller on ``robot`` (any object of ROBOT_PROTOCOL.md, e.g.
    ``osrl.mujoco.MujocoRobot``) with the Rust trainer of ``osrl train``: motor babbling, then
    on-policy learning along ``trajectory`` (``figure8``, ``circle``, ``min_jerk``) for
    ``minutes`` simulated minutes in all, seeded with ``seed``. The robot is first reset at
    rest at the home posture. ``trajectory``, ``minutes`` and ``seed`` default to the config's
    ``trajectory.kind``, ``train.minutes`` and ``train.seed`` (themselves ``figure8``, 30 and
    0); given both as a keyword and in ``config``, they must be equal (``ValueError``).

    ``model``: osrl's model of the robot (a built-in name or URDF path; default
    ``robot.osrl_name``, which ``MujocoRobot.builtin`` sets). It gives the trajectory, the home
    posture, the learner's data-sheet values and the saved model's robot, and the evaluations
    run on osrl's own simulator of it (the learner never sees it: training uses ``robot``'s
    measurements only). ``config``: ``{"learner": {...}, "train": {...}, "trajectory":
    {...}}`` with ``osrl train``'s TOML keys (unknown keys raise ``ValueError``).

    The robot's attributes are checked first, each error naming it (``robot.dof``, ...):
    ``dof`` and ``task_dim`` integers equal to the model's, ``control_period`` within
    1e-4–0.1 s, ``torque_limits`` ``dof`` numbers > 0 (inf: none), ``joint_limits`` a pair
    ``(q_min, q_max)`` with ``q_min < q_max`` per joint (∓inf: none). A measured command
    ``robot.step().u`` beyond 10 × the torque limits (osrl's model's where the robot gives
    none) stops the training with ``ValueError``.

    The GIL is released while training, taken for each ``robot.step``; Ctrl-C stops it. An
    exception raised by the robot (or by a measurement's attribute) stops the training and is
    raised again. A training that learned nothing raises ``ValueError`` when the learner's
    guards rejected the robot's measurements (with the counts), and warns (``UserWarning``)
    when it was too short for the learner's warm-up."""
    ...

class Trajectory:
    """The task-space path ``osrl.train(robot, kind, config={"trajectory": config})`` follows
    for osrl's model ``robot`` (a built-in name or URDF path): ``sample(t)`` gives the targets
    a loop outside the trainer (a MuJoCo evaluation, a plot) tracks. ``kind``: ``figure8``,
    ``circle`` or ``min_jerk`` (default: the config's ``kind``, itself ``figure8``; given in
    both, they must be equal); ``config``: ``[trajectory]`` keys (unknown keys raise
    ``ValueError``)."""

    def __init__(self, robot: str, kind: Optional[str] = None,
                 config: Optional[Dict[str, Any]] = None) -> None: ...
    def sample(self, t: float) -> Tuple[Array, Array, Array]:
        """``(x_d, xd_d, xdd_d)`` at time ``t`` (s) on the task axes (m, m/s, m/s²); times
        before 0 give the start."""
        ...
    @property
    def period(self) -> float:
        """Seconds of one cycle of the path."""
        ...
    @property
    def ramp(self) -> float:
        """Seconds of the smooth start (0 for minimum-jerk moves)."""
        ...
    @property
    def home(self) -> Array:
        """The home posture (rad): at rest on the start of the path."""
        ...
    @property
    def task_axes(self) -> List[int]: ...
