"""Rule discovery in XCS: the match set and its covering, the niche GA, subsumption and
deletion.

Follows Butz & Wilson, "An algorithmic description of XCS" (2001), procedure by procedure
(GENERATE MATCH SET, GENERATE COVERING CLASSIFIER, RUN GA, SELECT OFFSPRING, APPLY CROSSOVER,
APPLY MUTATION, DOES SUBSUME, DO ACTION SET SUBSUMPTION, INSERT IN / DELETE FROM POPULATION).
Two choices where implementations differ, taken from Butz's XCSJava: an offspring starts from
its parent's fitness per micro-classifier (F / numerosity), and the most general subsumer of an
action set is drawn uniformly among equally general candidates.
"""

from __future__ import annotations

from bisect import bisect_right
from collections.abc import Iterable, Sequence
from itertools import accumulate

import numpy as np

from .xcs_params import Settings
from .xcs_population import Population, bits_to_int, more_general

MAX_COVERING_ROUNDS = 1000
"""Covering repeats while deletion keeps removing advocates it just made; with N >= the number
of actions it ends after a few rounds, this bound only turns a pathology into an error."""
OFFSPRING_FITNESS_FACTOR = 0.1
"""B&W: an offspring's fitness is a tenth of its parents' (it has not proven itself yet)."""


def cover(population: Population, state: int, action: int, settings: Settings,
          rng: np.random.Generator, time: int) -> int:
    """Add a classifier for ``action`` whose condition matches the state (an integer, bit i
    for position i), each position a # with probability p_hash; returns its row."""
    specified = bits_to_int(rng.random(population.n_bits) >= settings.p_hash)
    return population.add(specified, state & specified, action,
                          prediction=settings.prediction_init, error=settings.error_init,
                          fitness=settings.fitness_init, experience=0, numerosity=1,
                          action_set_size=1.0, time_stamp=time)


def match_set(population: Population, words: np.ndarray, state: int, permitted: np.ndarray,
              all_permitted: bool, settings: Settings, rng: np.random.Generator,
              time: int) -> tuple[np.ndarray, np.ndarray]:
    """GENERATE MATCH SET: [M] (rows) for the packed state ``words`` and their actions, after
    covering every permitted action that no matching classifier advocates (``all_permitted``:
    ``permitted`` is every action)."""
    for _ in range(MAX_COVERING_ROUNDS):
        match = population.match(words)
        actions = population.action[match]
        if all_permitted and len(set(actions.tolist())) == settings.n_actions:
            return match, actions  # (the set: cheaper than a count on small sets)
        advocates = np.bincount(actions, minlength=settings.n_actions)
        missing = permitted[advocates[permitted] == 0]
        if missing.size == 0:
            return match, actions
        for action in missing:
            cover(population, state, int(action), settings, rng, time)
            delete_from_population(population, settings, rng)
    raise RuntimeError("XCS: covering kept being undone by deletion; N is too small")


def delete_from_population(population: Population, settings: Settings,
                           rng: np.random.Generator, times: int = 1) -> None:
    """Remove one micro-classifier, ``times`` times, while the population holds more than N of
    them (each removal spins the wheel with its own draw)."""
    population.delete_over(settings.N, times, rng, settings.theta_del, settings.delta)


def two_point_crossover(first: tuple[int, int], second: tuple[int, int], start: int,
                        stop: int) -> tuple[tuple[int, int], tuple[int, int]]:
    """Two (care, value) conditions with their positions [start, stop) exchanged."""
    segment = ((1 << stop) - 1) ^ ((1 << start) - 1)
    keep = ~segment
    return ((first[0] & keep | second[0] & segment, first[1] & keep | second[1] & segment),
            (second[0] & keep | first[0] & segment, second[1] & keep | first[1] & segment))


def mutate_condition(condition: tuple[int, int], positions: Iterable[int],
                     state: int) -> tuple[int, int]:
    """Niche mutation of the given positions: each flips between # and the state's bit, so
    the condition still matches the state."""
    care, value = condition
    for position in positions:
        bit = 1 << int(position)
        if care & bit:
            care, value = care & ~bit, value & ~bit
        else:
            care, value = care | bit, value | (state & bit)
    return care, value


def mutate_action(action: int, draw: float, choice: float, settings: Settings) -> int:
    """Another action, uniformly among the rest, when ``draw`` < mu (``choice`` in [0, 1)
    picks it)."""
    if settings.n_actions < 2 or draw >= settings.mu:
        return action
    other = int(choice * (settings.n_actions - 1))
    return other + (other >= action)


_DRAWS = 9
"""Uniform draws per GA besides the 2 x L mutation draws: two roulette spins (0, 1), crossover
or not (2), two crossover points (3, 4), whether each offspring's action mutates (5, 6) and to
which action (7, 8)."""


