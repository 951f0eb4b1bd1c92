"""Issue 28's choices, each on hand-made numbers: XCS crediting exploit steps, eq. 7.2's max
and covering over the considered actions, Algorithm 2's filter scope, stacking's push
precondition, navigation's start lanes, chapter 4's state unit and A_M grid, chapter 5's aim
of eq. 5.10, transfer's fallback and sensor noise, and every page's "Deviations and open
choices" section."""

from __future__ import annotations

from typing import Annotated

import numpy as np
import pytest

from behaviours.learners.affordance_table import AffordanceTable
from behaviours.learners.affordance_xcs import AffordanceXCS
from behaviours.learners.part_models import OpeningGoal, PartActionModel
from behaviours.learners.skill_acquisition import candidate_actions
from behaviours.learners.transfer import gradient_step
from behaviours.learners.validation import ActionBounds
from behaviours.xcs_tasks import STACKING_ACTIONS, NavigationTask, StackingTask, View
from robot.reproduce.framework import Deviation, Reading, ScaledConfig, Study
from robot.reproduce.framework.registry import registered
from robot.reproduce.studies.ch5_baseline import moving_nonfunctional
from robot.reproduce.studies.common.ch4 import ScaledState
from robot.reproduce.studies.common.ch5 import BaselineRow, PairModel
from sim.navigation import LANES
from tests.xcs_helpers import by_condition, cl, make

# -- XCS: crediting exploit steps, and what eq. 7.2's max ranges over ---------------------------


def test_exploit_steps_learn_only_with_learn_in_exploit():
    """p <- p + beta (P - p) (eq. 7.1) with beta = 0.2 on an experienced classifier."""
    for learns, expected in ((False, 500.0), (True, 600.0)):
        xcs = make([cl("##", 0, prediction=500.0, experience=100),
                    cl("##", 1, prediction=100.0, experience=100)], learn_in_exploit=learns)
        assert xcs.act("01", explore=False) == 0  # the best (eq. 3.9)
        xcs.reward(1000.0, done=True)
        assert by_condition(xcs)[("##", 0)].prediction == pytest.approx(expected)
        assert xcs.time_ == 0  # exploit steps never move the GA's clock


def test_an_exploit_step_credits_the_one_before_by_eq_7_2():
    xcs = make([cl("##", 0, prediction=500.0, experience=100),
                cl("##", 1, prediction=100.0, experience=100)], learn_in_exploit=True)
    xcs.act("01", explore=False)
    xcs.reward(0.0, done=False)
    xcs.act("10", explore=False)  # P = 0 + 0.71 * 500 credits [A]-1
    assert by_condition(xcs)[("##", 0)].prediction == pytest.approx(500 + 0.2 * (355 - 500))


@pytest.mark.parametrize(("considered", "best"), [(None, 100.0), ({0, 1}, 800.0)])
def test_eq_7_2_takes_its_max_over_the_considered_actions(considered, best):
    """Algorithm 2 filters the choice only: the filtered action's 800 still counts in 7.2."""
    xcs = make([cl("##", 0, prediction=100.0, experience=100),
                cl("##", 1, prediction=800.0, experience=100)])
    assert xcs.act("01", explore=True, allowed={0}, considered=considered) == 0
    xcs.reward(0.0, done=False)
    xcs.act("01", explore=True, allowed={0}, considered=considered)
    payoff = 0.71 * best
    assert by_condition(xcs)[("##", 0)].prediction == pytest.approx(100 + 0.2 * (payoff - 100))


def test_covering_reaches_the_considered_actions_and_allowed_must_lie_among_them():
    plain = make([cl("##", 0)], n_actions=3)
    plain.act("01", explore=True, allowed={0})
    assert {c.action for c in plain.classifiers()} == {0}
    wide = make([cl("##", 0)], n_actions=3)
    wide.act("01", explore=True, allowed={0}, considered={0, 2})
    assert {c.action for c in wide.classifiers()} == {0, 2}
    with pytest.raises(ValueError, match="must be among the considered actions"):
        make([cl("##", 0)], n_actions=3).act("01", allowed={0, 1}, considered={0})


class _Recorder:
    """A task learner that remembers what each act was given."""

    def __init__(self) -> None:
        self.calls: list[dict] = []

    def act(self, state, explore=True, allowed=None, *, considered=None) -> int:
        self.calls.append({"allowed": allowed, "considered": considered})
        return 0

    def reward(self, r, done) -> None: ...

    def end_trial(self) -> None: ...


def test_the_filter_scope_decides_what_eq_7_2_and_covering_see():
    table = AffordanceTable()
    table.update("1100", "010", 0)  # pushing the fixed box moved nothing
    actions = ("000", "001", "011", "010")
    for scope, considered in (("choice", range(4)), ("choice_and_value", None)):
        learner = _Recorder()
        AffordanceXCS(learner, actions, table, filter_scope=scope).act("1100", "1100", True)
        call = learner.calls[0]
        assert call["allowed"] == {0, 1, 2}
        assert (call["considered"] if considered is None else list(call["considered"])) == (
            considered if considered is None else list(considered))
    learner = _Recorder()  # preconditions bound both the choice and the value
    AffordanceXCS(learner, actions, table).act("1100", "1100", True, applicable=(0, 3))
    assert learner.calls[0] == {"allowed": {0}, "considered": (0, 3)}
    with pytest.raises(ValueError, match="unknown filter_scope"):
        AffordanceXCS(_Recorder(), actions, filter_scope="values")


# -- the chapter-3 tasks ------------------------------------------------------------------------


