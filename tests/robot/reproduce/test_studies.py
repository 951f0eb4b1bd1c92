"""Every study at its quick size, run in this process, checked for what it measured (not for
which keys exist); each committed sweep's first parameter at that size (issue 28), the way
``goalagent sweep`` runs it; and the studies' own statistics on hand-made seeds. The quick runs
and the sweeps share one seed cache, as a user's runs do: a sweep's cell at the study's quick
values takes its seed from the quick run instead of running it again."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from robot.reproduce.framework.backends import LocalBackend
from robot.reproduce.framework.cache import Cache
from robot.reproduce.framework.registry import UnknownStudy, find, registered
from robot.reproduce.framework.runner import reproduce
from robot.reproduce.framework.settings import apply, parse_grid
from robot.reproduce.framework.statistics import summarize
from robot.reproduce.framework.sweeps import sweep
from robot.reproduce.studies import ch4_agent, ch4_exploration, ch4_skills
from robot.reproduce.studies.common.ch4 import CONFIGURATIONS, METHODS, Exploration
from robot.reproduce.studies.common.tasks import experienced_rules, majority_movability

pytestmark = pytest.mark.heavy  # run first (tests/conftest.py)

NAMES = ("appA-params", "appA-search", "ch3-baselines", "ch3-navigation", "ch3-stacking",
         "ch4-agent", "ch4-exploration", "ch4-exploration-camera", "ch4-skills", "ch5-agent",
         "ch5-baseline", "ch5-transfer", "xcs-maze4", "xcs-mux", "xcs-woods2")


def quick(name: str, out: Path, seeds: int = 2, settings: tuple[str, ...] = (),
          cache: Cache | None = None):
    """The study at its quick size, ``settings`` (KEY=VALUE) applied, its seeds kept in
    ``cache``: (document, typed results, page, metrics by key)."""
    study = find(name)
    config = apply(study, study.quick_config(), list(settings))
    outcome = reproduce(study, config, list(range(seeds)), LocalBackend(1), out, cache=cache)
    page = (out / f"{name}.md").read_text()
    assert f"# {name}" in page and "## Claims and tests" in page
    assert all(f"]({path.name})" in page for path in outcome.files if path.suffix == ".png")
    metrics = {row.key: row for row in outcome.document.summary.metrics}
    return outcome.document, outcome.document.results(study), page, metrics


def test_every_study_is_registered_by_name_and_unknown_names_get_close_ones():
    assert tuple(study.name for study in registered()) == NAMES
    with pytest.raises(UnknownStudy, match="did you mean 'xcs-mux'"):
        find("xcs-mx")
    for study in registered():  # every claim names metrics the study has
        config = study.default_config()
        keys = {metric.key for metric in study.metrics(config)}
        assert len(keys) == len(study.metrics(config))
        for claim in study.claims(config):
            assert claim.metric in keys and (not isinstance(claim.versus, str)
                                             or claim.versus in keys)
        assert set(study.headline) <= keys
        assert all(study.config.describe(key) for key in study.config.model_fields)


def test_xcs_mux_learns_the_multiplexers(tmp_path):
    document, seeds, _, metrics = quick("xcs-mux", tmp_path)
    assert document.config["scale"] == 0.05 and document.config["N"] is None
    for seed in seeds:
        assert seed.mux6.problems == list(range(50, 501, 50))  # 10,000 x 0.05, every 50
        assert 0.5 < seed.mux6.final_accuracy <= 1.0
        assert seed.mux6.macro_classifiers[-1] == seed.mux6.final_macro_classifiers <= 400
        assert seed.mux11.problems[-1] == 1500
    assert metrics["mux6.final_accuracy"].mean == np.mean([s.mux6.final_accuracy
                                                           for s in seeds])


def test_xcs_in_the_woods_never_beats_the_maps_optimum(tmp_path):
    _, seeds, _, metrics = quick("xcs-woods2", tmp_path / "woods")
    assert all(seed.optimum == 1.6875 and seed.final_steps >= 1 for seed in seeds)
    assert metrics["woods2.final_steps_over_optimum"].reference == 1.6875
    _, seeds, page, _ = quick("xcs-maze4", tmp_path / "maze", seeds=1)
    (seed,) = seeds
    assert seed.specific.optimum == 3.5 and seed.generalising.problems == [50, 100]
    assert "XCS without # (P# = 0, μ = 0)" in page


def test_table_7_1_runs_on_the_classic_problems(tmp_path):
    document, seeds, _, _ = quick("appA-params", tmp_path, seeds=1)
    assert (document.config["N"], document.config["theta_ga"], document.config["p_hash"]) == (
        100, 5, 0.6)
    assert seeds[0].woods2.final_macro_classifiers <= 100
    assert seeds[0].mux6_larger_n.final_macro_classifiers <= 400


def _is_movability(rows) -> bool:
    return all(len(obj) == 4 and set(obj) <= {"0", "1"} and len(action) == 3
               and set(action) <= {"0", "1"} and effect in (0, 1) for obj, action, effect in rows)


@pytest.fixture(scope="module")
def seed_cache(tmp_path_factory) -> Cache:
    """The module's seed cache, shared by the quick runs and the sweeps."""
    return Cache(tmp_path_factory.mktemp("cache"))


