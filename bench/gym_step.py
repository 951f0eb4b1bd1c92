"""Gymnasium benchmark: a ``step`` through the Gymnasium API against the same action through
the learners' own protocol (issue 31: at most 5% more).

Per task, the same pre-drawn actions run twice in a fresh world: once through the task's own
protocol (the XCS ``Task``'s ``perform`` for navigation, stacking and the head search;
``PartContact.step``, Algorithm 3's ``ContinuousWorld``, for the can) and once through
``gymnasium.make(id)``'s ``step``, with the wrappers ``make`` adds (order enforcing, the
passive checker). A trial ends as the environment ends it (the goal, a fall, ``n_step``
actions), and both paths then reset. Only the steps are timed, in process CPU time (the
machine is shared); the best of ``--repeats`` interleaved rounds counts. Both paths must see
the same rewards and states, or no ratio is printed. The can runs with ``reward="opening"``
(the protocol has no forward model); ``CanOpening |η|`` adds the environment's own forward
model (eq. 4.2-4.4), work the protocol does not do, for information.

    .venv/bin/python bench/gym_step.py [--steps N] [--repeats K]
"""

from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np

# Run as a script, this file's folder comes first on sys.path: put the repository root there
# instead, so that `robot` and `behaviours` are the project's.
sys.path[0] = str(Path(__file__).resolve().parents[1])

import gymnasium  # noqa: E402
from rich.console import Console  # noqa: E402
from rich.table import Table  # noqa: E402

import robot.gym  # noqa: E402,F401  (headless rendering before MuJoCo loads)
from robot.gym.registration import register_envs  # noqa: E402

TARGET = 1.05
"""Issue 31: a Gymnasium step costs at most 5% more than the protocol's."""
SEED = 0
Run = Callable[[list], tuple[float, list]]


def direct_task(env_id: str):
    """The task the environment wraps, built afresh, and its trial length."""
    from behaviours.blob_grid import make_grid_perception
    from behaviours.object_state import make_object_perception
    from behaviours.xcs_tasks import NavigationTask, SearchTask, StackingTask
    from behaviours.xcs_trials import N_STEP, SEARCH_STEPS
    from sim.navigation import NavigationWorld
    from sim.search import SearchWorld
    from sim.stacking import StackingWorld

    if env_id == "goalagent/Navigation-v0":
        return NavigationTask(NavigationWorld(), make_object_perception("truth", "navigation"),
                              exchange_after=10), N_STEP
    if env_id == "goalagent/Stacking-v0":
        return StackingTask(StackingWorld(), make_object_perception("truth", "stacking")), N_STEP
    return SearchTask(SearchWorld(), make_grid_perception("truth"), move_after=10), SEARCH_STEPS


def xcs_protocol(env_id: str) -> Run:
    """Steps through ``Task.perform``; a trial ends where the environment would end it."""
    def run(actions: list) -> tuple[float, list]:
        task, n_step = direct_task(env_id)
        trial, steps, seconds, seen = 0, 0, 0.0, []
        task.reset(trial)
        for action in actions:
            start = time.process_time()
            outcome, view = task.perform(action)
            seconds += time.process_time() - start
            steps += 1
            seen.append((outcome.reward, view.bits))
            if outcome.done or steps >= n_step:
                trial, steps = trial + 1, 0
                task.reset(trial)
        task.world.close()
        return seconds, seen
    return run


def xcs_gym(env_id: str) -> Run:
    """Steps through ``gymnasium.make(env_id).step``."""
    def run(actions: list) -> tuple[float, list]:
        env = gymnasium.make(env_id)
        env.reset(seed=SEED)
        seconds, seen = 0.0, []
        for action in actions:
            start = time.process_time()
            _, reward, terminated, truncated, info = env.step(action)
            seconds += time.process_time() - start
            seen.append((reward, info["bits"]))
            if terminated or truncated:
                env.reset()
        env.close()
        return seconds, seen
    return run


def can_protocol(actions: list) -> tuple[float, list]:
    """Steps through ``PartContact.step`` on the push-lid can, one long exploration."""
    from behaviours.contact import PartContact
    from sim.world import GarbageWorld

    world = GarbageWorld("o1", seed=SEED)
    contact = PartContact(world, "lid", dims=3).start()
    seconds, seen = 0.0, []
    for action in actions:
        start = time.process_time()
        state = contact.step(action)
        seconds += time.process_time() - start
        seen.append(state)
    world.close()
    return seconds, seen


def can_gym(reward: str) -> Run:
    """Steps through ``gymnasium.make("goalagent/CanOpening-v0").step``."""
    def run(actions: list) -> tuple[float, list]:
        env = gymnasium.make("goalagent/CanOpening-v0", reward=reward, max_steps=len(actions))
        env.reset(seed=SEED)
        seconds, seen = 0.0, []
        for action in actions:
            start = time.process_time()
            observation, *_ = env.step(action)
            seconds += time.process_time() - start
            seen.append(float(observation[0]))
        env.close()
        return seconds, seen
    return run


def measure(protocol: Run, gym_path: Run, actions: list, repeats: int) -> tuple[float, float,
                                                                                   bool]:
    """Best per-step CPU seconds of each path, and whether both saw the same outcomes."""
    best_protocol = best_gym = float("inf")
    same = True
    for _ in range(repeats):
        seconds, seen = protocol(actions)
        best_protocol = min(best_protocol, seconds / len(actions))
        seconds, seen_gym = gym_path(actions)
        best_gym = min(best_gym, seconds / len(actions))
        same = same and seen == seen_gym
    return best_protocol, best_gym, same


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=200, help="steps per path and round")
    parser.add_argument("--repeats", type=int, default=3, help="rounds (the best counts)")
    args = parser.parse_args(argv)
    register_envs()
    rng = np.random.default_rng(SEED)
    cases = []
    for name, env_id in (("Navigation", "goalagent/Navigation-v0"),
                         ("Stacking", "goalagent/Stacking-v0"),
                         ("HeadSearch", "goalagent/HeadSearch-v0")):
        actions = [int(a) for a in rng.integers(0, 4, args.steps)]
        cases.append((name, xcs_protocol(env_id), xcs_gym(env_id), actions))
    moves = list(rng.uniform(-0.01, 0.01, (args.steps, 3)))
    cases.append(("CanOpening", can_protocol, can_gym("opening"), moves))
    cases.append(("CanOpening |η|", can_protocol, can_gym("prediction_error"), moves))
    table = Table(title=f"A step through Gymnasium against the protocol's ({args.steps} steps, "
                        f"best of {args.repeats}, CPU ms per step)")
    for column in ("task", "protocol", "gymnasium", "ratio", f"<= {TARGET}"):
        table.add_column(column, justify="right")
    failed = False
    for name, protocol, gym_path, actions in cases:
        per_protocol, per_gym, same = measure(protocol, gym_path, actions, args.repeats)
        if not same:
            table.add_row(name, "-", "-", "different outcomes", "no")
            failed = True
            continue
        ratio = per_gym / per_protocol
        table.add_row(name, f"{per_protocol * 1e3:.3f}", f"{per_gym * 1e3:.3f}", f"{ratio:.3f}",
                      "yes" if ratio <= TARGET else "no")
    Console().print(table)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
