"""XCS as an agent steps it: `act` on a state, then `reward` the action (thesis App. A).

One `act` forms the match set [M] (covering the permitted actions no classifier advocates),
the prediction array (eq. 3.8) and the action set [A]; in explore mode it then reinforces the
previous step's action set [A]-1 with P = r-1 + gamma * max PA (eq. 7.2) and runs the niche GA
there. `reward(r, done)` closes the step: on the last step of a trial [A] itself is reinforced
with P = r (single-step problems are one-step trials). Exploit steps choose greedily and learn
nothing (App. A, "Performance Component"), unless ``learn_in_exploit``: then they update
[A]-1 and [A] as explore steps do (Algorithm 2 credits every step) but run no GA and leave the
GA's clock alone (rule discovery belongs to exploration). Explore steps choose at random among
the advocated actions, or, with ``consistent_actions``, keep the previous action as App. A
describes.

`allowed` is Algorithm 2's action filter (eq. 3.10): the choice ranges over the allowed actions
only. `considered` (a superset) is what max PA in eq. 7.2 and covering range over: Algorithm 2
filters the choice only, so it passes every applicable action; left out, it is `allowed` (the
filter then shapes the values too).

The learner's parameters are checked by scikit-learn (``_parameter_constraints``), once; the
arguments of each step (the state, ``explore``, ``allowed``, ``r``, ``done``) are checked by
hand, because scikit-learn's validators cost a fifth of a multiplexer trial each.
"""

from __future__ import annotations

import numbers
import reprlib
from collections.abc import Iterable
from dataclasses import dataclass
from operator import mul
from os import PathLike
from typing import ClassVar

import numpy as np
from sklearn.base import BaseEstimator
from sklearn.utils import Tags
from sklearn.utils.validation import check_scalar

from . import xcs_persistence
from .tags import with_domain
from .xcs_choice import best_action, explore_action, prediction_array
from .xcs_discovery import action_set_subsumption, match_set, run_ga
from .xcs_inputs import check_reward, permitted_actions, state_bits
from .xcs_params import CONSTRAINTS, Settings, make_generator
from .xcs_population import (
    FITNESS,
    NUMEROSITY,
    TIME_STAMP,
    Classifier,
    Population,
    bits_to_int,
    int_to_words,
    words_for,
)
from .xcs_update import UpdateConstants, update_action_set

STATE_CACHE_SIZE = 1 << 16
_all = np.logical_and.reduce
"""The ufunc reduction itself: ndarray.all adds a Python-level call per use."""


@dataclass(slots=True)
class _Step:
    """What one `act` left behind: its action set (rows), action, state (bit i is position
    i), mode and the population's kill count."""

    rows: np.ndarray
    action: int
    state: int
    explore: bool
    kills: int
    """`Population.kills` when the set was formed: while it is unchanged, all rows live."""
    learns: bool = True
    """Whether the step is credited: every explore step, exploit steps with learn_in_exploit."""
    reward: float = 0.0


