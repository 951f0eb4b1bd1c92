"""The classic problems the XCS reproductions run on: maps, sensing and optima checked against
the published values (Wilson's Woods2: 1.7 steps; Lanzi's Maze4: 3.5 steps)."""

from __future__ import annotations

import numpy as np
import pytest

from robot.reproduce.studies.common.lcs_problems import (
    MAZE4,
    MAZE_CODES,
    WOODS2,
    WOODS2_CODES,
    Woods,
    multiplexer_answer,
)


def world(rows: tuple[str, ...], codes: dict[str, str]) -> Woods:
    return Woods(rows, codes, np.random.default_rng(0))


def test_the_optima_are_the_published_ones():
    assert world(WOODS2, WOODS2_CODES).optimal_steps() == pytest.approx(1.6875)  # Wilson: 1.7
    maze4 = world(MAZE4, MAZE_CODES)
    assert maze4.optimal_steps() == 3.5 and len(maze4.free_cells) == 26 and maze4.n_bits == 16


def test_maze4_senses_clockwise_from_north_and_walls_block():
    maze4 = world(MAZE4, MAZE_CODES)
    maze4.position = (1, 5)  # food to the east, walls north, north-east and north-west
    state, reward, done = maze4.step(0)  # north: a wall, the animat stays
    assert (reward, done, maze4.position) == (0.0, False, (1, 5))
    assert state == "10" "10" "11" "00" "00" "10" "00" "10"  # N NE E SE S SW W NW
    assert maze4.step(2)[1:] == (1000.0, True)


def test_the_multiplexer_answers_the_addressed_bit():
    assert multiplexer_answer(np.array([1, 0, 0, 0, 1, 0]), 2) == 1
    assert multiplexer_answer(np.array([0, 1, 1, 0, 1, 1]), 2) == 0
