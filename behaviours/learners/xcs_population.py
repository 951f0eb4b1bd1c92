"""The XCS population [P] as parallel numpy arrays, one row per macro-classifier.

Why hand-written rather than a library: the XCS packages keep one Python object per classifier,
so every match set walks the population in Python. Here a ternary condition is two bit masks
(`care`: the position is specified, not #; `value`: the bit it requires), so matching the whole
population against a state is one vectorised XOR/AND (`match`), and deletion is one vector
computation. Each classifier's masks are also kept as Python integers (`keys`), in a dict from
(care, value, action) to row, so the GA's crossover, mutation, subsumption and its search for an
identical classifier are a few integer operations, not array passes.

Rows are slots. A deleted classifier's slot stays dead (numerosity 0, `alive` False) until
`compact()`, and new classifiers are always appended after the last used slot, so the row
indices the learner holds for [A] and [A]-1 stay valid until it compacts (and remaps them).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import NamedTuple

import numpy as np

WORD_BITS = 64
WORD_MASK = (1 << WORD_BITS) - 1


class Classifier(NamedTuple):
    """One macro-classifier as `XCS.classifiers()` reports it (condition over {0, 1, #})."""

    condition: str
    action: int
    prediction: float
    error: float
    fitness: float
    experience: int
    numerosity: int
    action_set_size: float
    time_stamp: int


def words_for(n_bits: int) -> int:
    """Number of 64-bit words that hold ``n_bits`` condition positions."""
    return max(1, -(-n_bits // WORD_BITS))


def bits_to_int(bits: np.ndarray) -> int:
    """0/1 vector -> integer with position i at bit i."""
    return int.from_bytes(np.packbits(bits.astype(bool), bitorder="little").tobytes(), "little")


def int_to_words(mask: int, n_words: int) -> np.ndarray:
    """Integer mask -> ``n_words`` uint64 words (word w holds positions 64w .. 64w+63)."""
    return np.array([(mask >> (WORD_BITS * w)) & WORD_MASK for w in range(n_words)], np.uint64)


def condition_masks(condition: str) -> tuple[int, int]:
    """Condition text such as ``"01#1"`` -> (care, value) integer masks."""
    care = value = 0
    for position, symbol in enumerate(condition):
        if symbol != "#":
            care |= 1 << position
            if symbol == "1":
                value |= 1 << position
    return care, value


def condition_text(care: int, value: int, n_bits: int) -> str:
    """(care, value) integer masks -> condition text such as ``"01#1"``."""
    return "".join("#" if not care >> i & 1 else "1" if value >> i & 1 else "0"
                   for i in range(n_bits))


def more_general(general: tuple[int, int], specific: tuple[int, int]) -> bool:
    """B&W's IS MORE GENERAL on (care, value) masks: strictly more #s, and wherever the
    general condition specifies a bit the other specifies the same bit."""
    general_care, general_value = general
    care, value = specific
    return ((care & general_care) == general_care and (value ^ general_value) & general_care == 0
            and care.bit_count() > general_care.bit_count())


FEW = 8
"""Below this many elements, work on Python floats costs fewer calls than array operations."""

PREDICTION, ERROR, FITNESS, SET_SIZE, EXPERIENCE, NUMEROSITY, TIME_STAMP = range(7)
"""Rows of `Population.stats`, one column per slot (counts are stored as exact floats)."""
_COLUMNS = ("prediction", "error", "fitness", "action_set_size", "experience", "numerosity",
            "time_stamp")


class Population:
    """Macro-classifiers over ``n_bits``-bit states as parallel arrays (see the module doc).

    ``stats`` holds a classifier's numbers in one column (one row per quantity, contiguous for
    population-wide sums), so the learner reads and writes a whole action set with one gather
    and one scatter; ``prediction``, ``error``, ``fitness``,
    ``action_set_size``, ``experience``, ``numerosity`` and ``time_stamp`` are its row views.
    ``care``/``value`` are (words, slots): a dead slot's masks require a bit past the end of
    the state, which no state has, so matching needs no liveness test.
    """

    prediction: np.ndarray
    error: np.ndarray
    fitness: np.ndarray
    action_set_size: np.ndarray
    experience: np.ndarray
    numerosity: np.ndarray
    time_stamp: np.ndarray

    def __init__(self, n_bits: int, capacity: int) -> None:
        self.n_bits = n_bits
        self.n_words = words_for(n_bits + 1)
        self._dead = int_to_words(1 << n_bits, self.n_words)
        self.size = 0
        """High-water mark: slots ``[0, size)`` are in use, alive or dead."""
        self.micro_count = 0
        """Sum of numerosities (the population size N bounds)."""
        self.kills = 0
        """Macro-classifiers removed so far: rows held since it last changed are all alive."""
        self.keys: list[tuple[int, int, int] | None] = []
        """Per slot: (care, value, action) as integers; None for a dead slot."""
        self._rows: dict[tuple[int, int, int], int] = {}
        self._allocate(max(capacity, 8))

    def _allocate(self, capacity: int) -> None:
        self.care = np.zeros((self.n_words, capacity), np.uint64)
        self.value = np.zeros((self.n_words, capacity), np.uint64)
        self._care_0, self._value_0 = self.care[0], self.value[0]  # one-word states' views
        self._used_masks: tuple[int, np.ndarray | None, np.ndarray | None] = (-1, None, None)
        """(size, the used slots' views of ``_care_0`` and ``_value_0``) for `match`."""
        self.action = np.zeros(capacity, np.int64)
        self.specificity = np.zeros(capacity, np.int64)
        self.stats = np.zeros((len(_COLUMNS), capacity))
        for index, name in enumerate(_COLUMNS):
            setattr(self, name, self.stats[index])
        self._flat_index = np.arange(self.stats.size).reshape(self.stats.shape)
        """Each cell's index in the flattened ``stats``: `write_columns` puts through it."""

    @property
    def capacity(self) -> int:
        return self.action.size

    @property
    def macro_count(self) -> int:
        """Number of live macro-classifiers."""
        return len(self._rows)

    def alive(self, rows: np.ndarray) -> np.ndarray:
        """Whether each of ``rows`` holds a live classifier."""
        return self.numerosity[rows] > 0

    def add(self, care: int, value: int, action: int, *, prediction: float, error: float,
            fitness: float, experience: int, numerosity: int, action_set_size: float,
            time_stamp: int) -> int:
        """Append a new macro-classifier (the caller checked there is no identical one);
        returns its row."""
        if self.size == self.capacity:
            self._grow()
        row = self.size
        self.size += 1
        if self.n_words == 1:
            self.care[0, row], self.value[0, row] = care, value
        else:
            self.care[:, row] = int_to_words(care, self.n_words)
            self.value[:, row] = int_to_words(value, self.n_words)
        self.action[row] = action
        self.specificity[row] = care.bit_count()
        self.stats[:, row] = (prediction, error, fitness, action_set_size, experience,
                              numerosity, time_stamp)
        key = (care, value, action)
        self.keys.append(key)
        self._rows[key] = row
        self.micro_count += numerosity
        return row

    def _grow(self) -> None:
        care, value, action = self.care, self.value, self.action
        specificity, stats = self.specificity, self.stats
        self._allocate(2 * self.capacity)
        used = action.size
        self.care[:, :used], self.value[:, :used] = care, value
        self.action[:used], self.specificity[:used] = action, specificity
        self.stats[:, :used] = stats

    def write_columns(self, rows: np.ndarray, columns: np.ndarray | list[float],
                      quantities: int = len(_COLUMNS)) -> None:
        """``stats[:quantities, rows] = columns`` through flat indices (a 2-D fancy assignment
        costs about twice a gather of the indices and a `put`); ``columns`` is an array or
        the quantities' values one row after the other."""
        self.stats.put(self._flat_index[:quantities].take(rows, axis=1), columns)

    def match(self, words: np.ndarray) -> np.ndarray:
        """Rows of the live classifiers whose condition matches the packed state ``words``."""
        n = self.size
        if self.n_words == 1:  # a value only has bits where its care mask has
            views = self._used_masks
            if views[0] != n:  # (the views change only when slots are added or compacted)
                views = self._used_masks = (n, self._care_0[:n], self._value_0[:n])
            return ((views[1] & words[0]) == views[2]).nonzero()[0]
        mismatch = ((self.care[:, :n] & words[:, None]) != self.value[:, :n]).any(axis=0)
        return (~mismatch).nonzero()[0]

    def matches(self, rows: np.ndarray, words: np.ndarray) -> np.ndarray:
        """Whether each of ``rows`` matches the packed state ``words``."""
        return ~((self.value[:, rows] ^ words[:, None]) & self.care[:, rows]).any(axis=0)

    def find(self, care: int, value: int, action: int) -> int:
        """Row of the live classifier with exactly this condition and action, or -1."""
        return self._rows.get((care, value, action), -1)

    def kill(self, row: int) -> None:
        """Remove a whole macro-classifier (its slot stays dead until `compact`)."""
        self.micro_count -= int(self.stats[NUMEROSITY, row])
        self.kills += 1
        del self._rows[self.keys[row]]
        self.keys[row] = None
        self.care[:, row] = self._dead
        self.value[:, row] = self._dead
        self.stats[:, row] = 0.0

    def delete_one(self, uniform: float, theta_del: float, delta: float) -> None:
        """B&W's DELETE FROM POPULATION: remove one micro-classifier by roulette on the votes.

        A classifier's vote is its action-set size estimate times its numerosity, raised by
        mean fitness / its fitness per micro-classifier when it is experienced (> theta_del)
        and that fitness is below delta times the population's mean (F < delta * mean *
        numerosity, the same test without a division). ``uniform`` is the wheel's draw in
        [0, 1). Dead slots have all numbers 0, so they get no vote and are never weak.
        """
        self._remove(lambda: uniform, 1, None, theta_del, delta)

    def delete_over(self, limit: int, times: int, rng: np.random.Generator, theta_del: float,
                    delta: float) -> None:
        """`delete_one` up to ``times`` times while more than ``limit`` micro-classifiers are
        left, each with its own draw from ``rng``."""
        self._remove(rng.random, times, limit, theta_del, delta)

    def _remove(self, draw: Callable[[], float], times: int, limit: int | None,
                theta_del: float, delta: float) -> None:
        """`delete_one` ``times`` times (while more than ``limit`` are left), each spin with
        the next ``draw()``. What one removal leaves unchanged carries over to the next: the
        votes before raising and who is experienced (a removal changes only its own
        classifier's numerosity; a removed classifier's numbers are all 0, so it has no vote
        and is never weak either way), and the population's fitness sum unless a whole
        classifier went."""
        if limit is not None and self.micro_count <= limit:
            return
        size = self.size
        numerosity, fitness = self.numerosity[:size], self.fitness[:size]
        estimate = self.action_set_size[:size]
        experienced = self.experience[:size] > theta_del
        votes = estimate * numerosity
        fitness_sum = None
        for left in range(times - 1, -1, -1):
            if fitness_sum is None:
                fitness_sum = float(np.add.reduce(fitness))
            mean_fitness = fitness_sum / self.micro_count
            weak = fitness < (delta * mean_fitness) * numerosity
            weak &= experienced
            weak_rows = weak.nonzero()[0]  # usually a few: raise their votes only
            spun = votes.copy() if left and weak_rows.size else votes
            if weak_rows.size >= FEW:
                spun[weak_rows] *= mean_fitness * numerosity[weak_rows] / fitness[weak_rows]
            else:  # the same operations on Python floats: fewer calls than the array ones
                for row in weak_rows.tolist():  # (a fitness of 0, only after an underflow,
                    weight = mean_fitness * numerosity.item(row)  # divides as numpy does)
                    own = fitness.item(row)
                    spun[row] = spun.item(row) * (weight / own if own
                                                  else float(np.divide(weight, own)))
            cumulative = np.add.accumulate(spun)
            row = min(int(cumulative.searchsorted(draw() * cumulative.item(-1), "right")),
                      size - 1)
            count = numerosity.item(row)
            if count > 1:
                numerosity[row] = count - 1
                self.micro_count -= 1
            else:
                self.kill(row)
                fitness_sum = None
            if limit is not None and self.micro_count <= limit:
                return
            votes[row] = estimate.item(row) * numerosity.item(row)

    def compact(self) -> np.ndarray:
        """Drop dead slots; returns the old-row -> new-row map (-1 for dead rows)."""
        n = self.size
        live = (self.stats[NUMEROSITY, :n] > 0).nonzero()[0]
        mapping = np.full(n, -1, np.int64)
        mapping[live] = np.arange(live.size)
        kept = live.size
        self.care[:, :kept], self.value[:, :kept] = self.care[:, live], self.value[:, live]
        self.action[:kept], self.specificity[:kept] = self.action[live], self.specificity[live]
        self.stats[:, :kept] = self.stats[:, live]
        self.care[:, kept:n] = self.value[:, kept:n] = 0
        self.action[kept:n] = self.specificity[kept:n] = 0
        self.stats[:, kept:n] = 0.0
        self.keys = [self.keys[row] for row in live]
        self._rows = {key: row for row, key in enumerate(self.keys)}
        self.size = kept
        return mapping

    def records(self) -> list[Classifier]:
        """Every live macro-classifier as a `Classifier` record, in slot order."""
        return [Classifier(condition_text(key[0], key[1], self.n_bits), key[2],
                           float(self.stats[PREDICTION, row]), float(self.stats[ERROR, row]),
                           float(self.stats[FITNESS, row]), int(self.stats[EXPERIENCE, row]),
                           int(self.stats[NUMEROSITY, row]), float(self.stats[SET_SIZE, row]),
                           int(self.stats[TIME_STAMP, row]))
                for row, key in enumerate(self.keys) if key is not None]
