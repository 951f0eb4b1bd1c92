"""The learners' own protocols over the Gymnasium environments, so XCS and Algorithm 3 run
through the Gymnasium API on the very environments a standard RL agent uses.

``EnvTask`` is the XCS ``Task`` protocol (``behaviours.xcs_tasks``) over a navigation,
stacking or search environment: ``reset(trial)`` is ``env.reset(options={"trial": trial})``,
``perform(action)`` is ``env.step(action)``; the state bits are read back from the
observation, the object in front from its first four bits (0000: nothing, since every object's
colour code has a bit set), the push effect from ``info``. ``done`` is ``terminated``: a
truncated trial is not over for XCS, which ends it itself after ``n_step`` actions.

``EnvContact`` is Algorithm 3's ``ContinuousWorld`` (``behaviours.learners.exploration``) over
a can-opening environment.

Both pass an optional seed to the first ``reset``: a new experiment in a fresh world.
"""

from __future__ import annotations

from collections.abc import Sequence

import gymnasium as gym
import numpy as np

from behaviours.xcs_tasks import StepResult, View
from robot.gym.tasks import XcsTaskEnv

NOTHING = "0000"
"""o = (o_height, o_color) when nothing is in front (eq. 3.13)."""


class EnvTask:
    """An XCS task (``behaviours.xcs_tasks.Task``) through a goalagent task environment."""

    def __init__(self, env: gym.Env, seed: int | None = None):
        """Drive ``env`` (made by ``gymnasium.make`` or not); ``seed`` seeds its first reset."""
        inner = env.unwrapped
        if not isinstance(inner, XcsTaskEnv):
            raise TypeError(f"EnvTask drives the navigation, stacking and search "
                            f"environments, not {type(inner).__name__}")
        self.env, self.inner, self._seed = env, inner, seed
        self.actions = inner.action_codes
        self.names = dict(zip(inner.action_codes, inner.action_names, strict=True))
        self._view: View | None = None

    def _read(self, observation: object) -> View:
        bits = self.inner.decode(observation)
        front = bits[:4] if self.inner.n_bits == 8 and bits[:4] != NOTHING else None
        self._view = View(bits, front)
        return self._view

    def reset(self, trial: int) -> View:
        """Set up trial ``trial`` (0-based) of the experiment."""
        observation, _ = self.env.reset(seed=self._seed, options={"trial": trial})
        self._seed = None
        return self._read(observation)

    def perform(self, action: int) -> tuple[StepResult, View]:
        """One step of the environment as the XCS trials read it."""
        observation, reward, terminated, _, info = self.env.step(action)
        return (StepResult(float(reward), bool(terminated), bool(info["success"]),
                           info["effect"]), self._read(observation))

    def view(self) -> View:
        """What the last reset or step observed."""
        if self._view is None:
            raise RuntimeError("nothing observed yet: reset the task first")
        return self._view

    def applicable(self, view: View) -> tuple[int, ...] | None:
        """The environment's task's preconditions (§3.5.4: stacking pushes only with an
        object perceived in front), so XCS through Gymnasium chooses as it does directly."""
        return self.inner.task.applicable(view)


class EnvContact:
    """Algorithm 3's continuous world through a can-opening environment."""

    def __init__(self, env: gym.Env, seed: int | None = None):
        """Drive ``env``; ``start`` resets it (with ``seed``)."""
        self.env, self._seed = env, seed
        space = env.action_space
        self.action_bounds: Sequence[tuple[float, float]] = [
            (float(lo), float(hi)) for lo, hi in zip(space.low, space.high, strict=True)]
        self._state: float | None = None

    def start(self) -> EnvContact:
        """A new episode: the can closed, the hand holding its part."""
        observation, _ = self.env.reset(seed=self._seed)
        self._seed = None
        self._state = float(observation[0])
        return self

    def observe(self) -> float:
        """s_o now (eq. 4.19)."""
        if self._state is None:
            raise RuntimeError("the episode has not started: call start() first")
        return self._state

    def step(self, action: np.ndarray) -> float:
        """Move the hand by ``action`` (m) and return s'_o."""
        observation, *_ = self.env.step(np.asarray(action, dtype=np.float64))
        self._state = float(observation[0])
        return self._state