def run_ga(population: Population, rows: np.ndarray, fitness: Sequence[float], state: int,
           settings: Settings, rng: np.random.Generator) -> None:
    """Two offspring from the live action set ``rows`` with fitnesses ``fitness`` (eq. 7.3
    already passed, time stamps already set): roulette-wheel selection of the parents,
    two-point crossover with probability chi, niche mutation, GA subsumption by a parent or
    insertion, then deletion down to N. All the GA's random numbers come from one draw; the
    few numbers of two parents and two children are handled as Python numbers (cheaper than
    array calls at this size)."""
    n_bits = population.n_bits
    draws = rng.random(_DRAWS + 2 * n_bits).tolist()
    cumulative = list(accumulate(fitness))  # left to right, as np.add.accumulate sums
    candidates, total = rows.tolist(), cumulative[-1]
    parents = [candidates[min(bisect_right(cumulative, spin * total), len(candidates) - 1)]
               for spin in draws[:2]]
    prediction, error, fitness_, set_size, experience, numerosity, stamp = (
        population.stats.take(parents, axis=1).tolist())
    micro_fitness = [fitness_[0] / numerosity[0], fitness_[1] / numerosity[1]]
    keys = [population.keys[parents[0]], population.keys[parents[1]]]
    conditions = [keys[0][:2], keys[1][:2]]
    # the parents that COULD SUBSUME (B&W): experienced and accurate (the GA moves neither)
    subsumers = [index for index in (0, 1) if experience[index] > settings.theta_sub
                 and error[index] < settings.epsilon_0]
    if draws[2] < settings.chi:
        start, stop = sorted((int(draws[3] * (n_bits + 1)), int(draws[4] * (n_bits + 1))))
        conditions = list(two_point_crossover(conditions[0], conditions[1], start, stop))
        prediction = [(prediction[0] + prediction[1]) / 2] * 2
        error = [(error[0] + error[1]) / 2] * 2
        micro_fitness = [(micro_fitness[0] + micro_fitness[1]) / 2] * 2
    mutations = draws[_DRAWS:]
    if min(mutations) < settings.mu:  # (rarely: most offspring keep their condition)
        for child in (0, 1):
            positions = [position for position, draw
                         in enumerate(mutations[child * n_bits:(child + 1) * n_bits])
                         if draw < settings.mu]
            conditions[child] = mutate_condition(conditions[child], positions, state)
    for child in (0, 1):
        condition = conditions[child]
        action = mutate_action(keys[child][2], draws[5 + child], draws[7 + child], settings)
        if settings.ga_subsumption and _subsume(population, parents, keys, subsumers,
                                                condition, action):
            continue
        insert(population, condition, action, prediction=prediction[child],
               error=error[child], fitness=OFFSPRING_FITNESS_FACTOR * micro_fitness[child],
               action_set_size=set_size[child], time_stamp=int(stamp[child]))
    delete_from_population(population, settings, rng, times=2)  # one for each offspring


def _subsume(population: Population, parents: list[int], keys: list[tuple[int, int, int]],
             subsumers: list[int], condition: tuple[int, int], action: int) -> bool:
    """GA subsumption: the first parent able to subsume (``subsumers``: their indices) that
    has the offspring's action and is more general absorbs it; whether one did."""
    for index in subsumers:
        key = keys[index]
        if key[2] == action and more_general(key[:2], condition):
            population.numerosity[parents[index]] = population.numerosity.item(parents[index]) + 1
            population.micro_count += 1
            return True
    return False


def insert(population: Population, condition: tuple[int, int], action: int, *,
           prediction: float, error: float, fitness: float, action_set_size: float,
           time_stamp: int) -> None:
    """INSERT IN POPULATION: one more copy of an identical classifier, else a new one."""
    row = population.find(condition[0], condition[1], action)
    if row >= 0:
        population.numerosity[row] = population.numerosity.item(row) + 1
        population.micro_count += 1
        return
    population.add(condition[0], condition[1], action, prediction=prediction, error=error,
                   fitness=fitness, experience=0, numerosity=1, action_set_size=action_set_size,
                   time_stamp=time_stamp)


def action_set_subsumption(population: Population, rows: np.ndarray, settings: Settings,
                           rng: np.random.Generator) -> None:
    """The most general classifier of [A] that could subsume absorbs every classifier of [A]
    it is more general than (their numerosities move to it)."""
    candidates = rows[(population.experience[rows] > settings.theta_sub)
                      & (population.error[rows] < settings.epsilon_0)]
    if candidates.size == 0:
        return
    specificity = population.specificity[candidates]
    most_general = candidates[specificity == specificity.min()]
    subsumer = int(most_general[rng.integers(most_general.size)])
    general = population.keys[subsumer][:2]
    for row in rows:
        if row != subsumer and more_general(general, population.keys[row][:2]):
            population.numerosity[subsumer] += population.numerosity[row]
            population.micro_count += int(population.numerosity[row])
            population.kill(int(row))
