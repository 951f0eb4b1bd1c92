"""The ``garbage`` EIS environment: a robot arm, a ball and one simulated garbage can.

Percepts describe what the robot perceives each cycle (camera or ground truth, see
``behaviours.perception``); actions run the motor skills of ``behaviours.skills`` and the
affordance behaviours of ``behaviours.learning`` (thesis ch. 6). The vocabulary is documented
in ``robot/envs/README.md``. A refused action (a part not on this can, θ out of bounds, a mode
not available) raises ``ActionRefused`` before the world is touched.
"""

from __future__ import annotations

import contextlib
from collections.abc import Iterable
from pathlib import Path

from behaviours.learners.effect_models import ModelStore
from behaviours.learners.known_objects import DatabaseError, KnownObjectDatabase
from behaviours.learning import ACTIVE_N_MAX, LEARNING_MODES, AffordanceBehaviours
from behaviours.perception import Observation, make_perception
from behaviours.skills import (
    THETA_BOUNDS,
    SkillError,
    ball_within_reach,
    check_skill,
    drop_ball,
    grasp_ball,
    perform_skill,
)
from goalagent.eis.exceptions import ActionRefused, ManagementException
from goalagent.eis.pyenv import PerceptLike, PythonEnvironment, action
from goalagent.kb.terms import Atom
from robot.envs.affordance_requests import AffordanceRequests, afford_percept
from robot.paths import default_model_path, default_objects_path
from sim.canfile import CanFileError, find_can
from sim.world import GarbageWorld

__all__ = ["GarbageEnvironment", "afford_percept"]

CLOSED = 0.01
"""An opening (m) below this counts as closed."""
CLOSING_SKILLS = (("sweep_down", "lid"), ("sweep_down", "handle"), ("extend_arm", "handle"),
                  ("sweep_right", "lid"), ("sweep_left", "lid"))
"""What the robot tries, in order, to close a can: press the lid down, press a lifted handle
down, push a pulled handle back in, slide a sliding lid back (until the can is closed)."""
CLOSING_ROUNDS = 3
"""How many times ``close_lid`` goes through the closing skills at most."""


