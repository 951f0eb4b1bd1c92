"""Chapter 4's can opening as a Gymnasium environment: ``goalagent/CanOpening-v0``.

The hand holds the lid (pushed open) or the handle (pulled open) of a simulated garbage can and
moves in small steps, through ``behaviours.contact.PartContact``: the same interface that
Algorithm 3 and the chapter-4 studies explore (§4.6.1).

- action: a = (Δx, Δy, Δz) in metres, ``Box(-0.01, 0.01, (3,))`` (§4.6.1's
  A = {(x, y, z) | -0.01 <= x, y, z <= 0.01}); ``dims=1`` takes Δx only (the thesis's 1-D runs);
- observation: s_o, the share of the image the dark opening takes (eq. 4.19), ``Box(0, 1,
  (1,))``, seen by the ``close`` camera (``perception="camera"``) or computed from ground truth;
- reward (``reward=``): ``"prediction_error"`` (default) is chapter 4's intrinsic reward
  r = |η| (eq. 4.6), the error of the environment's own forward model F(s_o, a) (4.2-4.4: one
  hidden layer of 10 tanh units, α = 0.3, learned online from the episode's steps);
  ``"opening"`` is the effect e_o = s'_o - s_o (eq. 4.20), so an episode's return is how far the
  can was opened;
- an episode is one exploration (Algorithm 3's loop): it starts with the can closed and the
  hand holding the part, and is truncated after N_s steps (``max_steps``: 100 for 1-D actions,
  300 for 3-D, §4.6.1); nothing terminates it;
- ``can``: a shipped can's name (o1 .. o5, slide, pedal) or the path of a can file (``.yaml``,
  ``robot/envs/README.md``); ``part``: ``lid`` or ``handle`` (default: the part that opens it);
- ``reset(seed=...)`` seeds the scene (the ball's place) and the forward model.
"""

from __future__ import annotations

import os
from typing import Any, ClassVar

import gymnasium as gym
import numpy as np
from gymnasium import spaces

from behaviours.contact import CONTACT_CAMERA, CONTACT_STEP, PartContact
from behaviours.learners.forward_model import ForwardModel
from behaviours.perception import make_perception
from robot.gym.checks import choice, ready_to_step, reset_options, valid_action, whole
from robot.gym.rendering import OVERVIEW, Frames, WorldRendering, scene_cameras
from robot.gym.rendering import View as CameraView
from robot.gym.tasks import PERCEPTIONS, RENDER_MODES
from sim.canfile import find_can
from sim.world import GarbageWorld

REWARDS = ("prediction_error", "opening")
HOLDABLE_PARTS = ("lid", "handle")
BUDGET = {1: 100, 3: 300}
"""N_s of Algorithm 3 by action dimensions (§4.6.1)."""
SEED_LIMIT = 2 ** 31 - 1


class CanOpeningEnv(WorldRendering, gym.Env):
    """Hold the lid or handle of a can and move it (see the module doc)."""

    metadata: ClassVar[dict[str, Any]] = {"render_modes": list(RENDER_MODES), "render_fps": 4}
    overview = CameraView((0.0, 0.05, 0.55), 1.2, -40.0, -25.0)

    def __init__(self, *, can: str | os.PathLike[str] = "o1", part: str | None = None,
                 dims: int = 3, reward: str = "prediction_error", perception: str = "truth",
                 max_steps: int | None = None, render_mode: str | None = None,
                 camera: str = OVERVIEW):
        """Build the can's world; every keyword is checked before anything is built."""
        spec = find_can(can)
        opens = spec.functional[0] if spec.functional[0] in HOLDABLE_PARTS else "lid"
        self.part = choice("part", opens if part is None else part,
                           tuple(p for p in spec.parts if p in HOLDABLE_PARTS))
        self.dims = choice("dims", whole("dims", dims, 1), tuple(BUDGET))
        self.reward_kind = choice("reward", reward, REWARDS)
        self.perception = choice("perception", perception, PERCEPTIONS)
        self.max_steps = whole("max_steps", BUDGET[dims] if max_steps is None else max_steps, 1)
        self.render_mode = choice("render_mode", render_mode, (None, *RENDER_MODES))
        self.world = GarbageWorld(spec)
        self.camera = choice("camera", camera, scene_cameras(self.world.model))
        self.frames = Frames(self.overview, self.camera)
        self.action_space = spaces.Box(-CONTACT_STEP, CONTACT_STEP, (self.dims,), np.float64)
        self.observation_space = spaces.Box(0.0, 1.0, (1,), np.float64)
        self._meaning = (f"{self.dims} number(s) of metres, each within "
                         f"[-{CONTACT_STEP}, {CONTACT_STEP}]")
        self.contact = PartContact(self.world, self.part, dims=self.dims,
                                   perception=make_perception(perception, CONTACT_CAMERA))
        self.model: ForwardModel | None = None
        self._state, self._steps, self._started, self._over = 0.0, 0, False, False

    def reset(self, *, seed: int | None = None,
              options: dict[str, Any] | None = None) -> tuple[np.ndarray, dict[str, Any]]:
        """The can closed, the hand holding the part; a ``seed`` seeds the scene and F."""
        reset_options(options, {})
        super().reset(seed=seed)
        self.world.reset(seed=seed if seed is not None
                         else int(self.np_random.integers(SEED_LIMIT)))
        self.contact.start()
        self._state = float(self.contact.observe())
        if self.reward_kind == "prediction_error":
            self.model = ForwardModel(action_bounds=[(-CONTACT_STEP, CONTACT_STEP)] * self.dims,
                                      random_state=int(self.np_random.integers(SEED_LIMIT)))
            self.model.initialize(1)
        self._steps, self._started, self._over = 0, True, False
        return self._observe(), self._info(None, None)

    def step(self, action: Any) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]:
        """Move the hand by ``action``; reward |η| (4.6) or the effect (4.20)."""
        ready_to_step(self._started, self._over)
        valid_action(self.action_space, action, self._meaning)
        move = np.asarray(action, dtype=np.float64)
        before = self._state
        if self.model is not None:
            # F's own steps, as Algorithm 3 takes them (behaviours.learners.exploration): the
            # row is built from a checked action and a perceived state, and scikit-learn's
            # validation of every row would cost a quarter of the step
            inputs = self.model._inputs(np.concatenate([[before], move])[None, :])
            predicted: float | None = float(self.model.network_.predict(inputs)[0, 0])  # 4.2
        else:
            predicted = None
        self._state = float(self.contact.step(move))
        effect = self._state - before  # 4.20
        if self.model is not None and predicted is not None:
            reward = abs(effect - predicted)  # 4.3, 4.6
            self.model._learn(inputs, np.array([[effect]]))  # 4.4
        else:
            reward = effect
        self._steps += 1
        truncated = self._steps >= self.max_steps
        self._over = truncated
        return self._observe(), reward, False, truncated, self._info(effect, predicted)

    def _observe(self) -> np.ndarray:
        return np.array([min(max(self._state, 0.0), 1.0)], dtype=np.float64)

    def _info(self, effect: float | None, predicted: float | None) -> dict[str, Any]:
        return {"opening": self.world.opening(), "effect": effect, "prediction": predicted,
                "steps": self._steps, "part": self.part}
