"""Algorithm 3 (thesis §4.4.3) and skill acquisition (§4.5) on small synthetic worlds."""

from __future__ import annotations

import numpy as np
import pytest
from sklearn.base import clone

from behaviours.learners.cacla import TDConvergence
from behaviours.learners.exploration import ActiveExplorer, ContinuousWorld
from behaviours.learners.forward_model import ForwardModel
from behaviours.learners.skill_acquisition import (
    acquire_skills,
    candidate_actions,
    goal_action,
)
from behaviours.learners.theta_exploration import ThetaWorld, explore_theta
from behaviours.learners.validation import ActionBounds

STEP = 0.01


class Slider:
    """A part on a rail: Δx moves it by ``gain``·Δx, clipped to [0, top]; Δy, Δz do nothing."""

    def __init__(self, dims: int = 1, gain: float = 1.5, top: float = 0.15) -> None:
        self.action_bounds = [(-STEP, STEP)] * dims
        self.gain, self.top, self.position = gain, top, 0.0
        self.actions: list[np.ndarray] = []

    def observe(self) -> float:
        return self.position

    def step(self, action: np.ndarray) -> float:
        # each action within the bounds, checked in plain numpy (NaN fails too): this runs
        # at every step of every exploration, where scikit-learn's check_array was a third of
        # the file's time
        assert action.shape == (len(self.action_bounds),), action
        assert np.all(np.abs(action) <= STEP * (1 + 1e-12)), action
        self.actions.append(np.array(action))
        self.position = float(np.clip(self.position + self.gain * action[0], 0.0, self.top))
        return self.position


def test_a_slider_is_a_continuous_world() -> None:
    assert isinstance(Slider(), ContinuousWorld)


def test_one_exploration_records_algorithm_3_step_by_step() -> None:
    world = Slider(dims=3)
    explorer = ActiveExplorer(n_max=60, random_state=1).explore(world)
    h = explorer.history_
    n = h.steps
    assert explorer.n_steps_ == n == len(world.actions) and 21 <= n <= 60
    assert np.array_equal(h.actions, np.array(world.actions))
    assert np.all(np.abs(h.actions) <= STEP)
    assert np.allclose(h.states[1:, 0], h.states[:-1, 0] + h.effects[:-1, 0])  # s' is next s
    assert np.allclose(h.effects[:, 0], np.clip(h.states[:, 0] + 1.5 * h.actions[:, 0], 0,
                                                 0.15) - h.states[:, 0])  # 4.20
    assert np.allclose(h.rewards, np.abs(h.effects[:, 0] - h.predictions[:, 0]))  # 4.3, 4.6
    assert np.array_equal(h.td_errors, explorer.cacla_.td_errors_)
    # replaying the TD errors through (4.10)-(4.11) stops at the same step
    test = TDConvergence(20, 1e-4)
    stops = [k for k, d in enumerate(h.td_errors, start=1) if test.update(d)]
    assert h.converged_at == (stops[0] if stops else None) and explorer.converged_ == bool(stops)
    assert np.isnan(h.averaged[:19]).all() and h.averaged[19:] == pytest.approx(test.averages)
    assert explorer.forward_model_.n_samples_seen_ == n


def test_modes_share_the_first_random_actions_and_then_part() -> None:
    """Same seed: active and random draw the same first N = 20 actions (a paired comparison)."""
    runs = {mode: ActiveExplorer(mode=mode, n_max=40, tol=1e-12, random_state=3).explore(
        Slider()).history_ for mode in ("active", "random")}
    assert runs["active"].steps == runs["random"].steps == 40  # tol tiny: never converged
    assert np.array_equal(runs["active"].actions[:20], runs["random"].actions[:20])
    assert not np.array_equal(runs["active"].actions[20:], runs["random"].actions[20:])
    assert runs["active"].converged_at is None


def test_active_exploration_follows_its_actor() -> None:
    """After the random start, actions are the actor's mean plus N(0, σ²) noise (4.5)."""
    explorer = ActiveExplorer(n_max=200, n_random=0, tol=1e-12, sigma=0.01,
                              random_state=0).explore(Slider())
    unit = explorer.history_.actions[:, 0] / STEP
    assert np.abs(np.diff(unit)).mean() < 0.05  # a narrow Gaussian around a slow actor
    random = ActiveExplorer(mode="random", n_max=200, tol=1e-12, random_state=0).explore(Slider())
    assert np.abs(np.diff(random.history_.actions[:, 0] / STEP)).mean() > 0.4