@pytest.fixture(scope="module")
def navigation(tmp_path_factory, seed_cache):
    """ch3-navigation's quick run, its seeds cached for the sweep over learn_in_exploit."""
    return quick("ch3-navigation", tmp_path_factory.mktemp("ch3-navigation"), cache=seed_cache)


@pytest.fixture(scope="module")
def search(tmp_path_factory, seed_cache):
    """appA-search's quick run, its seeds cached for the sweep over consistent_actions."""
    return quick("appA-search", tmp_path_factory.mktemp("appA-search"), cache=seed_cache)


def test_ch3_navigation_learns_which_box_moves(navigation):
    _, seeds, page, metrics = navigation
    for seed in seeds:
        assert seed.trials == 4  # 20 x 0.2
        for mode in (seed.truth, seed.camera):
            for run in (mode.affordance_xcs, mode.standard_xcs):
                assert _is_movability(run.movability)
                assert all(effect == {"1001": 1, "1100": 0}[obj]
                           for obj, _, effect in run.movability)  # every push taught the truth
                assert all(1 <= steps <= 10 for steps in run.steps)
                assert run.explore == [1, 0, 1, 0] and all(len(rule) == 9 for rule in run.rules)
    assert metrics["knows_fixed"].mean == 1.0 and metrics["camera_identical"].mean == 1.0
    assert "## Learned movability (Table 3.3" in page and "## XCS rules of the first seed" in page


def test_ch3_stacking_learns_pose_dependent_movability(tmp_path):
    _, seeds, page, metrics = quick("ch3-stacking", tmp_path)
    table = {(o, a): e for o, a, e in majority_movability([s.truth.movability for s in seeds])}
    assert table.get(("0010", "101"), 1) == 1 and table.get(("1001", "100"), 1) == 1
    assert metrics["truth.chooses_box"].mean in (0.0, 0.5, 1.0)
    assert "Chosen object (first choice of the last exploit trial), truth: {" in page


def test_appA_search_looks_for_the_target_before_and_after_it_moves(search):
    _, seeds, page, metrics = search
    for place in ("up_left", "right"):
        assert all(3 <= metrics[f"{mode}.{place}.last_exploit_steps"].mean <= 20
                   for mode in ("truth", "camera"))
    assert all(seed.per_place == 4 and len(seed.truth.steps) == 8 for seed in seeds)
    assert "## XCS rules of the first seed, truth (Table 7.2 style" in page


def test_the_rule_listing_and_the_majority_table():
    rules = [(1, "1###", "010", 5.0, 1.0, 0.2, 2.0, 3, 1), (2, "#0##", "000", 5.0, 1.0, 0.2,
                                                            2.0, 9, 1),
             (3, "##1#", "001", 5.0, 1.0, 0.2, 2.0, 0, 1), (4, "###0", "011", 5.0, 1.0, 0.2,
                                                            2.0, 7, 1)]
    assert [row[0] for row in experienced_rules(rules, 2)] == [2, 4]
    tables = [[("1100", "010", 0), ("1001", "010", 1)], [("1001", "010", 1),
                                                        ("1100", "010", 1)],
              [("0010", "100", 0)]]
    assert majority_movability(tables) == [("1100", "010", 0), ("1001", "010", 1),
                                           ("0010", "100", 0)]


