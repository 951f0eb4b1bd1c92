"""Classic learning-classifier-system test problems: the Boolean multiplexer and Wilson's woods.

These are the problems XCS was published on (Wilson 1995; Butz & Wilson 2001), kept small and
exact so a reproduction compares like with like:

- `multiplexer_answer`: the k-address-bit multiplexer (6-mux: k = 2, 11-mux: k = 3).
- `Woods`: a toroidal grid world; the animat senses its 8 neighbours clockwise from north, each
  cell coded in bits, moves to one of them (a rock blocks the move), and a trial ends with
  reward 1000 when it steps onto food. `WOODS2` is Wilson's 30 x 15 map with two kinds of rock
  (O, Q) and of food (F, G), coded O=010, Q=011, F=110, G=111, blank=000 (Wilson 1995).
  `MAZE4` is Lanzi's maze where few generalisations are possible (Lanzi 1997), 2 bits a cell.
"""

from __future__ import annotations

from collections import deque

import numpy as np

WOODS2 = (
    "..............................",
    ".QQF..QQF..OQF..QQG..OQG..OQF.",
    ".OOO..QOO..OQO..OOQ..QQO..QQQ.",
    ".OOQ..OQQ..OQQ..QQO..OOO..QQO.",
    "..............................",
    "..............................",
    ".QOF..QOG..QOF..OOF..OOG..QOG.",
    ".QQO..QOO..OOO..OQO..QQO..QOO.",
    ".QQQ..OOO..OQO..QOQ..QOQ..OQO.",
    "..............................",
    "..............................",
    ".QOG..QOF..OOG..OQF..OOG..OOF.",
    ".OOQ..OQQ..QQO..OQQ..QQO..OQQ.",
    ".QQO..OOO..OQO..OOQ..OQQ..QQQ.",
    "..............................",
)
"""Wilson's Woods2 (1995), as distributed with Lanzi's xcslib."""

WOODS2_CODES = {".": "000", "O": "010", "Q": "011", "F": "110", "G": "111"}
"""Wilson's 3-bit cell codes for Woods2: first bit 'food-like', second 'opaque'."""

MAZE4 = (
    "OOOOOOOO",
    "O..O..FO",
    "OO..O..O",
    "OO.O..OO",
    "O......O",
    "OO.O...O",
    "O....O.O",
    "OOOOOOOO",
)
"""Lanzi's Maze4 (1997; the map as distributed with xcsf): walls all round, one food cell,
3.5 steps to food on average from its 26 blank cells."""

MAZE_CODES = {".": "00", "O": "10", "F": "11"}
"""2 bits a cell for Lanzi's mazes (blank 00, obstacle 10, food 11): 16-bit states."""

FOOD = frozenset("FG")
FREE = "."
MOVES = ((-1, 0), (-1, 1), (0, 1), (1, 1), (1, 0), (1, -1), (0, -1), (-1, -1))
"""(row, column) steps of actions 0-7: N, NE, E, SE, S, SW, W, NW (clockwise from north)."""


def multiplexer_answer(bits: np.ndarray, address_bits: int) -> int:
    """The multiplexer's output: the data bit that the first ``address_bits`` bits select."""
    address = 0
    for bit in bits[:address_bits]:
        address = 2 * address + int(bit)
    return int(bits[address_bits + address])


class Woods:
    """A toroidal woods environment over a map of equal-length rows (see module doc)."""

    def __init__(self, rows: tuple[str, ...], codes: dict[str, str],
                 rng: np.random.Generator) -> None:
        if not rows or len({len(row) for row in rows}) != 1:
            raise ValueError("rows must be a non-empty list of equally long map rows")
        unknown = set("".join(rows)) - set(codes)
        if unknown:
            raise ValueError(f"map symbols without a code: {sorted(unknown)}")
        self.rows = rows
        self.codes = codes
        self.rng = rng
        self.height, self.width = len(rows), len(rows[0])
        self.free_cells = [(r, c) for r in range(self.height) for c in range(self.width)
                           if rows[r][c] == FREE]
        self._senses = {cell: self._sense(cell) for cell in self.free_cells}
        self.position = self.free_cells[0]

    @property
    def n_bits(self) -> int:
        return 8 * len(next(iter(self.codes.values())))

    def _neighbour(self, cell: tuple[int, int], action: int) -> tuple[int, int]:
        step = MOVES[action]
        return (cell[0] + step[0]) % self.height, (cell[1] + step[1]) % self.width

    def _sense(self, cell: tuple[int, int]) -> str:
        return "".join(self.codes[self.rows[r][c]]
                       for r, c in (self._neighbour(cell, action) for action in range(8)))

    def reset(self) -> str:
        """Put the animat on a random blank cell; returns what it senses there."""
        self.position = self.free_cells[int(self.rng.integers(len(self.free_cells)))]
        return self._senses[self.position]

    def step(self, action: int) -> tuple[str, float, bool]:
        """Move (rocks block); returns (sensed state, reward, trial over)."""
        target = self._neighbour(self.position, action)
        symbol = self.rows[target[0]][target[1]]
        if symbol in FOOD:
            return self._senses[self.position], 1000.0, True
        if symbol == FREE:
            self.position = target
        return self._senses[self.position], 0.0, False

    def optimal_steps(self) -> float:
        """Mean shortest number of steps to food over all blank starting cells (BFS)."""
        distances = []
        for start in self.free_cells:
            seen, queue = {start}, deque([(start, 0)])
            while queue:
                cell, distance = queue.popleft()
                neighbours = [self._neighbour(cell, action) for action in range(8)]
                if any(self.rows[r][c] in FOOD for r, c in neighbours):
                    distances.append(distance + 1)
                    break
                for r, c in neighbours:
                    if self.rows[r][c] == FREE and (r, c) not in seen:
                        seen.add((r, c))
                        queue.append(((r, c), distance + 1))
        return float(np.mean(distances))
