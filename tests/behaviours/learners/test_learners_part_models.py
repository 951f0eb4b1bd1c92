"""Part models of thesis §5.4 on hand-computed values: ĝ, ĥ (5.16-5.18), 5.19, 5.9, 5.11, 5.12."""

from __future__ import annotations

import numpy as np
import pytest
from sklearn.base import clone

from behaviours.learners.part_models import (
    OpeningGoal,
    PartActionModel,
    select_parameter,
    select_part_action,
)

BOUNDS = {"push": (0.0, 0.1), "lift": (0.0, 0.1)}


def test_g_and_h_are_least_squares_lines():
    # e_ψ = 0.01 + 0.5 θ exactly; e_o = 2 e_ψ exactly
    theta = np.array([0.02, 0.04, 0.08])
    model = PartActionModel().fit(theta, 0.01 + 0.5 * theta, 2 * (0.01 + 0.5 * theta))
    assert model.g_intercept_ == pytest.approx(0.01)
    assert model.g_slope_ == pytest.approx(0.5)
    assert model.h_intercept_ == pytest.approx(0.0, abs=1e-12)
    assert model.h_slope_ == pytest.approx(2.0)
    assert model.predict_displacement(0.06)[0] == pytest.approx(0.04)
    assert model.predict(0.06)[0] == pytest.approx(0.08)


def test_residual_sum_of_squares_is_eq_5_18():
    # three points off a line: the fit of (0,0), (1,1), (2,0) is y = 1/3, RSS = 2/3
    model = PartActionModel().fit([0.0, 1.0, 2.0], [0.0, 1.0, 0.0], [0.0, 0.0, 0.0])
    assert model.g_slope_ == pytest.approx(0.0, abs=1e-12)
    assert model.g_intercept_ == pytest.approx(1 / 3)
    assert model.g_rss_history_[-1] == pytest.approx(2 / 3)


def test_one_sample_gives_the_line_through_the_origin():
    model = PartActionModel().fit([0.05], [0.04], [0.1])
    assert (model.g_intercept_, model.g_slope_) == (0.0, pytest.approx(0.8))
    assert (model.h_intercept_, model.h_slope_) == (0.0, pytest.approx(2.5))


def test_settling_needs_two_fits_and_a_small_change_of_rss():
    model = PartActionModel()
    model.partial_fit(0.02, 0.0, 0.0)
    assert not model.settled(1e-4)  # one RSS only
    model.partial_fit(0.05, 0.0, 0.0)
    assert model.settled(1e-4)  # 0 -> 0
    model.partial_fit(0.09, 0.05, 0.0)  # an outlier raises the RSS of ĝ
    assert model.g_rss_history_[-1] > 1e-4
    assert not model.settled(1e-4)
    model.partial_fit(0.07, 0.03, 0.0)
    assert model.n_samples_ == 4


def test_partial_fit_equals_fit_on_everything():
    rng = np.random.default_rng(0)
    theta, disp, eff = rng.uniform(0, 0.1, (3, 6))
    stepwise = PartActionModel()
    for t, d, e in zip(theta, disp, eff, strict=True):
        stepwise.partial_fit(t, d, e)
    whole = PartActionModel().fit(theta, disp, eff)
    assert stepwise.g_slope_ == pytest.approx(whole.g_slope_)
    assert stepwise.h_intercept_ == pytest.approx(whole.h_intercept_)


def test_bad_input_is_a_clear_value_error():
    with pytest.raises(ValueError, match="inconsistent numbers of samples"):
        PartActionModel().fit([0.1, 0.2], [0.1], [0.1])
    with pytest.raises(ValueError, match="Input theta contains NaN"):
        PartActionModel().fit([np.nan], [0.1], [0.1])
    with pytest.raises(ValueError, match="at least one row"):
        PartActionModel().fit([], [], [])
    with pytest.raises(ValueError, match="must have 1 column"):
        PartActionModel().fit([[0.1, 0.2]], [0.1], [0.1])
    with pytest.raises(ValueError, match="not fitted"):
        PartActionModel().predict(0.1)
    with pytest.raises(ValueError, match="delta1"):
        OpeningGoal(0.1, -1.0)
    assert clone(PartActionModel()).get_params() == {}


