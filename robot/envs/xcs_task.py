"""What the ``navigation``, ``stacking`` and ``search`` EIS environments share.

Each puts one robot (entity ``robot``) in a chapter-3 or Appendix-A task world and offers two
ways to act: the task's primitive moves one at a time (Table 3.1, App. A's head moves), and
the behaviour action ``run_trial(explore|exploit)``, which runs one whole XCS-driven trial
(Algorithm 2: XCS filtered by the affordance table, or standard XCS) and reports back. Either
way every push teaches the affordance table (Algorithm 1), which the agent perceives as
``afford(Object, Action, moved|unmoved)`` triples. The vocabulary is in
``robot/envs/README.md``. Files given as ``table`` / ``rules`` are loaded at the start when
they exist (a corrupt one is a clear error) and written atomically after every change.
"""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path
from typing import ClassVar

from behaviours.learners.affordance_table import AffordanceTable, LearnerFileError
from behaviours.learners.affordance_xcs import AffordanceXCS
from behaviours.learners.xcs import XCS
from behaviours.xcs_tasks import Task, View
from behaviours.xcs_trials import METHODS, N_STEP, TABLE_7_1, TrialRecord, run_trial
from goalagent.eis.exceptions import ActionRefused, ManagementException
from goalagent.eis.pyenv import PerceptLike, PythonEnvironment, action
from goalagent.kb.terms import Atom, Struct
from sim.headless import use_headless_rendering

EFFECT_NAMES = {0: "unmoved", 1: "moved"}
"""How the push effects of §3.5.2 read in percepts."""
MODES = ("explore", "exploit")
MAX_STEPS = 100


class XcsTaskEnvironment(PythonEnvironment):
    """One robot in a task world, its XCS learner and affordance table, trial bookkeeping."""

    entity_names = ("robot",)
    default_entity_type = "robot"
    common_parameters: ClassVar[dict[str, object]] = {
        "perception": str, "seed": int, "method": str, "table": str, "rules": str,
        "n_step": int,
    }
    default_method = "affordance_xcs"
    default_n_step = N_STEP
    xcs_options: ClassVar[dict[str, bool]] = {}

    # ------------------------------------------------------------------ life cycle
    def on_init(self, params: dict[str, object]) -> None:
        """Check the parameters, load the learner's files, build the world and the task."""
        use_headless_rendering()
        self.mode = str(params.get("perception", "truth"))
        if self.mode not in ("truth", "camera"):
            self._bad(f"unknown perception mode {self.mode!r}; use camera or truth")
        self.n_step = int(params.get("n_step", self.default_n_step))
        if not 1 <= self.n_step <= MAX_STEPS:
            self._bad(f"n_step must lie within 1..{MAX_STEPS}, got {self.n_step}")
        method = str(params.get("method", self.default_method))
        if method not in METHODS:
            self._bad(f"unknown method {method!r}; use {' or '.join(METHODS)}")
        self.table_path = Path(str(params["table"])) if params.get("table") else None
        self.rules_path = Path(str(params["rules"])) if params.get("rules") else None
        try:
            table = (AffordanceTable.load(self.table_path)
                     if self.table_path is not None and self.table_path.exists() else None)
            xcs = (XCS.load(self.rules_path)
                   if self.rules_path is not None and self.rules_path.exists() else None)
        except (LearnerFileError, ValueError) as error:
            self._bad(str(error))
        self.task_params(params)
        self.task = self.make_task()
        if xcs is None:
            xcs = XCS(len(self.task.actions), **{**TABLE_7_1, **self.xcs_options},
                      random_state=int(params.get("seed", 0)))
        self.learner = AffordanceXCS(xcs, self.task.actions, table,
                                     use_affordances=method == "affordance_xcs")
        self.trial = 0
        self._events: list[PerceptLike] = []
        self._begin(self.task.reset(0))

    def _bad(self, message: str) -> None:
        """Refuse an init parameter with a message naming this environment."""
        raise ManagementException(f"environment '{self.name}': {message}")

    def task_params(self, params: dict[str, object]) -> None:
        """Read the task's own parameters (subclasses)."""

    def make_task(self) -> Task:
        """Build the world and the task (subclasses)."""
        raise NotImplementedError

    def close_world(self) -> None:
        """Free the world's renderer (subclasses)."""
        raise NotImplementedError

    def on_kill(self) -> None:
        """Free the renderer."""
        self.close_world()

    def _begin(self, view: View) -> None:
        """A fresh trial has been set up and looks like ``view``."""
        self.view, self.steps, self.payoff = view, 0, 0.0
        self.over = self.success = False

    # ------------------------------------------------------------------ percepts
    def percepts(self, entity: str) -> Iterable[PerceptLike]:
        """The encoded state, the affordance table, the trial's progress, and once what the
        last action reported."""
        result: list[PerceptLike] = [("state", Atom(self.view.bits)), ("trial", self.trial + 1),
                                     ("steps", self.steps)]
        if self.over:
            result.append("trial_over")
        result.extend(self.task_percepts())
        result.extend(self._events)
        self._events = []
        return result

    def object_percepts(self) -> list[PerceptLike]:
        """``in_front(O)`` and the ``afford(O, A, E)`` triples (tasks with objects)."""
        front = Atom(self.view.obj) if self.view.obj is not None else Atom("none")
        names = self.task.names
        return [("in_front", front)] + [
            Struct("afford", (Atom(o), Atom(names[a]), Atom(EFFECT_NAMES.get(e, str(e)))))
            for o, a, e in self.learner.table.triples()]

    def task_percepts(self) -> list[PerceptLike]:
        """The task's own percepts (subclasses)."""
        return []

    # ------------------------------------------------------------------ acting
    def primitive(self, name: str) -> None:
        """Perform one of the task's primitive actions (by its name in ``task.names``)."""
        if self.over:
            raise ActionRefused(f"{name}: the trial is over; restart first")
        index = self.task.actions.index(next(a for a, n in self.task.names.items() if n == name))
        before = self.view
        outcome, self.view = self.task.perform(index)
        if outcome.effect is not None and before.obj is not None:
            self.learner.observe_effect(before.obj, index, outcome.effect)
            self._events.append(Struct("effect", (Atom(before.obj), Atom(name),
                                                  Atom(EFFECT_NAMES[outcome.effect]))))
            self._save_table()
        self.steps += 1
        self.payoff += outcome.reward
        self.success = outcome.success
        self.over = outcome.done or self.steps >= self.n_step

    @action("restart")
    def restart(self, entity: str) -> None:
        """Set the world up for the next trial (the world's change comes after its trials)."""
        self.trial += 1
        self._begin(self.task.reset(self.trial))

    @action("run_trial")
    def run_trial(self, entity: str, mode: str) -> None:
        """Run one XCS trial (Algorithm 2) from a fresh start; report ``trial_result``."""
        if mode not in MODES:
            raise ActionRefused(f"run_trial({mode}): the mode is explore or exploit")
        if self.steps or self.over:
            self.trial += 1
        record: TrialRecord = run_trial(self.task, self.learner, self.trial,
                                        explore=mode == "explore", n_step=self.n_step)
        self.view = self.task.view()
        self.steps, self.payoff, self.success, self.over = (record.steps, record.payoff,
                                                            record.success, True)
        self._events.append(Struct("trial_result", (
            Atom(mode), round(record.payoff, 1), record.steps,
            Atom("true" if record.success else "false"))))
        self._save_table()
        if self.rules_path is not None:
            self.learner.learner.save(self.rules_path)

    def _save_table(self) -> None:
        if self.table_path is not None:
            self.learner.table.save(self.table_path)
