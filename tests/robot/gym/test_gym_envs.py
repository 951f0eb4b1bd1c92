"""The thesis's tasks as Gymnasium environments (issue 31): registration by installing,
Gymnasium's own checker, the spaces, the rewards of eqs. 3.14, 3.15, App. A and 4.6/4.20,
seeding, the world's change after 10 trials, rendering and recording, and bad input."""

from __future__ import annotations

import ast
import subprocess
import sys
import warnings

import gymnasium
import numpy as np
import pytest
from gymnasium.error import InvalidAction, ResetNeeded
from gymnasium.utils.env_checker import check_env

from robot.gym.registration import ENV_IDS

WALK_LEFT, WALK_AHEAD, WALK_RIGHT, PUSH = range(4)
PUSH_STAND, PUSH_SQUAT, CHOOSE_BOX, CHOOSE_FOAM = range(4)
LOOK_UP, LOOK_RIGHT, LOOK_DOWN, LOOK_LEFT = range(4)


def make(env_id: str, **kwargs):
    return gymnasium.make(f"goalagent/{env_id}-v0", **kwargs)


def test_installing_registers_every_id_with_nothing_imported_but_gymnasium(tmp_path):
    program = ("import sys, gymnasium\n"
               "ids = sorted(k for k in gymnasium.registry if k.startswith('goalagent/'))\n"
               "print(ids, 'mujoco' in sys.modules)\n"
               "env = gymnasium.make('goalagent/Navigation-v0')\n"
               "print(env.reset(seed=0)[0].tolist())\n")
    done = subprocess.run([sys.executable, "-c", program], cwd=tmp_path, capture_output=True,
                          text=True, timeout=120, env={"PATH": "/usr/bin:/bin"})
    assert done.returncode == 0, done.stderr
    ids, loaded = done.stdout.splitlines()[0].rsplit(" ", 1)
    assert ast.literal_eval(ids) == sorted(ENV_IDS)
    assert loaded == "False"  # registering loads no MuJoCo
    assert done.stdout.splitlines()[1] == "[1, 0, 0, 1, 0, 0, 0, 1]"


@pytest.mark.parametrize("env_id", sorted(ENV_IDS))
def test_gymnasium_check_env_passes_without_a_warning(env_id):
    env = gymnasium.make(env_id, render_mode="rgb_array")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        check_env(env.unwrapped)
    env.close()


@pytest.mark.parametrize(("env_id", "observation", "actions"), [
    ("Navigation", gymnasium.spaces.MultiBinary(8), 4),
    ("Stacking", gymnasium.spaces.MultiBinary(8), 4),
    ("HeadSearch", gymnasium.spaces.MultiBinary(9), 4),
])
def test_the_xcs_tasks_observe_the_state_bits_and_act_by_table_3_1(env_id, observation, actions):
    env = make(env_id)
    assert env.observation_space == observation
    assert env.action_space == gymnasium.spaces.Discrete(actions)
    discrete = make(env_id, observation="discrete")
    assert discrete.observation_space == gymnasium.spaces.Discrete(2 ** observation.n)
    bits, info = env.reset(seed=3)
    number, _ = discrete.reset(seed=3)
    assert "".join(map(str, bits)) == info["bits"] and int(info["bits"], 2) == number
    env.close()
    discrete.close()


def test_navigation_rewards_follow_eq_3_14_and_the_boxes_swap_after_10_trials():
    env = make("Navigation")
    names = env.unwrapped.action_names
    assert names == ("walk_left", "walk_ahead", "walk_right", "push_ahead")
    _, info = env.reset(seed=0)
    assert info["object"] == "1001" and info["trial"] == 1  # the blue movable box ahead
    _, reward, terminated, _, info = env.step(WALK_AHEAD)  # blocked by the box: no progress
    assert (reward, terminated, info["effect"]) == (-100.0, False, None)
    rewards = []
    for _ in range(3):
        _, reward, terminated, truncated, info = env.step(PUSH)
        rewards.append(reward)
    assert rewards == [0.0, 0.0, 1000.0] and terminated and not truncated
    assert info["success"] and info["effect"] == 1
    for trial in range(2, 11):
        _, info = env.reset()
        assert info["trial"] == trial and info["object"] == "1001"
    _, info = env.reset()  # trial 11: the red fixed box is in front now
    assert info["trial"] == 11 and info["object"] == "1100"
    _, reward, terminated, _, info = env.step(PUSH)
    assert (reward, terminated, info["effect"]) == (-100.0, False, 0)
    _, info = env.reset(options={"trial": 3})
    assert info["object"] == "1001"
    _, info = env.reset(seed=1)  # a new experiment starts at trial 1
    assert info["trial"] == 1
    never = make("Navigation", exchange_after=None)
    assert never.reset(options={"trial": 500})[1]["object"] == "1001"
    env.close()
    never.close()