def test_goal_test_5_9_counts_a_wider_opening_as_reached():
    goal = OpeningGoal(goal=0.1, delta1=0.02)
    assert goal.reached(0.1) and goal.reached(0.14)
    assert not goal.reached(0.099)
    assert goal.desired_effect(0.0) == pytest.approx(0.12)
    assert goal.desired_effect(0.05) == pytest.approx(0.07)


def _model(g: tuple[float, float], h: tuple[float, float]) -> PartActionModel:
    theta = np.array([0.02, 0.06, 0.1])
    disp = g[0] + g[1] * theta
    return PartActionModel().fit(theta, disp, h[0] + h[1] * disp)


def test_parameter_selection_5_12_takes_the_smallest_theta_within_delta2():
    model = _model((0.0, 1.0), (0.0, 1.0))  # ĝ(θ) = θ
    assert select_parameter(model, 0.05, (0.0, 0.1), 0.002) == pytest.approx(0.048)
    assert select_parameter(model, 0.2, (0.0, 0.1), 0.002) is None  # out of Θ
    assert select_parameter(model, 0.0, (0.0, 0.1), 0.002) == pytest.approx(1e-4)  # open end
    flat = _model((0.03, 0.0), (0.0, 1.0))
    assert select_parameter(flat, 0.031, (0.0, 0.1), 0.002) == pytest.approx(1e-4)
    assert select_parameter(flat, 0.05, (0.0, 0.1), 0.002) is None
    with pytest.raises(ValueError, match="delta2"):
        select_parameter(model, 0.05, (0.0, 0.1), 0.0)


def test_part_and_action_selection_5_11_on_hand_made_models():
    models = {
        # the lid: ĝ = θ, ĥ = 2 e_ψ; at most 0.2 of opening: reaches 0.12 with e_ψ = 0.06
        ("lid", "push"): _model((0.0, 1.0), (0.0, 2.0)),
        # the body: moves, opens a little; best it can do is 0.3 * 0.05 = 0.015
        ("body", "push"): _model((0.0, 0.5), (0.0, 0.3)),
        # the handle: does not move at all
        ("handle", "lift"): _model((0.0, 0.0), (0.0, 0.0)),
    }
    choice = select_part_action(models, BOUNDS, 0.12, delta1=0.02, delta2=0.002)
    assert choice.pair == ("lid", "push")
    assert choice.displacement == pytest.approx(0.06)
    assert choice.error == pytest.approx(0.0, abs=1e-9)
    assert choice.theta == pytest.approx(0.058)
    without_lid = select_part_action(models, BOUNDS, 0.12, delta1=0.02, delta2=0.002,
                                     exclude={("lid", "push")})
    assert without_lid.pair == ("body", "push")
    assert without_lid.error == pytest.approx(0.12 - 0.015)
    assert select_part_action({}, BOUNDS, 0.12, delta1=0.02, delta2=0.002) is None


def test_among_pairs_that_reach_the_goal_the_smallest_motion_wins():
    models = {
        ("lid", "push"): _model((0.0, 1.0), (0.0, 2.0)),  # θ* ≈ 0.058
        ("handle", "lift"): _model((0.0, 2.0), (0.0, 2.0)),  # θ* ≈ 0.029
    }
    choice = select_part_action(models, BOUNDS, 0.12, delta1=0.02, delta2=0.002)
    assert choice.pair == ("handle", "lift")
    assert choice.theta == pytest.approx(0.029)
    with pytest.raises(ValueError, match="no parameter bounds"):
        select_part_action(models, {"push": (0.0, 0.1)}, 0.12, delta1=0.02, delta2=0.002)
