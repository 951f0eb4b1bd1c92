"""The `garbage` EIS environment: its vocabulary, refusals and the affordance behaviours."""

from __future__ import annotations

from pathlib import Path

import mujoco
import pytest

from behaviours.learning import AffordanceEvidence
from goalagent.eis import ActException, ActionRefused, ManagementException, load_environment
from goalagent.eis.terms import Action
from goalagent.kb.terms import format_term
from robot.envs.garbage import afford_percept


def environment(tmp_path: Path, **params: object):
    env = load_environment("garbage")()
    env.init({"models": str(tmp_path / "models.json"), **params})
    env.start()
    env.register_agent("robot")
    env.associate_entity("robot", "robot")
    return env


def percepts(env) -> set[str]:
    return {str(p) for p in env.get_all_percepts("robot")["robot"]}


def act(env, name: str, *args: object) -> None:
    env.perform_action("robot", Action.of(name, *args))


def test_percepts_describe_the_scene(tmp_path: Path):
    env = environment(tmp_path, can="o2", trials=3)
    seen = percepts(env)
    assert {"trials(3)", "disposed(0)", "obs(body)", "obs(lid)", "obs(handle)"} <= seen
    assert "above(lid,handle)" in seen and "above(handle,body)" in seen
    assert "opened" not in seen and "holding(ball)" not in seen
    assert any(p.startswith("part(handle,") for p in seen)
    env.kill()


@pytest.mark.parametrize(("action", "args", "why"), [
    ("extend_arm", ("handle", 0.05), "has no part 'handle'"),
    ("extend_arm", ("lid", 0.2), "out of bounds"),
    ("learn", ("lid", "wiggle", "opened", "random"), "unknown action type"),
    ("drop", ("ball",), "does not hold the ball"),
    ("grasp", ("cup",), "only the ball"),
])
def test_refused_actions_say_why_and_leave_the_world_unchanged(tmp_path, action, args, why):
    env = environment(tmp_path, can="o1")
    before = env.world.state()
    steps = env.world.data.time
    with pytest.raises(ActionRefused, match=why):
        act(env, action, *args)
    assert env.world.state() == before and env.world.data.time == steps
    env.kill()


def test_learn_then_apply_reports_the_thesis_percepts(tmp_path: Path, capsys):
    env = environment(tmp_path, can="o1")
    act(env, "grasp", "ball")
    act(env, "learn", "lid", "sweep_left", "opened", "random")
    told = capsys.readouterr().err  # where learning keeps its models, said once
    assert told == f"garbage: learned effect models are kept in {tmp_path / 'models.json'}\n"
    seen = percepts(env)
    assert "afford(lid,sweep_left,opened,0,0,0.05)" in seen
    assert any(p.startswith("exploration(lid,sweep_left,random,") for p in seen)
    act(env, "learn", "lid", "extend_arm", "opened", "random")
    seen = percepts(env)
    assert "afford(lid,extend_arm,opened,0,0,0.3)" in seen
    assert any(p.startswith("model(lid,extend_arm,") for p in seen)
    assert "kept in" not in capsys.readouterr().err
    act(env, "apply", "lid", "extend_arm")
    seen = percepts(env)
    assert {"afford(lid,extend_arm,opened,1,1,1)", "opened", "holding(ball)"} <= seen
    assert not any(p.startswith("afford(") for p in percepts(env))  # reported once
    act(env, "drop", "ball")
    assert "in_can(ball)" in percepts(env)
    act(env, "close_lid")
    seen = percepts(env)
    assert "disposed(1)" in seen and "opened" not in seen and "in_can(ball)" not in seen
    assert Path(tmp_path / "models.json").exists()
    env.kill()


def test_active_learning_reports_the_same_percepts_and_how_many_tries(tmp_path: Path):
    env = environment(tmp_path, can="o1", active_n_max=40)
    act(env, "learn", "lid", "extend_arm", "opened", "active")
    seen = percepts(env)
    assert "afford(lid,extend_arm,opened,0,0,0.3)" in seen
    assert any(p.startswith("model(lid,extend_arm,") for p in seen)
    (tries,) = [p for p in seen if p.startswith("exploration(lid,extend_arm,active,")]
    assert 21 <= int(tries.rstrip(")").split(",")[-1]) <= 40
    act(env, "apply", "lid", "extend_arm")
    assert "afford(lid,extend_arm,opened,1,1,1)" in percepts(env)
    env.kill()


def test_an_arm_skill_reports_its_effect(tmp_path: Path):
    env = environment(tmp_path, can="o5")
    act(env, "contract_arm", "handle", 0.1)
    (effect,) = [p for p in percepts(env) if p.startswith("effect(")]
    assert effect.startswith("effect(handle,contract_arm,0.1,")
    assert "opened" in percepts(env)
    env.kill()


def test_a_run_can_be_recorded(tmp_path: Path):
    video = tmp_path / "run.mp4"
    env = environment(tmp_path, can="o1", record=str(video))
    act(env, "extend_arm", "lid", 0.05)
    env.kill()
    assert video.stat().st_size > 10_000


