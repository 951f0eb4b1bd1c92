"""The thesis's three XCS tasks as Gymnasium environments: navigation and stacking (§3.5) and
the head-camera search (App. A).

Each wraps the task of ``behaviours/xcs_tasks.py`` (the world's calls, the perception, the
rewards of eqs. 3.14, 3.15 and App. A): the one implementation that the XCS trials, the EIS
environments and these environments all drive. What is added here is what Gymnasium asks:

- observation: the state string, eq. 3.12's 8 bits s = (o_height, o_color, s_xyz) (3.11-3.13)
  or App. A's 9-bit blob grid, as ``MultiBinary(n)`` (``observation="multibinary"``) or as the
  integer the bits spell, ``Discrete(2**n)`` (``observation="discrete"``); perceived by the
  camera (``perception="camera"``: OpenCV on the rendered head-camera frame) or from the
  simulator's ground truth (``"truth"``);
- action: ``Discrete`` over Table 3.1's codes (navigation 000 walk left, 001 walk ahead,
  011 walk right, 010 push ahead; stacking 100 push standing, 101 push squatting, 110 choose
  the box, 111 choose a foam) or App. A's head moves (00 up, 01 right, 10 down, 11 left);
- an episode is one trial (§3.5.7): it terminates at the goal (or when the robot falls off
  the table) and is truncated after ``n_step`` actions (10; the search's N_s is 20);
- the world's change of the experiment: the boxes are exchanged from trial ``exchange_after``
  (10) on, the search target moves from trial ``move_after`` (10) on. Trials are counted from
  the last seeded reset; ``reset(options={"trial": k})`` sets up trial k (0-based) directly;
- ``reset(seed=...)`` starts a new experiment in a freshly built world (the worlds themselves
  are deterministic: the same seed and actions give the same observations and rewards);
- ``info``: the state bits, the object in front (None: nothing), the trial (from 1), the
  steps taken, whether the goal was reached, and the push effect (1 moved, 0 unmoved, None:
  no push on an object) that feeds Algorithm 1's affordance table.
"""

from __future__ import annotations

import sys
from typing import Any, ClassVar

import gymnasium as gym
import numpy as np
from gymnasium import spaces

from behaviours.blob_grid import make_grid_perception
from behaviours.object_state import make_object_perception
from behaviours.xcs_tasks import (
    NAVIGATION_STARTS,
    NavigationTask,
    SearchTask,
    StackingTask,
    StepResult,
    Task,
    View,
)
from behaviours.xcs_trials import N_STEP, SEARCH_STEPS
from robot.gym.checks import choice, ready_to_step, reset_options, valid_action, whole
from robot.gym.rendering import OVERVIEW, Frames, WorldRendering, scene_cameras
from robot.gym.rendering import View as CameraView
from sim.navigation import NavigationWorld
from sim.search import SearchWorld
from sim.stacking import StackingWorld

PERCEPTIONS = ("truth", "camera")
OBSERVATIONS = ("multibinary", "discrete")
RENDER_MODES = ("rgb_array",)
MAX_N_STEP = 100
"""Longest trial (actions) an environment accepts, as the EIS task environments do."""
WHOLE = (int, np.int64)
"""Action types checked by a quick range test (anything else goes through the space)."""
NEVER = sys.maxsize
"""A trial number no experiment reaches: ``exchange_after=None`` never exchanges."""