def test_a_trial_is_truncated_after_n_step_actions_and_then_needs_a_reset():
    env = make("Navigation", n_step=2)
    env.reset(seed=0)
    assert env.step(WALK_AHEAD)[3] is False
    _, _, terminated, truncated, _ = env.step(WALK_AHEAD)
    assert (terminated, truncated) == (False, True)
    with pytest.raises(ResetNeeded, match="episode has ended"):
        env.step(WALK_AHEAD)
    env.close()


def test_stacking_rewards_follow_eq_3_15():
    env = make("Stacking")
    env.reset(seed=0)
    _, reward, _, _, info = env.step(CHOOSE_BOX)
    assert reward == -100.0 and info["object"] == "1001"
    _, reward, terminated, _, info = env.step(PUSH_STAND)  # the high box alone is a stack
    assert (reward, terminated, info["success"], info["effect"]) == (1000.0, True, True, 1)
    env.reset()
    env.step(CHOOSE_FOAM)
    _, reward, terminated, _, info = env.step(PUSH_STAND)  # the bar sweeps over the foam
    assert (reward, terminated, info["effect"]) == (0.0, False, 0)
    env.close()


def test_head_search_rewards_the_centre_and_the_target_moves_after_10_trials():
    env = make("HeadSearch")
    env.reset(seed=0)
    assert env.unwrapped.n_step == 20
    rewards = [env.step(action)[1] for action in (LOOK_LEFT, LOOK_LEFT, LOOK_UP)]
    _, reward, terminated, _, _ = env.step(LOOK_UP)
    assert rewards == [0.0, 0.0, 0.0] and (reward, terminated) == (1000.0, True)
    env.reset(options={"trial": 10})  # moved to the right: three looks right
    rewards = [env.step(LOOK_RIGHT)[1] for _ in range(3)]
    assert rewards == [0.0, 0.0, 1000.0]
    env.close()


def test_can_opening_rewards_the_prediction_error_or_the_opening():
    from behaviours.learners.forward_model import ForwardModel

    env = make("CanOpening", dims=1)
    assert env.action_space == gymnasium.spaces.Box(-0.01, 0.01, (1,), np.float64)
    assert env.observation_space == gymnasium.spaces.Box(0.0, 1.0, (1,), np.float64)
    state, info = env.reset(seed=4)
    assert info["part"] == "lid" and env.unwrapped.max_steps == 100
    draw = np.random.default_rng(4).integers(2 ** 31 - 1)  # F is seeded from the env's rng
    model = ForwardModel(random_state=int(draw)).initialize(1)
    for move in (0.01, 0.008, -0.005):
        row = [[state[0], move]]
        expected = float(model.predict(row)[0])
        after, reward, terminated, truncated, info = env.step(np.array([move]))
        effect = after[0] - state[0]  # eq. 4.20
        assert info["effect"] == pytest.approx(effect) and info["prediction"] == expected
        assert reward == pytest.approx(abs(effect - expected))  # eq. 4.3, 4.6
        model.partial_fit(row, [effect])  # eq. 4.4
        state = after
    assert state[0] > 0.03  # pushed, the lid opened
    opening = make("CanOpening", can="o5", reward="opening")
    assert opening.action_space.shape == (3,) and opening.unwrapped.max_steps == 300
    state, info = opening.reset(seed=0)
    assert info["part"] == "handle"
    total = sum(opening.step(np.array([-0.01, 0.0, 0.0]))[1] for _ in range(3))
    assert total == pytest.approx(opening.unwrapped._state - state[0]) and total > 0.03
    env.close()
    opening.close()