@pytest.mark.parametrize(("params", "message"), [
    ({"can": "o9"}, "unknown can 'o9'"),
    ({"perception": "sonar"}, "use camera or truth"),
    ({"colour": "red"}, "no init parameter 'colour'"),
])
def test_bad_init_parameters_are_clear_errors(tmp_path, params, message):
    env = load_environment("garbage")()
    with pytest.raises(ManagementException, match=message):
        env.init(params)


def test_an_unknown_agent_cannot_act(tmp_path: Path):
    env = environment(tmp_path)
    with pytest.raises(ActException):
        env.perform_action("stranger", Action.of("grasp", "ball"))
    env.kill()


def test_afford_percepts_keep_the_numbers_the_behaviours_report():
    """learn's r1 stays the float 0.3; apply's verdict stays the integers 1, 1, 1 (§6.3.3)."""
    learned = afford_percept(AffordanceEvidence("lid", "extend_arm", "opened", 0, 0, 0.3))
    verified = afford_percept(AffordanceEvidence("lid", "extend_arm", "opened", 1, 1, 1))
    assert format_term(learned) == "afford(lid,extend_arm,opened,0,0,0.3)"
    assert format_term(verified) == "afford(lid,extend_arm,opened,1,1,1)"


def test_a_learn_asked_again_with_nothing_new_is_answered_as_repeated(tmp_path: Path):
    """The livelock guard: the same request, with only learning since, is not run again."""
    env = environment(tmp_path, can="o1", n_max=4)
    act(env, "learn", "lid", "sweep_left", "opened", "random")
    assert any(p.startswith("exploration(lid,sweep_left,random,") for p in percepts(env))
    steps = env.world.steps
    act(env, "learn", "lid", "sweep_left", "opened", "random")
    seen = percepts(env)
    assert "learn_repeated(lid,sweep_left,opened,random)" in seen
    assert not any(p.startswith(("exploration(", "afford(")) for p in seen)
    assert env.world.steps == steps  # nothing was done
    act(env, "learn", "lid", "sweep_right", "opened", "random")  # another question: learned
    assert any(p.startswith("exploration(lid,sweep_right,") for p in percepts(env))
    act(env, "extend_arm", "lid", 0.02)  # the world changed: asking again is fair
    act(env, "learn", "lid", "sweep_left", "opened", "random")
    assert any(p.startswith("exploration(lid,sweep_left,") for p in percepts(env))
    env.kill()


def test_a_missed_drop_says_why_and_the_ball_can_be_picked_up_again(tmp_path: Path):
    env = environment(tmp_path, can="o2")
    act(env, "grasp", "ball")
    act(env, "drop", "ball")  # the lid is closed
    seen = percepts(env)
    assert "ball_missed(blocked)" in seen
    assert "holding(ball)" not in seen and "in_can(ball)" not in seen
    act(env, "grasp", "ball")
    assert "holding(ball)" in percepts(env)
    act(env, "lift_up", "handle", 0.1)
    act(env, "drop", "ball")
    seen = percepts(env)
    assert "in_can(ball)" in seen and not any(p.startswith("ball_missed") for p in seen)
    env.kill()


def test_a_ball_out_of_reach_is_refused_each_time_it_is_asked_for(tmp_path: Path):
    env = environment(tmp_path, can="o1")
    ball = env.world.data.joint("ball_free").qpos
    ball[:3] = (-0.6, 0.0, 0.025)  # on the floor, behind the robot's reach
    mujoco.mj_forward(env.world.model, env.world.data)
    before = env.world.state()
    for _ in range(2):
        with pytest.raises(ActionRefused, match=r"grasp\(ball\): the ball at .* out of the arm"):
            act(env, "grasp", "ball")
    assert env.world.state() == before
    env.kill()


def test_a_lid_that_does_not_close_is_reported(tmp_path: Path):
    env = environment(tmp_path, can="o1")
    act(env, "extend_arm", "lid", 0.1)
    env.world.arm_stiffness = 1.0  # an arm too weak to press the lid down
    act(env, "close_lid")
    (stuck,) = [p for p in percepts(env) if p.startswith("lid_stuck(")]
    assert float(stuck[len("lid_stuck("):-1]) > 0.1
    assert "disposed(0)" in percepts(env)
    env.kill()


def test_a_lid_sliding_the_other_way_is_closed_too(tmp_path: Path):
    """A closing skill that opens the can further (sweeping a right-sliding lid right) is not
    tried again; the other way closes it."""
    can = tmp_path / "right_slide.yaml"
    can.write_text("name: right_slide\nmechanism: {type: slide_lid, direction: right, gear: 1.5}\n"
                   "dimensions: {width: 0.26, depth: 0.30, height: 0.28}\nlid: {height: 0.02}\n")
    env = environment(tmp_path, can=str(can))
    act(env, "sweep_right", "lid", 0.1)
    assert "opened" in percepts(env)
    act(env, "close_lid")
    seen = percepts(env)
    assert "opened" not in seen and not any(p.startswith("lid_stuck") for p in seen)
    assert env.world.opening() < 0.01
    env.kill()