def exploration(steps: dict[tuple[str, str], int | None]) -> Exploration:
    """A hand-made ch4-exploration seed."""
    averaged = [None] * 19 + [0.5, 0.6, 0.60005, 0.7, 0.70002]  # (4.10) holds at 2 of 4
    run = {"states": [0.0, 0.01, 0.004], "td_errors": [0.1, -0.2, 0.0, 0.3] * 6,
           "effects": [0.02] * 20 + [0.0, 0.005, 0.03, 0.0], "averaged": averaged,
           "actions": [[0.0]], "steps": 24, "surface": [[-0.01, 0.0, 0.02]] * 5}
    return Exploration(perception="truth", configurations={
        name: {method: {**run, "converged_at": steps.get((name, method))} for method in METHODS}
        for name in CONFIGURATIONS})


def test_ch4_exploration_statistics_on_hand_made_seeds():
    seeds = [exploration({("lid-1d", "active"): 30, ("lid-1d", "random"): None}),
             exploration({("lid-1d", "active"): 41, ("lid-1d", "random"): 25}),
             exploration({("lid-1d", "active"): 35})]
    config = ch4_exploration.ScaledExplorationConfig()
    summary = summarize(ch4_exploration.metrics(config), ch4_exploration.claims(config), seeds)
    rows = {row.key: row for row in summary.metrics}
    assert rows["lid-1d.random.converged"].mean == pytest.approx(1 / 3)
    assert rows["lid-1d.active.converged_at"].mean == pytest.approx(106 / 3)
    assert rows["lid-1d.active.converged_at"].sd == pytest.approx(np.std([30, 41, 35], ddof=1))
    assert rows["handle-3d.random.converged_at"].n == 0
    assert rows["lid-1d.random.largest_state"].mean == 0.01
    assert rows["lid-1d.random.positive_td"].mean == 0.5
    assert rows["lid-1d.random.stable_share"].mean == 0.75
    assert rows["lid-1d.active.firing_share"].mean == pytest.approx(2 / 4)
    assert rows["lid-1d.active.td_spread"].mean == pytest.approx(np.std([0.1, 0.2, 0.0, 0.3]))
    assert rows["lid-1d.active.averaged_at_end"].mean == 0.70002
    assert rows["lid-1d.active.opens_as_thesis"].mean == 1.0  # rises: extend opens the lid
    assert rows["handle-1d.random.opens_as_thesis"].mean == 0.0  # pulling opens the handle
    assert "lid-3d.active.opens_as_thesis" not in rows
    converged = next(c for c in summary.comparisons if c.metric == "lid-1d.active.converged")
    assert (converged.n, converged.mean_difference, converged.verdict) == (
        3, pytest.approx(2 / 3), "not supported")


def test_ch4_variant_criteria_are_listed_beside_the_thesis():
    """Active: |δ| constant (after-transient at 41, sustained and window-to-window at 40);
    random: one error of 0.01 more at k = 35 in a spike every 10 steps (75, 41, 75, 75)."""
    spiky = [0.01 if k % 10 == 0 or k == 35 else 0.0 for k in range(1, 101)]
    seed = exploration({})
    for runs in seed.configurations.values():
        runs["active"] = runs["active"].model_copy(update={
            "converged_at": 21, "td_errors": [-0.05] * 100, "averaged": [None] * 19 + [0.05] * 81})
        runs["random"] = runs["random"].model_copy(update={
            "td_errors": spiky, "averaged": [None] * 19 + [0.001] * 81})
    listing = ch4_exploration.variant_listing(ch4_exploration.ScaledExplorationConfig(),
                                              [seed, seed])
    assert "VARIANT stop criteria — NOT the thesis's (4.10)" in listing
    assert "| lid-1d | thesis (4.10) | 2/2, 21 | 0/2, — | 2 / 0 / 0 | 0.0500 / — |" in listing
    assert ("| lid-1d | sustained (VARIANT) | 2/2, 40 | 2/2, 75 | 2 / 0 / 0 | 0.0500 / 0.0010 |"
            in listing)
    assert "| handle-3d | after-transient (VARIANT) | 2/2, 41 | 2/2, 41 | 0 / 2 / 0 |" in listing


