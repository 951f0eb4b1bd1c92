"""The ``garbage`` EIS environment: a robot arm, a ball and one simulated garbage can.

Percepts describe what the robot perceives each cycle (camera or ground truth, see
``behaviours.perception``); actions run the motor skills of ``behaviours.skills`` and the
affordance behaviours of ``behaviours.learning`` (thesis ch. 6). The vocabulary is documented
in ``robot/envs/README.md``. A refused action (a part not on this can, θ out of bounds, a mode
not available) raises ``ActionRefused`` before the world is touched.
"""

from __future__ import annotations

import contextlib
import sys
from collections.abc import Iterable
from pathlib import Path

import numpy as np

from behaviours.learners.known_objects import DatabaseError, KnownObjectDatabase
from behaviours.learning import (
    ACTIVE_N_MAX,
    LEARNING_MODES,
    AffordanceBehaviours,
    AffordanceEvidence,
    LearningModeUnavailable,
)
from behaviours.models import ModelStore
from behaviours.part_learning import learn_by_transfer
from behaviours.perception import Observation, make_perception
from behaviours.skills import (
    THETA_BOUNDS,
    SkillError,
    check_skill,
    drop_ball,
    grasp_ball,
    perform_skill,
)
from goalagent.eis.exceptions import ActionRefused, ManagementException
from goalagent.eis.pyenv import PerceptLike, PythonEnvironment, action
from goalagent.kb.terms import Atom, Struct
from robot.paths import default_model_path, default_objects_path
from sim.canfile import CanFileError, find_can
from sim.world import GarbageWorld

CLOSED = 0.01
"""An opening (m) below this counts as closed."""
CLOSING_SKILLS = (("sweep_down", "lid"), ("sweep_down", "handle"), ("extend_arm", "handle"),
                  ("sweep_right", "lid"), ("sweep_left", "lid"))
"""What the robot tries, in order, to close a can: press the lid down, press a lifted handle
down, push a pulled handle back in, slide a sliding lid back (until the can is closed)."""


def afford_percept(evidence: AffordanceEvidence) -> Struct:
    """The percept ``afford(Obj, Act, Eff, Tot, Suc, Rel)`` (eq. 6.1) for what a behaviour found."""
    return Struct("afford", (Atom(evidence.obj), Atom(evidence.act), Atom(evidence.eff),
                             evidence.tot, evidence.suc, evidence.rel))


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
        self._transfer_rng = np.random.RandomState(self.seed)
        self.learning = str(params.get("learning", "random"))
        if self.learning not in LEARNING_MODES:
            raise ManagementException(f"environment 'garbage': unknown learning mode "
                                      f"{self.learning!r}; the modes are "
                                      f"{', '.join(LEARNING_MODES)}")
        self.disposed = 0
        self._events: list[PerceptLike] = []
        self._observation: Observation | None = None
        self._told: set[str] = set()

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

    def _changed(self) -> None:
        self._observation = None

    def _tell_where(self, what: str, path: Path) -> None:
        """Say once per run where learning keeps what it wrote (stderr), so a user can find,
        keep or delete it."""
        if what not in self._told:
            self._told.add(what)
            print(f"garbage: {what} are kept in {path}", file=sys.stderr)

    # ------------------------------------------------------------------ ball
    @action("grasp")
    def grasp(self, entity: str, obj: str) -> None:
        """Grasp the ball on the table."""
        self._ball(obj)
        state = self.world.state()
        if state.holding_ball:
            raise ActionRefused("grasp(ball): the robot already holds the ball")
        if state.ball_in_can:
            raise ActionRefused("grasp(ball): the ball is in the can; close the lid first")
        grasp_ball(self.world)
        self._changed()

    @action("drop")
    def drop(self, entity: str, obj: str) -> None:
        """Drop the held ball into the can's opening (it falls outside if that is closed)."""
        self._ball(obj)
        if not self.world.state().holding_ball:
            raise ActionRefused("drop(ball): the robot does not hold the ball")
        drop_ball(self.world)
        self._changed()

    @staticmethod
    def _ball(obj: str) -> None:
        if obj != "ball":
            raise ActionRefused(f"there is no {obj!r} to handle here, only the ball")

    @action("close_lid")
    def close_lid(self, entity: str) -> None:
        """Close the can; with the ball inside, that completes a trial and a new ball is
        put on the table (the scene is reset for the next trial)."""
        for skill, part in CLOSING_SKILLS:
            if self.world.opening() < CLOSED:
                break
            if part in self.world.parts:
                perform_skill(self.world, skill, part, THETA_BOUNDS[skill][1])
        if self.world.state().ball_in_can and self.world.opening() < CLOSED:
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
        the three for every pair it tried."""
        if not effect and not mode:
            effect, mode = first, second
            if mode != "transfer":
                raise ActionRefused(f"learn({effect}, {mode}): the whole-object form needs mode "
                                    "'transfer'; learn(Part, Act, Eff, Mode) learns one pair")
        elif not mode:
            raise ActionRefused("learn takes (Part, Act, Eff, Mode) or (Eff, transfer)")
        else:
            self._affordance_request(first, second)
        if effect != "opened":
            raise ActionRefused(f"learn: only the effect 'opened' can be measured, not {effect!r}")
        if mode == "transfer":
            self._learn_by_transfer(effect)
            return
        try:
            result = self.behaviours.learn(first, second, effect, mode)
        except LearningModeUnavailable as error:
            raise ActionRefused(str(error)) from None
        self._changed()
        store = self.behaviours.store
        if store is not None:
            self._tell_where("learned effect models", store.path)
        self._events.append(afford_percept(result.evidence))
        self._events.append(Struct("model", (Atom(first), Atom(second),
                                             round(result.theta_max, 4),
                                             round(result.e_max, 4))))
        self._events.append(Struct("exploration", (Atom(first), Atom(second), Atom(mode),
                                                   result.samples)))

    def _learn_by_transfer(self, effect: str) -> None:
        """Algorithm 6 on this can; afford/model percepts for every pair tried (§5.5.4)."""
        result = learn_by_transfer(self.world, self.perception, self.objects, delta=self.delta,
                                   effect_name=effect, random_state=self._transfer_rng)
        self._changed()
        self._tell_where("known objects", self.objects.path)
        for report in result.reports:
            evidence = report.evidence
            if evidence.suc:
                self.behaviours.remember(evidence.obj, evidence.act, report.theta_max)
            self._events.append(afford_percept(evidence))
            self._events.append(Struct("model", (Atom(evidence.obj), Atom(evidence.act),
                                                 round(report.theta_max, 4),
                                                 round(report.e_max, 4))))
            self._events.append(Struct("exploration", (Atom(evidence.obj), Atom(evidence.act),
                                                       Atom("transfer"), report.actions)))

    @action("apply")
    def apply(self, entity: str, part: str, action_type: str) -> None:
        """Use an affordance: act with the best known θ (eq. 6.13) and report the verified
        effect as ``afford(Part, Act, opened, 1, 1, 1)`` or ``afford(..., 1, 0, 0)``."""
        self._affordance_request(part, action_type)
        result = self.behaviours.apply(part, action_type)
        self._changed()
        self._events.append(afford_percept(result.evidence))