class XcsTaskEnv(WorldRendering, gym.Env):
    """One of the chapter-3 / App. A tasks, one trial per episode (see the module doc)."""

    metadata: ClassVar[dict[str, Any]] = {"render_modes": list(RENDER_MODES), "render_fps": 4}
    n_bits: ClassVar[int]
    default_n_step: ClassVar[int] = N_STEP
    overview: ClassVar[CameraView]

    def __init__(self, *, perception: str = "truth", observation: str = "multibinary",
                 n_step: int | None = None, render_mode: str | None = None,
                 camera: str = OVERVIEW):
        """Build the world and its task; every keyword is checked before anything is built."""
        self.perception = choice("perception", perception, PERCEPTIONS)
        self.observation = choice("observation", observation, OBSERVATIONS)
        self.n_step = whole("n_step", self.default_n_step if n_step is None else n_step, 1,
                            MAX_N_STEP)
        self.render_mode = choice("render_mode", render_mode, (None, *RENDER_MODES))
        self.task = self.make_task()
        self.camera = choice("camera", camera, scene_cameras(self.world.model))
        self.frames = Frames(self.overview, self.camera)
        self.action_codes: tuple[str, ...] = self.task.actions
        self.action_names = tuple(self.task.names[code] for code in self.action_codes)
        self.action_space = spaces.Discrete(len(self.action_codes))
        self.observation_space: spaces.Space = (
            spaces.MultiBinary(self.n_bits) if observation == "multibinary"
            else spaces.Discrete(2 ** self.n_bits))
        self._meaning = ", ".join(
            f"{i} {code} {name}" for i, (code, name)
            in enumerate(zip(self.action_codes, self.action_names, strict=True)))
        self._arrays: dict[str, np.ndarray] = {}
        self._fresh, self._started, self._over = True, False, False
        self._trial = self._next_trial = self._steps = 0

    # ---------------------------------------------------------------- the task
    @property
    def world(self) -> NavigationWorld | StackingWorld | SearchWorld:
        """The MuJoCo world of the current experiment."""
        return self.task.world  # type: ignore[attr-defined]

    def make_task(self) -> Task:
        """A fresh world and the task over it (subclasses)."""
        raise NotImplementedError

    def decode(self, observation: object) -> str:
        """The state bits an observation of this environment stands for."""
        if self.observation == "multibinary":
            return "".join(str(int(bit)) for bit in np.asarray(observation))
        return format(int(observation), f"0{self.n_bits}b")  # type: ignore[call-overload]

    def _observe(self, view: View) -> np.ndarray | np.int64:
        if self.observation == "discrete":
            return np.int64(int(view.bits, 2))
        seen = self._arrays.get(view.bits)
        if seen is None:
            seen = self._arrays[view.bits] = np.array([int(b) for b in view.bits], np.int8)
        return seen.copy()  # a new array each step, as Gymnasium asks

    def _info(self, view: View, outcome: StepResult | None = None) -> dict[str, Any]:
        return {"bits": view.bits, "object": view.obj, "trial": self._trial + 1,
                "steps": self._steps, "success": bool(outcome and outcome.success),
                "effect": outcome.effect if outcome else None}

    # ---------------------------------------------------------------- Gymnasium
    def reset(self, *, seed: int | None = None,
              options: dict[str, Any] | None = None) -> tuple[Any, dict[str, Any]]:
        """Start a trial: the next of the experiment, or ``options["trial"]`` (0-based); a
        ``seed`` starts a new experiment in a fresh world."""
        chosen = reset_options(options, {"trial": lambda k: whole("trial", k, 0)})
        super().reset(seed=seed)
        if seed is not None:
            if not self._fresh:
                self.world.close()
                self.task = self.make_task()
            self._next_trial = 0
        self._trial = int(chosen.get("trial", self._next_trial))  # type: ignore[call-overload]
        self._next_trial = self._trial + 1
        view = self.task.reset(self._trial)
        self._fresh, self._started, self._over, self._steps = False, True, False, 0
        return self._observe(view), self._info(view)

    def step(self, action: Any) -> tuple[Any, float, bool, bool, dict[str, Any]]:
        """One of the task's actions; terminated at the goal (or a fall), truncated after
        ``n_step`` actions."""
        ready_to_step(self._started, self._over)
        if not (type(action) in WHOLE and 0 <= action < len(self.action_codes)):
            valid_action(self.action_space, action, self._meaning)  # the slower general check
        outcome, view = self.task.perform(int(action))
        self._steps += 1
        terminated = outcome.done
        truncated = not terminated and self._steps >= self.n_step
        self._over = terminated or truncated
        return (self._observe(view), float(outcome.reward), terminated, truncated,
                self._info(view, outcome))


class NavigationEnv(XcsTaskEnv):
    """§3.5's navigation past a movable and a fixed box (Fig. 3.3): ``goalagent/Navigation-v0``."""

    n_bits = 8
    overview = CameraView((0.45, -0.05, 0.40), 1.7, -15.0, -40.0)

    def __init__(self, *, exchange_after: int | None = 10, start: str = "right_lane",
                 **common: Any):
        """The boxes swap places from trial ``exchange_after`` on (None: never); each trial
        starts in the right-most lane or (``start="anywhere"``, §3.5.7) in a lane drawn from
        the experiment's seed and the trial, as ``NavigationTask`` draws it."""
        self.exchange_after = NEVER if exchange_after is None else whole(
            "exchange_after", exchange_after, 0)
        self.start = choice("start", start, NAVIGATION_STARTS)
        self.lane_seed = 0
        super().__init__(**common)

    def make_task(self) -> Task:
        """A fresh navigation world, perceived as eq. 3.12 says."""
        return NavigationTask(NavigationWorld(),
                              make_object_perception(self.perception, "navigation"),
                              exchange_after=self.exchange_after, start=self.start,
                              seed=self.lane_seed)

    def reset(self, *, seed: int | None = None,
              options: dict[str, Any] | None = None) -> tuple[Any, dict[str, Any]]:
        """As ``XcsTaskEnv.reset``; a ``seed`` also seeds the start lanes of its experiment."""
        if seed is not None:
            self.lane_seed = int(seed)
            self.task.seed = self.lane_seed  # type: ignore[attr-defined]
        return super().reset(seed=seed, options=options)


class StackingEnv(XcsTaskEnv):
    """Fig. 3.4's stacking at the table edge: ``goalagent/Stacking-v0``."""

    n_bits = 8
    overview = CameraView((0.25, 0.0, 0.35), 1.7, -30.0, -30.0)

    def make_task(self) -> Task:
        """A fresh stacking world, perceived as eq. 3.12 says."""
        return StackingTask(StackingWorld(), make_object_perception(self.perception, "stacking"))


class HeadSearchEnv(XcsTaskEnv):
    """App. A's head-camera search (Fig. 7.2): ``goalagent/HeadSearch-v0``."""

    n_bits = 9
    default_n_step = SEARCH_STEPS
    overview = CameraView((0.60, 0.1, 0.70), 1.8, -25.0, -15.0)

    def __init__(self, *, move_after: int | None = 10, **common: Any):
        """The operator moves the target from up-left to the right from trial ``move_after``
        on (None: never)."""
        self.move_after = NEVER if move_after is None else whole("move_after", move_after, 0)
        super().__init__(**common)

    def make_task(self) -> Task:
        """A fresh search world, perceived as App. A's blob grid."""
        return SearchTask(SearchWorld(), make_grid_perception(self.perception),
                          move_after=self.move_after)