def test_ch4_budgets_follow_the_thesis_and_shrink_with_the_scale():
    from robot.reproduce.studies.common.ch4 import SETUPS

    config = ch4_exploration.ScaledExplorationConfig()
    assert [config.budget(SETUPS[name]) for name in CONFIGURATIONS] == [100, 300, 100, 300]
    assert config.model_copy(update={"scale": 0.5}).budget(SETUPS["lid-3d"]) == 150
    assert config.model_copy(update={"scale": 0.05}).budget(SETUPS["lid-1d"]) == 22  # N + 2


@pytest.fixture(scope="module")
def scaled_exploration(tmp_path_factory, seed_cache):
    """ch4-exploration's quick run in its committed sweep's first value off the default,
    state_scale=100 (s_o in percent of the image), its seed cached for that sweep: one run
    for both tests. The unscaled state (state_scale=1) runs in ch4-skills' quick run, through
    the same ``explore``; ScaledState's arithmetic is test_fidelity.py's."""
    out = tmp_path_factory.mktemp("ch4-exploration")
    return out, quick("ch4-exploration", out, seeds=1, settings=("state_scale=100",),
                      cache=seed_cache)


def test_ch4_exploration_runs_small(scaled_exploration):
    out, (document, (seed,), _, _) = scaled_exploration
    assert document.config["state_scale"] == 100
    for name in CONFIGURATIONS:
        for method in METHODS:
            run = seed.of(name, method)
            assert run.steps == 22 == len(run.averaged)  # N_s at 5 %: 22
            assert (run.surface is not None) == name.endswith("1d")
    assert seed.of("lid-1d", "active").actions[:20] == seed.of("lid-1d", "random").actions[:20]
    assert len(list(out.glob("ch4-exploration-*.png"))) == 6


def test_ch4_skills_run_small_and_report_table_4_1_rows(tmp_path):
    _, (seed,), _, metrics = quick("ch4-skills", tmp_path, seeds=1)
    rows = seed.sequences
    assert len(rows) == 8 * 2 * 2  # forward models x trainings x phases
    assert {(r.fm, r.part, r.policy, r.dims) for r in rows} == {
        (fm, part, policy, dims) for fm, part, policy, dims, _ in ch4_skills.FORWARD_MODELS}
    assert all(abs(r.first_action[0]) <= 0.01 and len(r.first_action) == 3 for r in rows)
    assert all(r.first_action[1:] == [0.0, 0.0] for r in rows if r.dims == 1)
    share = sum(map(ch4_skills.expected_sign, [r for r in rows if r.training == "algorithm3"]))
    assert metrics["algorithm3.sign_share"].mean == share / 16


def test_ch4_agent_statistics_on_hand_made_seeds():
    def run(ended: bool, actions: int, learns: int) -> dict:
        return {"ended_as_thesis": ended, "exploratory_actions": actions,
                "learn_actions": learns, "affordances": {}}

    seeds = [ch4_agent.Result.model_validate(
        {"random": {"experiment1": run(True, 24, 5), "experiment2": run(True, 60, 11)},
         "active": {"experiment1": run(True, 155, 5), "experiment2": run(False, 296, 9)}}),
        ch4_agent.Result.model_validate(
        {"random": {"experiment1": run(True, 30, 6), "experiment2": run(True, 50, 10)},
         "active": {"experiment1": run(True, 121, 4), "experiment2": run(True, 250, 9)}})]
    config = ch4_agent.Config()
    summary = summarize(ch4_agent.metrics(config), ch4_agent.claims(config), seeds)
    rows = {row.key: row for row in summary.metrics}
    assert rows["experiment1.random.exploratory_actions"].mean == 27.0
    assert rows["experiment2.active.ended_as_thesis"].mean == 0.5
    assert rows["experiment1.active.exploratory_actions"].sd == pytest.approx(24.041631)
    fewer = next(c for c in summary.comparisons
                 if c.metric == "experiment1.active.exploratory_actions")
    assert fewer.mean_difference == 111.0 and fewer.verdict == "not supported"  # 2 seeds