def test_can_opening_takes_any_can_file(tmp_path):
    from sim.canfile import shipped_can_path

    text = shipped_can_path("o3").read_text().replace("name: o3", "name: mine")
    path = tmp_path / "mine.yaml"
    path.write_text(text)
    env = make("CanOpening", can=str(path), dims=1)
    assert env.unwrapped.world.can == "mine"
    env.reset(seed=0)
    assert env.step(np.array([0.01]))[0][0] > 0.0
    env.close()
    broken = tmp_path / "broken.yaml"
    broken.write_text("name: [\n")
    with pytest.raises(ValueError, match="broken.yaml:"):
        make("CanOpening", can=str(broken))


@pytest.mark.parametrize("env_id", sorted(ENV_IDS))
def test_a_seeded_reset_replays_the_same_episode(env_id):
    env = gymnasium.make(env_id)
    runs = []
    for _ in range(2):
        observation, _ = env.reset(seed=11)
        env.action_space.seed(5)
        steps = [observation.tolist()]
        for _ in range(4):
            observation, reward, terminated, truncated, _ = env.step(env.action_space.sample())
            steps.append((observation.tolist(), reward))
            if terminated or truncated:
                break
        runs.append(steps)
    assert runs[0] == runs[1]
    env.close()


@pytest.mark.parametrize(("env_id", "bad_action"), [
    ("Navigation", 4), ("Navigation", -1), ("Navigation", 1.5), ("Navigation", "push"),
    ("HeadSearch", 7), ("CanOpening", np.array([0.02, 0.0, 0.0])),
    ("CanOpening", np.array([0.0, 0.0])), ("CanOpening", "up"),
])
def test_bad_actions_and_steps_before_reset_leave_the_world_as_it_was(env_id, bad_action):
    env, fresh = gymnasium.make(f"goalagent/{env_id}-v0"), gymnasium.make(f"goalagent/{env_id}-v0")
    good = env.action_space.sample()
    with pytest.raises(ResetNeeded, match="before reset"):
        env.unwrapped.step(good)
    env.reset(seed=2)
    fresh.reset(seed=2)
    with pytest.raises(InvalidAction, match="not in the action space"):
        env.step(bad_action)
    with pytest.raises(ValueError, match="unknown reset option.*'colour'"):
        env.reset(options={"colour": "red"})
    assert np.array_equal(env.step(good)[0], fresh.step(good)[0])
    assert np.array_equal(env.unwrapped.world.data.qpos, fresh.unwrapped.world.data.qpos)
    env.close()
    fresh.close()


@pytest.mark.parametrize(("env_id", "kwargs", "message"), [
    ("Navigation", {"perception": "sonar"}, "perception must be one of 'truth', 'camera'"),
    ("Navigation", {"observation": "image"}, "observation must be one of"),
    ("Navigation", {"n_step": 0}, "n_step must be 1..100"),
    ("Navigation", {"exchange_after": -1}, "exchange_after must be 0 or more"),
    ("Stacking", {"render_mode": "ansi"}, "render_mode must be one of None, 'rgb_array'"),
    ("HeadSearch", {"camera": "side"}, "camera must be one of 'overview', 'head'"),
    ("HeadSearch", {"move_after": True}, "move_after must be a whole number"),
    ("CanOpening", {"can": "o9"}, "unknown can 'o9'"),
    ("CanOpening", {"can": "o1", "part": "handle"}, "part must be one of 'lid'"),
    ("CanOpening", {"dims": 2}, "dims must be one of 1, 3"),
    ("CanOpening", {"reward": "money"}, "reward must be one of 'prediction_error'"),
])
def test_bad_keywords_are_refused_with_what_they_take(env_id, kwargs, message):
    with pytest.raises(ValueError, match=message):
        make(env_id, **kwargs)


def test_an_unknown_keyword_is_pythons_usual_error():
    with pytest.raises(TypeError, match="colour"):
        make("Stacking", colour="red")


def test_record_video_records_the_overview(tmp_path):
    import imageio.v3 as iio

    env = gymnasium.wrappers.RecordVideo(make("Navigation", render_mode="rgb_array"),
                                         str(tmp_path), episode_trigger=lambda _: True)
    env.reset(seed=0)
    for _ in range(3):
        env.step(PUSH)
    env.close()
    (video,) = tmp_path.glob("*.mp4")
    frames = iio.imread(video)
    assert frames.shape[0] == 4 and frames.shape[1:] == (360, 480, 3)  # reset + 3 steps