def test_active_converges_in_more_runs_than_random_on_a_big_slider() -> None:
    """3-D actions, only Δx matters, effects up to 2 per step on a rail of 4 (see docstring).

    With the thesis's N = 20 and ε = 1e-4, (4.10) asks two TD errors 20 steps apart to agree
    within 0.002, so it separates the modes only where effects are large against that. Here
    the actor soon pushes the part to an end, where nothing changes any more and the TD error
    settles; random actions keep moving it. Measured on seeds 0–19, 20–39, 40–59: active 13, 15
    and 11 runs converged within N_s = 300, random 2, 4 and 1.
    """
    converged = {}
    for mode in ("active", "random"):
        runs = [ActiveExplorer(mode=mode, n_max=300, random_state=seed).explore(
            Slider(dims=3, gain=200, top=4.0)) for seed in range(20)]
        converged[mode] = sum(run.converged_ for run in runs)
    assert converged["active"] >= converged["random"] + 5, converged


class BrokenWorld(Slider):
    def step(self, action: np.ndarray) -> float:
        return float("nan")


def test_bad_worlds_and_parameters_give_clear_errors() -> None:
    with pytest.raises(ValueError, match="Input the world's next state contains NaN"):
        ActiveExplorer(random_state=0).explore(BrokenWorld())
    with pytest.raises(ValueError, match="'mode' parameter of ActiveExplorer must be a str among"):
        ActiveExplorer(mode="curious").explore(Slider())
    with pytest.raises(ValueError, match="'n_max' parameter of ActiveExplorer must be an int"):
        ActiveExplorer(n_max=0).explore(Slider())
    bad_bounds = Slider()
    bad_bounds.action_bounds = [(0.01, -0.01)]
    with pytest.raises(ValueError, match="lo < hi"):
        ActiveExplorer().explore(bad_bounds)
    assert clone(ActiveExplorer(mode="random", random_state=2)).get_params()["mode"] == "random"


def test_candidate_actions_are_an_even_grid() -> None:
    grid = candidate_actions(ActionBounds([(-STEP, STEP)] * 3))
    assert grid.shape == (11**3, 3)
    assert sorted(set(np.round(grid[:, 0], 6))) == pytest.approx(
        [-0.01, -0.008, -0.006, -0.004, -0.002, 0.0, 0.002, 0.004, 0.006, 0.008, 0.01])


class TableModel:
    """A stand-in forward model whose predictions are a fixed table over A_M."""

    def __init__(self, effects: list[float]) -> None:
        self.effects = np.array(effects)

    def predict_effects(self, state: object, actions: np.ndarray) -> np.ndarray:
        return self.effects[: len(actions)]


def test_goal_generation_picks_the_extreme_prediction() -> None:
    """Eq. 4.12–4.13 (max) and 4.16–4.17 (min) over A_M."""
    candidates = np.array([[-0.01], [0.0], [0.01]])
    model = TableModel([-0.02, 0.001, 0.03])
    assert goal_action(model, 0.0, candidates) == (pytest.approx([0.01]), 0.03)
    assert goal_action(model, 0.0, candidates, maximise=False) == (pytest.approx([-0.01]), -0.02)


def trained_model(world: Slider, dims: int, samples: int = 1500) -> ForwardModel:
    """A forward model trained on random (state, action) → effect samples of the slider."""
    rng = np.random.RandomState(0)
    model = ForwardModel(action_bounds=world.action_bounds, random_state=0)
    for _ in range(samples):
        state = rng.uniform(0, world.top)
        action = rng.uniform(-STEP, STEP, dims)
        effect = np.clip(state + world.gain * action[0], 0, world.top) - state
        model.partial_fit(np.concatenate([[state], action])[None, :], [effect])
    return model