def test_ch5_transfer_learns_o3_from_o1_at_once(tmp_path):
    """Aiming at the goal itself (eq. 5.10 as printed) o1's θ* leaves o3 just short of the
    one-sided goal, and one step along o1's gradient (Algorithm 6, line 13) opens it."""
    document, (seed,), page, metrics = quick("ch5-transfer", tmp_path, seeds=1,
                                             settings=("aim=goal",))
    assert document.config["cans"] == ["o1", "o3"] and document.config["aim"] == "goal"
    o1, o3 = seed.perceptions["truth"]["o1"], seed.perceptions["truth"]["o3"]
    assert (o1.source, o1.n_with, o1.n_without) == (None, 39, 39)
    assert (o3.source, o3.part, o3.action, o3.branch) == ("o1", "lid", "extend_arm", "gradient")
    assert o3.n_with == 2 < o3.n_without == 41 and o3.theta > 0 and o3.opening >= 0.1
    assert metrics["truth.o3.found"].mean == 1.0
    assert "| o3 | 41.0 | 2.0 | o1 | extend_arm(lid) (1/1) | gradient | True | 53, 1, o1 |" in page


def test_ch5_baseline_lists_every_pair_model(tmp_path):
    _, (seed,), page, metrics = quick("ch5-baseline", tmp_path, seeds=1)
    o1 = seed.perceptions["truth"]["o1"]
    assert o1.n == 39 and (o1.part, o1.action) == ("lid", "extend_arm")
    assert len(o1.models) == 12 and all(m.n >= 3 for m in o1.models)
    assert metrics["truth.o1.n_without"].reference == 36
    assert "| o1 | lid | **extend_arm** |" in page


SMALL = {
    "ch3-navigation": ({"learn_in_exploit": "false,true"}, "navigation"),
    "ch4-exploration": ({"state_scale": "100"}, "scaled_exploration"),
    "ch5-transfer": ({"sensor_noise": "0.01"}, None),
    "appA-search": ({"consistent_actions": "true,false"}, "search"),
}
"""Each committed sweep's first parameter at the study's quick size, and the quick run whose
seed 0 is a cell of it (learn_in_exploit=false and consistent_actions=true are the defaults);
ch4's and ch5's sweeps run one value off the default only (ch4's is its quick run's)."""


@pytest.mark.parametrize("name", sorted(SMALL))
def test_each_sweep_runs_small_and_says_which_cells_hold_each_claim(name, tmp_path, request,
                                                                     seed_cache):
    study = find(name)
    grid_text, quick_run = SMALL[name]
    if quick_run is not None:  # its seeds are in the cache: the sweep runs only the others
        request.getfixturevalue(quick_run)
    base = study.quick_config()
    grid = parse_grid(study, base, [f"{k}={v}" for k, v in grid_text.items()])
    outcome = sweep(study, base, grid, [0], LocalBackend(1), tmp_path, cache=seed_cache)
    assert outcome.tally.cached == (0 if quick_run is None else 1)
    assert [cell.values for cell in outcome.document.cells] == [
        {key: value} for key, values in grid.items() for value in values]
    page = (tmp_path / f"{name}-sweep-{next(iter(grid))}.md").read_text()
    assert "## Deviations and open choices" in page and "| swept |" in page
    claims = outcome.document.cells[0].summary.comparisons
    assert page.count("By cell: ") == len(claims) > 0


RESULTS = Path(__file__).resolve().parents[3] / "docs" / "results"


@pytest.mark.parametrize("name", NAMES)
def test_the_committed_results_are_what_the_code_makes_of_their_seeds(name):
    """docs/results/NAME.json's statistics and NAME.md are what the current code computes
    from the committed seeds: ``--replot`` would leave them as they are."""
    from robot.reproduce.framework.documents import read
    from robot.reproduce.framework.runner import document, figure_file, page

    study = find(name)
    committed = read(RESULTS / f"{name}.json")
    config = study.config.model_validate(committed.config)
    rebuilt = document(study, config, committed.seeds, list(committed.provenance),
                       committed.command)
    assert rebuilt == committed
    assert page(study, rebuilt) == (RESULTS / f"{name}.md").read_text()
    for figure in study.figures(config, rebuilt.results(study)):
        assert (RESULTS / figure_file(study, figure)).exists()
