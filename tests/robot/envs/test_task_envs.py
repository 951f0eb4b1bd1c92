"""The `navigation`, `stacking` and `search` EIS environments: vocabulary, refusals, files."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from behaviours.learners.affordance_table import AffordanceTable
from goalagent.eis import ActionRefused, ManagementException, load_environment
from goalagent.eis.terms import Action


def environment(name: str, **params: object):
    env = load_environment(name)()
    env.init(params)
    env.start()
    env.register_agent("robot")
    env.associate_entity("robot", "robot")
    return env


def percepts(env) -> set[str]:
    return {str(p) for p in env.get_all_percepts("robot")["robot"]}


def act(env, name: str, *args: object) -> None:
    env.perform_action("robot", Action.of(name, *args))


@pytest.fixture
def navigation(tmp_path: Path):
    env = environment("navigation", exchanged=True, table=str(tmp_path / "table.json"))
    yield env
    env.kill()


def test_navigation_percepts_the_state_the_object_in_front_and_progress(navigation):
    seen = percepts(navigation)
    assert {"state('11000001')", "in_front('1100')", "trial(1)", "steps(0)", "exchanged",
            "distance(0.4)"} <= seen
    assert not any(p.startswith("afford(") for p in seen) and "trial_over" not in seen


def test_a_push_reports_its_effect_once_and_the_table_is_saved(navigation, tmp_path: Path):
    act(navigation, "push")
    seen = percepts(navigation)
    assert {"effect('1100',push_ahead,unmoved)", "afford('1100',push_ahead,unmoved)",
            "steps(1)"} <= seen
    assert "effect('1100',push_ahead,unmoved)" not in percepts(navigation)  # once
    assert AffordanceTable.load(tmp_path / "table.json").triples() == [("1100", "010", 0)]


def test_walking_around_the_fixed_box_and_pushing_the_other_reaches_the_destination(navigation):
    for step in (("walk", "left"), ("walk", "left"), ("push",), ("push",), ("push",)):
        act(navigation, *step)
    seen = percepts(navigation)
    assert {"at_destination", "trial_over", "in_front('1001')"} <= seen
    with pytest.raises(ActionRefused, match="the trial is over; restart first"):
        act(navigation, "push")
    act(navigation, "restart")
    assert {"trial(2)", "steps(0)", "in_front('1100')"} <= percepts(navigation)


def test_run_trial_reports_its_result_and_ends_the_trial(navigation):
    act(navigation, "run_trial", "exploit")
    seen = percepts(navigation)
    results = [p for p in seen if p.startswith("trial_result(exploit,")]
    assert len(results) == 1 and "trial_over" in seen


@pytest.mark.parametrize(("action", "args", "why"), [
    ("walk", ("back",), "walks left, ahead or right"),
    ("run_trial", ("sometimes",), "explore or exploit"),
])
def test_navigation_refusals_leave_the_world_unchanged(navigation, action, args, why):
    before, steps = navigation.world.state(), navigation.world.steps
    with pytest.raises(ActionRefused, match=why):
        act(navigation, action, *args)
    assert navigation.world.state() == before and navigation.world.steps == steps


def test_a_saved_table_is_loaded_at_the_start(tmp_path: Path):
    table = AffordanceTable()
    table.update("1100", "010", 0)
    table.save(tmp_path / "table.json")
    env = environment("navigation", table=str(tmp_path / "table.json"))
    try:
        assert "afford('1100',push_ahead,unmoved)" in percepts(env)
    finally:
        env.kill()


@pytest.mark.parametrize(("name", "params", "message"), [
    ("navigation", {"perception": "sonar"}, "use camera or truth"),
    ("navigation", {"method": "q_learning"}, "unknown method 'q_learning'"),
    ("navigation", {"n_step": 0}, r"n_step must lie within 1\.\.100"),
    ("navigation", {"exchange_after": -1}, "exchange_after must be 0 or more"),
    ("search", {"move_after": -2}, "move_after must be 0 or more"),
    ("search", {"method": "affordance_xcs"}, "no init parameter 'method'"),
    ("stacking", {"colour": "red"}, "no init parameter 'colour'"),
])
def test_bad_init_parameters_are_clear_errors(name, params, message):
    with pytest.raises(ManagementException, match=message):
        load_environment(name)().init(params)


@pytest.mark.parametrize(("param", "content", "message"), [
    ("table", "{broken", "cannot read learner file"),
    ("table", json.dumps({"format": "goalagent-learner", "version": 1,
                          "kind": "affordance_table", "params": {"undesired_effects": [0]},
                          "state": {"triples": [["1100", "push", 0]]}}),
     r"state\.triples\[0\]\.action: must match pattern"),
    ("rules", "[]", "is not a goalagent learner file"),
])
def test_corrupt_learner_files_are_clear_errors(tmp_path: Path, param, content, message):
    path = tmp_path / "file.json"
    path.write_text(content)
    with pytest.raises(ManagementException, match=message):
        load_environment("stacking")().init({param: str(path)})


def test_stacking_vocabulary_and_refusals():
    env = environment("stacking")
    try:
        assert {"in_front(none)", "stack_height(0.0)", "state('00000010')"} <= percepts(env)
        act(env, "choose", "foam")
        act(env, "push", "stand")
        assert "effect('0010',push_stand,unmoved)" in percepts(env)
        act(env, "push", "squat")
        seen = percepts(env)
        assert {"afford('0010',push_squat,moved)", "stack_height(0.12)"} <= seen
        assert "stacked" not in seen
        before = env.world.state()
        for action, arg, why in (("choose", "cup", "a box and foams"),
                                 ("push", "kneel", "standing or squatting")):
            with pytest.raises(ActionRefused, match=why):
                act(env, action, arg)
        assert env.world.state() == before
        act(env, "choose", "box")
        act(env, "push", "stand")
        assert {"stacked", "trial_over"} <= percepts(env)
    finally:
        env.kill()


def test_search_vocabulary_and_the_rules_file(tmp_path: Path):
    rules = tmp_path / "rules.json"
    env = environment("search", move_after=1, rules=str(rules))
    try:
        assert {"head(0.0,0.0)", "moves(0)", "state('100000000')"} <= percepts(env)
        for direction in ("left", "left", "up", "up"):
            act(env, "look", direction)
        assert {"found", "trial_over", "head(0.2,-0.2)"} <= percepts(env)
        with pytest.raises(ActionRefused, match="looks up, right, down or left"):
            act(env, "look", "spin")
        act(env, "run_trial", "explore")
        assert "moves(1)" in percepts(env) and rules.exists()
    finally:
        env.kill()
    again = environment("search", rules=str(rules))  # the saved rules load back
    try:
        assert again.learner.learner.macro_count > 0
    finally:
        again.kill()
