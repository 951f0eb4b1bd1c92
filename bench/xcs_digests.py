"""Digests of seeded XCS runs, to show that a change to the learner leaves its results bit for
bit as they were.

Runs the 6-multiplexer (N = 400), the 11-multiplexer (N = 800; 3,000 trials each, one in five
an exploit step) and Woods1 (N = 800, 300 trials, one in four exploiting) with 4 seeds under 7
option sets: Wilson's, no GA subsumption, action-set subsumption, consistent actions,
learn_in_exploit, separate β_p/β_ε/β_F, and a restricted choice (``allowed``/``considered``,
P# = 0.5): 84 runs. Each digest hashes every chosen action, a prediction array now and then,
every final classifier (floats by ``repr``, so exactly) and the clock; the last line digests
them all. Run it on the tree before and after a change and compare:
``python bench/xcs_digests.py > after.txt && diff before.txt after.txt`` (about a minute).
"""

from __future__ import annotations

import hashlib
import sys
from pathlib import Path

import numpy as np

sys.path[0] = str(Path(__file__).resolve().parents[1])  # this tree's learner, not another's

from behaviours.learners.xcs import XCS  # noqa: E402

WILSON = {"beta": 0.2, "alpha": 0.1, "epsilon_0": 10.0, "nu": 5.0, "theta_ga": 25, "chi": 0.8,
          "mu": 0.04, "theta_del": 20, "delta": 0.1, "theta_sub": 20, "p_hash": 0.33}
OPTIONS = {
    "wilson": {},
    "no-ga-subsumption": {"ga_subsumption": False},
    "action-set-subsumption": {"action_set_subsumption": True},
    "consistent-actions": {"consistent_actions": True},
    "learn-in-exploit": {"learn_in_exploit": True},
    "separate-rates": {"beta_p": 0.3, "beta_e": 0.15, "beta_f": 0.25},
    "restricted": {"p_hash": 0.5},
}
"""Option sets; "restricted" also passes ``allowed`` (and ``considered``) on some steps."""
WOODS1 = (".....", ".....", "TTF..", "TTT..", "TTT..")
"""Wilson's Woods1 tile on a torus (as in tests/behaviours/learners/test_xcs_learning.py)."""
CODES = {".": "00", "T": "10", "F": "11"}
MOVES = ((-1, 0), (-1, 1), (0, 1), (1, 1), (1, 0), (1, -1), (0, -1), (-1, -1))


def digest_of(learner: XCS, running: hashlib._Hash) -> str:
    """The run's digest: what it hashed so far, the final classifiers and the counts."""
    for classifier in learner.classifiers():
        running.update(repr(tuple(classifier)).encode())
    running.update(repr((learner.time_, learner.macro_count, learner.micro_count)).encode())
    return running.hexdigest()[:16]


def multiplexer(address_bits: int, size: int, seed: int, option: str) -> str:
    """3,000 steps on a multiplexer, states given as strings, lists and tuples in turn."""
    length = address_bits + 2 ** address_bits
    learner = XCS(2, N=size, gamma=0.0, random_state=seed, **{**WILSON, **OPTIONS[option]})
    rng = np.random.default_rng(1000 + seed)
    running = hashlib.sha256()
    for trial in range(3000):
        bits = rng.integers(0, 2, length)
        answer = int(bits[address_bits + int("".join(map(str, bits[:address_bits])), 2)])
        state = ("".join(map(str, bits)) if trial % 3 else bits.tolist() if trial % 2
                 else tuple(bits.tolist()))
        choice = {}
        if option == "restricted" and trial % 7 == 0:
            choice = {"allowed": [int(rng.integers(2))], "considered": [0, 1]}
        elif option == "restricted" and trial % 7 == 3:
            choice = {"allowed": [1]}
        action = learner.act(state, explore=trial % 5 != 4, **choice)
        running.update(bytes([action]))
        learner.reward(1000.0 if action == answer else 0.0, done=True)
        if trial % 97 == 0:
            running.update(learner.prediction_array(state).tobytes())
    return digest_of(learner, running)


def neighbour(cell: tuple[int, int], action: int) -> tuple[int, int]:
    return (cell[0] + MOVES[action][0]) % 5, (cell[1] + MOVES[action][1]) % 5


def sense(cell: tuple[int, int]) -> str:
    return "".join(CODES[WOODS1[row][column]]
                   for row, column in (neighbour(cell, action) for action in range(8)))


def woods1(seed: int, option: str) -> str:
    """300 trials of at most 30 steps in Woods1 from random free cells."""
    learner = XCS(8, N=800, gamma=0.71, random_state=seed, **{**WILSON, **OPTIONS[option]})
    rng = np.random.default_rng(2000 + seed)
    free = [(row, column) for row in range(5) for column in range(5)
            if WOODS1[row][column] == "."]
    running = hashlib.sha256()
    for trial in range(300):
        cell = free[int(rng.integers(len(free)))]
        for step in range(30):
            choice = {}
            if option == "restricted" and step % 3 == 1:
                choice = {"allowed": [0, 2, 4, 6], "considered": list(range(8))}
            elif option == "restricted" and step % 3 == 2:
                choice = {"allowed": [1, 3, 5, 7]}
            action = learner.act(sense(cell), explore=trial % 4 != 3, **choice)
            running.update(bytes([action]))
            target = neighbour(cell, action)
            symbol = WOODS1[target[0]][target[1]]
            if symbol == "F":
                learner.reward(1000.0, done=True)
                break
            if symbol == ".":
                cell = target
            learner.reward(0.0, done=False)
        else:
            learner.end_trial()
        if trial % 29 == 0:
            running.update(learner.prediction_array(sense(cell)).tobytes())
    return digest_of(learner, running)


def main() -> int:
    every = hashlib.sha256()
    for option in OPTIONS:
        for seed in range(4):
            for problem, digest in (("6-mux", multiplexer(2, 400, seed, option)),
                                    ("11-mux", multiplexer(3, 800, seed, option)),
                                    ("woods1", woods1(seed, option))):
                print(f"{problem} {option} seed={seed} {digest}", flush=True)
                every.update(digest.encode())
    print("all", every.hexdigest()[:16])
    return 0


if __name__ == "__main__":
    sys.exit(main())