def test_stacking_pushes_only_with_an_object_in_front():
    task = StackingTask.__new__(StackingTask)
    task.push_needs_object = True
    task._choices = tuple(i for i, code in enumerate(STACKING_ACTIONS)
                          if STACKING_ACTIONS[code].startswith("choose"))
    assert task.applicable(View("0000000", None)) == (2, 3)  # choose box, choose foam
    assert task.applicable(View("1001100", "1001")) is None
    task.push_needs_object = False
    assert task.applicable(View("0000000", None)) is None


@pytest.mark.parametrize(("lane", "exchanged", "best"), [
    (LANES[0], False, 1000.0), (LANES[1], False, 1000.0), (LANES[2], False, 900.0),
    (LANES[3], False, 800.0), (LANES[0], True, 800.0), (LANES[2], True, 1000.0)])
def test_the_best_payoff_of_a_navigation_start(lane, exchanged, best):
    """Eqs 3.14 and 3.16: -100 per step sideways to a lane facing the movable box, +1000."""
    assert NavigationTask.best_payoff(lane, exchanged) == best


def test_trials_start_anywhere_on_the_start_side_drawn_from_the_seed():
    task = NavigationTask.__new__(NavigationTask)
    task.start, task.seed = "anywhere", 3
    lanes = [task.start_lane(trial) for trial in range(40)]
    assert set(lanes) == set(LANES) and lanes == [task.start_lane(t) for t in range(40)]
    task.start = "right_lane"
    assert {task.start_lane(trial) for trial in range(5)} == {LANES[0]}


# -- chapter 4 ----------------------------------------------------------------------------------


class _Line:
    action_bounds = ((-0.01, 0.01),)

    def __init__(self) -> None:
        self.state = 0.05

    def observe(self) -> float:
        return self.state

    def step(self, action) -> float:
        self.state += float(action[0])
        return self.state


def test_the_state_unit_scales_what_algorithm_3_sees():
    world = ScaledState(_Line(), 100.0)
    assert world.action_bounds == ((-0.01, 0.01),)
    assert world.observe() == pytest.approx(5.0)
    assert world.step(np.array([0.01])) == pytest.approx(6.0)


def test_a_grid_without_its_upper_end_gives_table_4_1s_actions():
    bounds = ActionBounds([(-0.01, 0.01)])
    assert candidate_actions(bounds, 10, endpoint=False)[:, 0] == pytest.approx(
        [-0.010, -0.008, -0.006, -0.004, -0.002, 0.0, 0.002, 0.004, 0.006, 0.008])
    assert candidate_actions(bounds, 11)[[0, -1], 0] == pytest.approx([-0.01, 0.01])


# -- chapter 5 ----------------------------------------------------------------------------------


def test_eq_5_10_aims_at_the_goal_or_delta1_above_it():
    assert OpeningGoal(0.1, 0.03, "goal").desired_effect(0.02) == pytest.approx(0.08)
    assert OpeningGoal(0.1, 0.03, "goal_plus_delta1").desired_effect(0.02) == pytest.approx(0.11)
    with pytest.raises(ValueError, match="aim must be one of"):
        OpeningGoal(0.1, 0.03, "above")
    source = PartActionModel().fit([0.02, 0.04], [0.02, 0.04], [0.04, 0.08])  # h slope 2
    step = {aim: gradient_step(0.05, source, 0.06, OpeningGoal(0.1, 0.03, aim), (0.0, 0.1))
            for aim in ("goal", "goal_plus_delta1")}
    assert step["goal"] == pytest.approx(0.05 + 0.04 / 2)  # the missing 0.04 m, ĥ slope 2
    assert step["goal_plus_delta1"] == pytest.approx(0.05 + 0.07 / 2)


def test_moving_non_functional_pairs_are_those_whose_g_reaches_a_centimetre():
    def pair(part, action, slope):
        return PairModel(part=part, action=action, n=5, g=(0.0, slope), h=(0.0, 0.0))

    row = BaselineRow(part="handle", action="lift_up", theta=0.05, opening=0.12, n=61,
                      models=[pair("handle", "lift_up", 1.0), pair("handle", "extend_arm", 0.2),
                              pair("lid", "extend_arm", 0.05), pair("body", "sweep_left", 0.0)])
    assert [(m.part, m.action) for m in moving_nonfunctional(row)] == [("handle", "extend_arm")]


# -- every page shows its choices ------------------------------------------------------------------


class _Choices(ScaledConfig):
    plain: int = 1
    """Not a choice."""
    open_one: Annotated[bool, Reading("§9.9: the thesis says so.")] = True
    """What the code does with it."""


def test_a_page_lists_each_open_choice_and_fixed_deviation():
    from robot.reproduce.framework.pages import deviations_text

    study = Study(name="toy-choices", description="a toy", config=_Choices, result=None,
                  run=None, metrics=lambda c: [], figures=lambda c, s: [],
                  deviations=(Deviation("Robot", "a NAO.", "a block."),))
    text = deviations_text(study, {"scale": 1.0, "plain": 2, "open_one": False})
    assert "| `open_one` | §9.9: the thesis says so. | **false** (default true) | What the " \
           "code does with it. |" in text
    assert "`plain`" not in text and "- **Robot**. Thesis: a NAO. Here: a block." in text
    assert "swept" in deviations_text(study, {"open_one": True}, grid=["open_one"])


def test_every_study_declares_its_deviations():
    for study in registered():
        config = study.default_config().model_dump(mode="json")
        readings = [key for key in config if study.config.reading(key) is not None]
        assert study.deviations or readings, study.name