class XCS(BaseEstimator):
    """Wilson's XCS over binary states and ``n_actions`` integer actions (see module doc).

    Parameters keep the names of Butz & Wilson (2001) and thesis Table 7.1; ``beta_p``,
    ``beta_e``, ``beta_f`` (eq. 7.1, 7.4, 7.5) default to ``beta``. They are stored as given
    and checked (``_parameter_constraints``) once, at the learner's first use; `set_params`
    on a started learner takes effect at its next step (``random_state`` only seeds a learner
    that has not started). The state length is fixed by the first state seen. Learned state:
    ``population_`` (the classifiers), ``time_`` (the number of explore steps, the GA's
    clock), ``n_bits_``.

    XCS learns from rewards, step by step (`act`, `reward`), not from (X, y): it has no `fit`,
    so scikit-learn's estimator checks that need one do not apply; `XCSClassifier` is its
    face for those.
    """

    _parameter_constraints: ClassVar[dict[str, list]] = CONSTRAINTS
    _settings: Settings | None = None
    """The checked parameters; None until the first use (and after `set_params`)."""

    def __init__(self, n_actions: int, *, N: int = 400, beta: float = 0.2,
                 beta_p: float | None = None, beta_e: float | None = None,
                 beta_f: float | None = None, gamma: float = 0.71, alpha: float = 0.1,
                 epsilon_0: float = 10.0, nu: float = 5.0, theta_ga: float = 25,
                 chi: float = 0.8, mu: float = 0.04, theta_del: int = 20, delta: float = 0.1,
                 theta_sub: int = 20, p_hash: float = 0.33, prediction_init: float = 10.0,
                 error_init: float = 0.0, fitness_init: float = 0.01,
                 ga_subsumption: bool = True, action_set_subsumption: bool = False,
                 consistent_actions: bool = False, learn_in_exploit: bool = False,
                 random_state: object = None) -> None:
        self.n_actions = n_actions
        self.N, self.beta, self.beta_p, self.beta_e, self.beta_f = N, beta, beta_p, beta_e, beta_f
        self.gamma, self.alpha, self.epsilon_0, self.nu = gamma, alpha, epsilon_0, nu
        self.theta_ga, self.chi, self.mu, self.theta_del = theta_ga, chi, mu, theta_del
        self.delta, self.theta_sub, self.p_hash = delta, theta_sub, p_hash
        self.prediction_init, self.error_init = prediction_init, error_init
        self.fitness_init = fitness_init
        self.ga_subsumption = ga_subsumption
        self.action_set_subsumption = action_set_subsumption
        self.consistent_actions = consistent_actions
        self.learn_in_exploit = learn_in_exploit
        self.random_state = random_state

    def __sklearn_tags__(self) -> Tags:
        return with_domain(super().__sklearn_tags__(), binary=True)

    def set_params(self, **params: object) -> XCS:
        """scikit-learn's `set_params`; the new values are checked at the next use."""
        super().set_params(**params)
        self.__dict__.pop("_settings", None)
        return self

    def _start(self) -> Settings:
        """Check the parameters and derive the hot path's constants from them; on the first
        use also create the learned state (an empty population, the clock, the generator)."""
        self._validate_params()
        settings = Settings.resolve(type(self).__name__, self.get_params(deep=False))
        if self.__dict__.get("population_") is not None and np.any(
                self.population_.action[:self.population_.size] >= settings.n_actions):
            raise ValueError(f"{type(self).__name__}: n_actions cannot drop below the "
                             f"actions of the learned population; clone a new learner")
        self._constants = UpdateConstants.of(settings)
        self._all_actions = np.arange(settings.n_actions)
        self._action_values = [np.array(action) for action in range(settings.n_actions)]
        if "time_" not in self.__dict__:
            self._rng = make_generator(self.random_state)
            self.population_: Population | None = None
            self.n_bits_: int | None = None
            self.time_ = 0
            self._pending: _Step | None = None
            self._previous: _Step | None = None
            self._states: dict[object, tuple[np.ndarray, int]] = {}
        self._settings = settings
        return settings

    def _ready(self) -> Settings:
        """The checked parameters, checking them first if this is the first use."""
        settings = self._settings
        return settings if settings is not None else self._start()

    # -- the agent-facing interface ------------------------------------------------------------

    def act(self, state: object, explore: bool = True,
            allowed: Iterable[int] | None = None, *,
            considered: Iterable[int] | None = None) -> int:
        """Choose an action for ``state`` (a "0101" string or a 0/1 sequence).

        Explore: a random advocated action (or, with ``consistent_actions``, the previous one
        while [A]-1 still matches); exploit: the best by eq. 3.9. ``allowed`` (action indices)
        restricts the choice; ``considered`` (a superset of ``allowed``; default ``allowed``)
        is what eq. 7.2's max and covering range over.
        """
        if self._settings is None:  # (written out: a call costs ~1% of a trial)
            self._start()
        if explore is not True and explore is not False and not isinstance(explore, np.bool_):
            raise ValueError(f"explore must be True or False, got {explore!r}")
        n_actions = self._all_actions.size
        permitted = (self._all_actions if allowed is None
                     else permitted_actions(allowed, n_actions))
        covered = permitted
        if considered is not None:
            covered = permitted_actions(considered, n_actions)
            if covered.size == n_actions:
                covered = self._all_actions
            if np.setdiff1d(permitted, covered).size:
                raise ValueError(f"allowed {permitted.tolist()} must be among the considered "
                                 f"actions {covered.tolist()}")
        words, number = self._encode(state)
        if self._pending is not None and self._pending.learns:
            raise ValueError("act: the previous action has not been rewarded; "
                             "call reward(r, done) first")
        self._pending = None
        learns = bool(explore) or self._settings.learn_in_exploit
        previous, self._previous = self._previous, None
        previous = self._compact_keeping(previous if learns else None)
        if explore:
            self.time_ += 1
        match, actions = match_set(self.population_, words, number, covered,
                                   covered is self._all_actions, self._settings, self._rng,
                                   self.time_)
        kills = self.population_.kills  # before [A]-1's GA can delete from [A]
        values: list[float] = []  # eq. 3.8 for the permitted actions, all advocated now
        best_value = 0.0  # max PA of eq. 7.2 over the considered actions
        if not explore or previous is not None:  # (a single explore step needs none)
            prediction = prediction_array(self.population_, match, actions,
                                              self._settings.n_actions)
            values = (prediction if allowed is None else prediction[permitted]).tolist()
            best_value = max(values if covered is permitted
                             else prediction[covered].tolist())
        if explore:
            kept = previous if self._settings.consistent_actions else None
            action = explore_action(permitted, self._rng, self.population_, words,
                                    None if kept is None else kept.rows,
                                    -1 if kept is None else kept.action)
        else:
            action = best_action(values, permitted, self._rng)
        action_set = (match[actions == self._action_values[action]] if learns
                      else match[:0])  # steps that are not credited learn nothing
        if previous is not None:
            self._reinforce(previous, previous.reward
                            + self._settings.gamma * best_value)  # eq. 7.2
        self._pending = _Step(action_set, action, number, bool(explore), kills, learns)
        return action

    def reward(self, r: float, done: bool) -> None:
        """The reward of the action `act` just returned; ``done`` ends the trial."""
        if self._settings is None:
            self._start()
        check_reward(r, done)
        step, self._pending = self._pending, None
        if step is None:
            raise ValueError("reward: no action to reward; call act(state) first")
        if not step.learns:
            return
        if done:
            self._reinforce(step, float(r))
        else:
            step.reward = float(r)
            self._previous = step

    def end_trial(self) -> None:
        """End a trial cut short (a step limit) without a terminal reward: the last action
        set stays unreinforced, as in Butz & Wilson, and the next `act` starts a new trial."""
        self._ready()
        self._pending = None
        self._previous = None

    def prediction_array(self, state: object) -> np.ndarray:
        """Eq. 3.8 for every action on ``state``: NaN where no classifier advocates it.
        A query: nothing is covered or learned."""
        self._ready()
        if self.population_ is None:
            self._encode(state, fix_length=False)
            return np.full(self._settings.n_actions, np.nan)
        words, _ = self._encode(state)
        match = self.population_.match(words)
        return prediction_array(self.population_, match, self.population_.action[match],
                                self._settings.n_actions)

    def classifiers(self) -> list[Classifier]:
        """Every macro-classifier as a `Classifier` record."""
        self._ready()
        return [] if self.population_ is None else self.population_.records()

    @property
    def macro_count(self) -> int:
        """Number of macro-classifiers (distinct condition-action pairs) in the population."""
        self._ready()
        return 0 if self.population_ is None else self.population_.macro_count

    @property
    def micro_count(self) -> int:
        """Sum of numerosities (what N bounds)."""
        self._ready()
        return 0 if self.population_ is None else self.population_.micro_count

    def set_classifiers(self, classifiers: Iterable[Classifier | tuple], *,
                        time: int | None = None) -> None:
        """Replace the population (e.g. a hand-built one); ``time`` sets the GA clock
        (default: the latest time stamp, or the current clock if later)."""
        settings = self._ready()
        records = xcs_persistence.check_records(classifiers, settings.n_actions, settings.N)
        if time is not None:
            check_scalar(time, "time", numbers.Integral, min_val=0)
        n_bits = len(records[0].condition) if records else self.n_bits_
        population = None
        if n_bits is not None:
            population = Population(n_bits, settings.N + settings.n_actions + 2)
            xcs_persistence.fill(population, records)
        self.population_, self.n_bits_ = population, n_bits
        self._states.clear()
        latest = max((record.time_stamp for record in records), default=0)
        self.time_ = int(time) if time is not None else max(self.time_, latest)
        self.end_trial()

    def save(self, path: str | PathLike[str]) -> None:
        """Write parameters, population, clock and random state to ``path`` atomically."""
        self._ready()
        xcs_persistence.save(self, path)

    @classmethod
    def load(cls, path: str | PathLike[str]) -> XCS:
        """A learner saved by `save`, continuing where it stopped (a new trial)."""
        return xcs_persistence.load(cls, path)

    # -- performance component -----------------------------------------------------------------

    def _encode(self, state: object, fix_length: bool = True) -> tuple[np.ndarray, int]:
        """Packed words and the integer (bit i = position i) of a state, checked against the
        state length."""
        key = state if type(state) is str or isinstance(state, str | tuple) else None
        if key is not None:
            encoded = self._states.get(key)
            if encoded is not None:
                return encoded
        bits = state_bits(state)
        if self.n_bits_ is None and fix_length:
            self.n_bits_ = bits.size
            settings = self._settings
            self.population_ = Population(bits.size, settings.N + settings.n_actions + 2)
        if self.n_bits_ is not None and bits.size != self.n_bits_:
            raise ValueError(f"state must have {self.n_bits_} bits, got {bits.size}: "
                             f"{reprlib.repr(state)}")
        number = bits_to_int(bits)
        # as many words as the population's masks, which have one bit past the state
        encoded = (int_to_words(number, words_for(bits.size + 1)), number)
        if key is not None and self.n_bits_ is not None:
            if len(self._states) >= STATE_CACHE_SIZE:
                self._states.clear()
            self._states[key] = encoded
        return encoded

    # -- reinforcement component ---------------------------------------------------------------

    def _reinforce(self, step: _Step, payoff: float) -> None:
        """UPDATE SET on the step's live action set with payoff P, then (explore steps only)
        the GA there when eq. 7.3 says the set's classifiers have waited long enough."""
        population, settings = self.population_, self._settings
        rows = step.rows
        stats = population.stats.take(rows, axis=1)
        if population.kills != step.kills:  # some classifiers may have been deleted
            live = stats[NUMEROSITY] > 0
            if not _all(live):
                rows, stats = rows[live], stats.compress(live, axis=1)
            if rows.size == 0:  # every classifier of the set was deleted meanwhile
                return
        numerosity, stamps, fitness, set_size = update_action_set(
            population, rows, stats, payoff, settings, self._constants)
        if settings.action_set_subsumption:  # numerosities move, their sum stays
            action_set_subsumption(population, rows, settings, self._rng)
            rows = rows[population.alive(rows)]
            columns = population.stats.take(rows, axis=1).tolist()
            numerosity, stamps = columns[NUMEROSITY], columns[TIME_STAMP]
            fitness = columns[FITNESS]
        if not step.explore:
            return
        # eq. 7.3's numerosity-weighted time stamps: whole numbers, exact in any order
        stamp_sum = sum(map(mul, stamps, numerosity))
        if self.time_ - stamp_sum / set_size > settings.theta_ga:  # eq. 7.3
            population.time_stamp[rows] = self.time_
            run_ga(population, rows, fitness, step.state, settings, self._rng)

    def _compact_keeping(self, previous: _Step | None) -> _Step | None:
        """Drop dead slots once they are half the population; remap [A]-1 if one is held."""
        population = self.population_
        if population is None:
            return previous
        live = population.macro_count
        if population.size - live < max(32, live):
            return previous
        mapping = population.compact()
        if previous is not None:
            rows = mapping[previous.rows]
            previous.rows = rows[rows >= 0]
        return previous