@pytest.mark.parametrize("dims", [1, 3])
def test_skill_acquisition_opens_then_closes(dims: int) -> None:
    world = Slider(dims=dims)
    model = trained_model(world, dims)
    opening, closing = acquire_skills(model, world, tau=0.01)
    assert opening.phase == "maximise" and closing.phase == "minimise"
    assert opening.terminated and closing.terminated
    assert all(step.action[0] > 0 for step in opening.steps)  # SK*: push, Δx > 0
    assert all(step.action[0] < 0 for step in closing.steps)  # SK_*: pull back
    assert abs(opening.steps[-1].effect) < 0.01 and abs(closing.steps[-1].effect) < 0.01
    assert opening.steps[0].state == 0.0 and opening.steps[-1].state > 0.12
    assert closing.steps[-1].state + closing.steps[-1].effect < 0.03
    first = opening.steps[0]
    assert first.goal == pytest.approx(float(model.predict_effects([0.0], [first.action])[0]))
    assert first.effect == pytest.approx(world.gain * first.action[0])


def test_skill_acquisition_stops_after_max_steps_when_effects_never_vanish() -> None:
    world = Slider(gain=1.5, top=100.0)
    opening, _ = acquire_skills(trained_model(Slider(), 1), world, tau=1e-6, max_steps=4)
    assert not opening.terminated and len(opening.steps) == 4


def test_theta_worlds_start_every_try_from_the_same_state() -> None:
    world = ThetaWorld(lambda theta: 2.0 * theta, (0.0, 0.1), state=0.03)
    assert world.action_bounds == [(pytest.approx(1e-4), 0.1)]  # lo < θ: lo is no action
    assert world.step(np.array([0.05])) == pytest.approx(0.13)
    assert world.observe() == 0.03 and world.step(np.array([0.01])) == pytest.approx(0.05)
    with pytest.raises(ValueError, match=r"returned nan for theta=0\.0100"):
        ThetaWorld(lambda theta: float("nan"), (0.0, 0.1), 0.0).step(np.array([0.01]))


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_active_theta_exploration_reads_e_max_off_the_forward_model(seed: int) -> None:
    """A lid that opens 2.2 m per m of push up to 0.11 m: e_max ≥ δ = 0.1 at the top (6.8)."""
    result = explore_theta(lambda t: min(0.11, 2.2 * t), bounds=(0.0, 0.1), state=0.0,
                           random_state=seed)
    assert 21 <= result.samples <= 100 and result.converged
    assert np.allclose(result.effects, np.minimum(0.11, 2.2 * result.thetas))
    assert np.all((result.thetas > 0.0) & (result.thetas <= 0.1))
    grid = np.linspace(1e-4, 0.1, 101)[:, None]
    predicted = result.forward_model.predict_effects([0.0], grid)
    assert result.e_max == pytest.approx(predicted.max()) and result.e_max >= 0.1
    assert result.theta_max == pytest.approx(grid[np.argmax(predicted), 0])
    assert result.theta_max > 0.05


def test_active_theta_exploration_of_a_useless_action_predicts_little() -> None:
    result = explore_theta(lambda t: 0.0, bounds=(0.0, 0.1), state=0.0, random_state=0)
    assert result.e_max < 0.05 and np.all(result.effects == 0.0)


def test_running_on_past_convergence_keeps_the_run_and_its_stop_step() -> None:
    stopped = ActiveExplorer(n_max=80, random_state=4).explore(Slider()).history_
    whole = ActiveExplorer(n_max=80, random_state=4, stop=False).explore(Slider()).history_
    assert stopped.converged_at is not None and whole.converged_at == stopped.converged_at
    assert whole.steps == 80 > stopped.steps == stopped.converged_at
    assert np.array_equal(whole.actions[: stopped.steps], stopped.actions)
    assert np.array_equal(whole.td_errors[: stopped.steps], stopped.td_errors)
    ran_on = ActiveExplorer(n_max=80, random_state=4, stop=False).explore(Slider())
    stop_here = ActiveExplorer(n_max=80, random_state=4).explore(Slider())
    grid = np.array([[0.05, a] for a in np.linspace(-0.01, 0.01, 5)])
    assert np.array_equal(ran_on.stopped_model_.predict(grid),
                          stop_here.forward_model_.predict(grid))
    assert stop_here.stopped_model_ is stop_here.forward_model_
    assert not np.array_equal(ran_on.forward_model_.predict(grid),
                              ran_on.stopped_model_.predict(grid))