class GarbageEnvironment(PythonEnvironment):
    """One robot (entity ``robot``) in front of one garbage can."""

    name = "garbage"
    entity_names = ("robot",)
    default_entity_type = "robot"
    parameters = {
        "can": str | Path,
        "perception": str,
        "seed": int,
        "record": bool | Path,
        "delta": float,
        "trials": int,
        "models": Path,
        "objects": Path,
        "learning": str,
        "n_max": int,
        "active_n_max": int,
    }

    # ------------------------------------------------------------------ life cycle
    def on_init(self, params: dict[str, object]) -> None:
        """Build the world: the can, the perception mode, the learners and the recorder."""
        try:
            can = find_can(str(params.get("can", "o1")))
        except CanFileError as error:
            raise ManagementException(f"environment 'garbage': {error}") from None
        self.seed = int(params.get("seed", 0))
        self.delta = float(params.get("delta", 0.1))
        self.trials = int(params.get("trials", 5))
        try:
            self.perception = make_perception(str(params.get("perception", "truth")))
        except ValueError as error:
            raise ManagementException(f"environment 'garbage': {error}") from None
        self.world = GarbageWorld(can, seed=self.seed)
        self._recording = contextlib.ExitStack()
        record = params.get("record", False)
        if record:
            self._recording.enter_context(self.world.record(Path(str(record))))
        store = ModelStore(Path(str(params.get("models") or default_model_path())))
        self.behaviours = AffordanceBehaviours(
            self.world, delta=self.delta, n_max=int(params.get("n_max", 10)), seed=self.seed,
            store=store, perception=self.perception,
            active_n_max=int(params.get("active_n_max", ACTIVE_N_MAX)),
        )
        try:
            self.objects = KnownObjectDatabase(
                Path(str(params.get("objects") or default_objects_path())))
        except DatabaseError as error:
            raise ManagementException(f"environment 'garbage': {error}") from None
        self.requests = AffordanceRequests(self.world, self.perception, self.behaviours,
                                           self.objects, delta=self.delta, seed=self.seed)
        self.learning = str(params.get("learning", "random"))
        if self.learning not in LEARNING_MODES:
            raise ManagementException(f"environment 'garbage': unknown learning mode "
                                      f"{self.learning!r}; the modes are "
                                      f"{', '.join(LEARNING_MODES)}")
        self.disposed = 0
        self._events: list[PerceptLike] = []
        self._observation: Observation | None = None

    def on_kill(self) -> None:
        """Finish the recording and free the renderer."""
        self._recording.close()
        self.world.close()

    # ------------------------------------------------------------------ percepts
    def observe(self) -> Observation:
        """What the robot perceives now (cached until the world changes)."""
        if self._observation is None:
            self._observation = self.perception.observe(self.world)
        return self._observation

    def percepts(self, entity: str) -> Iterable[PerceptLike]:
        """The scene as perceived this cycle, plus what the last action reported once."""
        seen = self.observe()
        state = self.world.state()
        result: list[PerceptLike] = [("trials", self.trials), ("disposed", self.disposed),
                                     ("learning_mode", Atom(self.learning))]
        for name, part in sorted(seen.parts.items()):
            result.append(("obs", Atom(name)))
            result.append(("part", Atom(name), round(part.area, 6),
                           round(part.rectangleness, 4), round(part.squareness, 4)))
        result.extend(("above", Atom(upper), Atom(lower)) for upper, lower in seen.above)
        result.append(("openness", round(seen.opening, 4)))
        if seen.opening >= self.delta:
            result.append("opened")
        if state.holding_ball:
            result.append(("holding", Atom("ball")))
        if state.ball_in_can:
            result.append(("in_can", Atom("ball")))
        result.extend(self._events)
        self._events = []
        return result

    def _changed(self, learning: bool = False) -> None:
        """The world may look different now. Anything but learning (which leaves the can as
        it found it) is also new information for the livelock guard of ``learn``."""
        self._observation = None
        if not learning:
            self.requests.world_changed()

    # ------------------------------------------------------------------ ball
    @action("grasp")
    def grasp(self, entity: str, obj: str) -> None:
        """Grasp the ball wherever it lies within reach (on the table, or where a missed drop
        left it); ``grasp_failed(ball)`` says when the hand closed without it."""
        self._ball(obj)
        state = self.world.state()
        if state.holding_ball:
            raise ActionRefused("grasp(ball): the robot already holds the ball")
        if state.ball_in_can:
            raise ActionRefused("grasp(ball): the ball is in the can; close the lid first")
        if not ball_within_reach(self.world):
            where = ", ".join(f"{x:.3f}" for x in state.ball_pos)
            raise ActionRefused(f"grasp(ball): the ball at ({where}) m is out of the arm's reach")
        if not grasp_ball(self.world):
            self._events.append(("grasp_failed", Atom("ball")))
        self._changed()

    @action("drop")
    def drop(self, entity: str, obj: str) -> None:
        """Drop the held ball into the can's opening; when it does not land inside,
        ``ball_missed(Why)`` says why: ``blocked`` (the can stopped it at the front edge: not
        open enough for the ball) or ``outside`` (let go over the opening, it came to rest
        outside the can)."""
        self._ball(obj)
        if not self.world.state().holding_ball:
            raise ActionRefused("drop(ball): the robot does not hold the ball")
        result = drop_ball(self.world)
        if not result.landed:
            self._events.append(("ball_missed", Atom("blocked" if result.blocked else "outside")))
        self._changed()

    @staticmethod
    def _ball(obj: str) -> None:
        if obj != "ball":
            raise ActionRefused(f"there is no {obj!r} to handle here, only the ball")

    @action("close_lid")
    def close_lid(self, entity: str) -> None:
        """Close the can; with the ball inside, that completes a trial and a new ball is
        put on the table (the scene is reset for the next trial). The closing skills are
        tried in turn, in rounds while the can is open (a geared lid may come down in two
        presses); one that opened the can further (a sliding lid swept the wrong way) is not
        tried again. ``lid_stuck(W)`` says when they left an opening of W m."""
        wrong_way: set[tuple[str, str]] = set()
        for _ in range(CLOSING_ROUNDS):
            for skill, part in CLOSING_SKILLS:
                before = self.world.opening()
                if before < CLOSED:
                    break
                if part in self.world.parts and (skill, part) not in wrong_way:
                    perform_skill(self.world, skill, part, THETA_BOUNDS[skill][1])
                    if self.world.opening() > before + CLOSED:
                        wrong_way.add((skill, part))
        if self.world.opening() >= CLOSED:
            self._events.append(("lid_stuck", round(self.world.opening(), 4)))
        elif self.world.state().ball_in_can:
            self.disposed += 1
            self.world.reset(seed=self.seed + self.disposed)
        self._changed()

    # ------------------------------------------------------------------ arm skills
    def _skill(self, action_type: str, part: str, theta: float) -> None:
        try:
            check_skill(self.world, action_type, part, theta)
        except SkillError as error:
            raise ActionRefused(f"{action_type}({part}, {theta}): {error}") from None
        result = perform_skill(self.world, action_type, part, theta)
        self._changed()
        self._events.append(("effect", Atom(part), Atom(action_type), result.theta,
                             round(result.part_displacement, 4), round(result.effect, 4)))

    @action("extend_arm")
    def extend_arm(self, entity: str, part: str, theta: float) -> None:
        """Push forward: approach the part and move the hand θ m away from the robot."""
        self._skill("extend_arm", part, theta)

    @action("contract_arm")
    def contract_arm(self, entity: str, part: str, theta: float) -> None:
        """Pull back: move the hand θ m towards the robot."""
        self._skill("contract_arm", part, theta)

    @action("sweep_left")
    def sweep_left(self, entity: str, part: str, theta: float) -> None:
        """Sweep the hand θ m to the left."""
        self._skill("sweep_left", part, theta)

    @action("sweep_right")
    def sweep_right(self, entity: str, part: str, theta: float) -> None:
        """Sweep the hand θ m to the right."""
        self._skill("sweep_right", part, theta)

    @action("lift_up")
    def lift_up(self, entity: str, part: str, theta: float) -> None:
        """Lift the hand θ m."""
        self._skill("lift_up", part, theta)

    @action("sweep_down")
    def sweep_down(self, entity: str, part: str, theta: float) -> None:
        """Move the hand θ m down."""
        self._skill("sweep_down", part, theta)

    # ------------------------------------------------------------------ affordances
    def _affordance_request(self, part: str, action_type: str) -> None:
        if part not in self.world.parts:
            raise ActionRefused(f"can {self.world.can} has no {part}; it has "
                                f"{', '.join(self.world.parts)}")
        if action_type not in THETA_BOUNDS:
            raise ActionRefused(f"unknown action type {action_type!r}; known: "
                                f"{', '.join(THETA_BOUNDS)}")

    @action("learn")
    def learn(self, entity: str, first: str, second: str, effect: str = "",
              mode: str = "") -> None:
        """``learn(Part, Act, Eff, Mode)`` learns what ``Act`` on ``Part`` does to ``Eff``
        (§6.3.4); the verdict comes back as ``afford(Part, Act, Eff, 0, 0, r1|r2)``,
        ``model(Part, Act, ThetaMax, EMax)`` and ``exploration(Part, Act, Mode, N)`` (how many
        exploratory actions it took). Mode ``transfer`` (either form, also the whole-object
        ``learn(Eff, transfer)``) runs Algorithm 6 against the known objects instead and reports
        the three for every pair it tried (``AffordanceRequests``, which also keeps the
        livelock guard: a request answered since the world last changed other than by learning
        is answered ``learn_repeated(...)``)."""
        asked: tuple[str, ...] = (first, second, effect, mode)
        if not effect and not mode:
            effect, mode, asked = first, second, (first, second)
            if mode != "transfer":
                raise ActionRefused(f"learn({effect}, {mode}): the whole-object form needs mode "
                                    "'transfer'; learn(Part, Act, Eff, Mode) learns one pair")
        elif not mode:
            raise ActionRefused("learn takes (Part, Act, Eff, Mode) or (Eff, transfer)")
        else:
            self._affordance_request(first, second)
        if effect != "opened":
            raise ActionRefused(f"learn: only the effect 'opened' can be measured, not {effect!r}")
        if mode not in LEARNING_MODES:
            raise ActionRefused(f"learn: unknown learning mode {mode!r}; the modes are "
                                f"{', '.join(LEARNING_MODES)}")
        self._events.extend(self.requests.learn(asked, effect, mode))
        self._changed(learning=True)

    @action("apply")
    def apply(self, entity: str, part: str, action_type: str) -> None:
        """Use an affordance: act with the best known θ (eq. 6.13) and report the verified
        effect as ``afford(Part, Act, opened, 1, 1, 1)`` or ``afford(..., 1, 0, 0)``."""
        self._affordance_request(part, action_type)
        self._events.extend(self.requests.apply(part, action_type))
        self._changed()
