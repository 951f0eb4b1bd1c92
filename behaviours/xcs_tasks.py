"""The three XCS tasks: navigation and stacking (thesis §3.5) and head-camera search (App. A).

A task turns one action index into world calls (Table 3.1's behaviours, App. A's head moves),
perceives the state before and after it, and returns the reward (eqs. 3.14, 3.15, App. A),
whether the trial is over, and the push effect for the affordance table (§3.5.2). ``applicable``
gives each state's actions whose preconditions hold (§3.2.2: preconditions are domain
knowledge; §3.5.4: the NAO confirmed that the requested object was in front before trying to
push it), so stacking pushes only with an object in front. Trials start
from the same setting each time (§3.5.7); ``reset(trial)`` also makes the world's change of
the experiment: the boxes exchanged after ``exchange_after`` trials, the target moved after
``move_after``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np

from behaviours.blob_grid import GridPerception, centre_seen
from behaviours.object_state import ObjectPerception, ObjectState, push_effect
from sim.navigation import LANES, START_LANE, NavigationWorld
from sim.search import SearchWorld
from sim.stacking import StackingWorld

D_DST = 0.05
"""The goal is reached within this distance (m) of the destination (eq. 3.14)."""
D_MOVE = 0.05
"""A step that brings the robot less than this (m) nearer the destination is punished (3.14)."""
GOAL_REWARD = 1000.0
PUNISHMENT = -100.0
NAVIGATION_ACTIONS = {"000": "walk_left", "001": "walk_ahead", "011": "walk_right",
                      "010": "push_ahead"}
STACKING_ACTIONS = {"100": "push_stand", "101": "push_squat", "110": "choose_box",
                    "111": "choose_foam"}
"""Table 3.1: the navigation task uses the first four actions, stacking the latter four."""
NAVIGATION_STARTS = ("right_lane", "anywhere")
"""Where a navigation trial starts: the right-most lane (facing the right box), or a lane drawn
per trial (§3.5.7: "anywhere on one side of the area")."""
SEARCH_ACTIONS = {"00": "look_up", "01": "look_right", "10": "look_down", "11": "look_left"}
"""App. A: one bit per head motor and direction."""


def navigation_reward(distance: float, progress: float) -> float:
    """Eq. 3.14: 1000 within ``D_DST`` of the destination, -100 for progress under ``D_MOVE``."""
    if distance < D_DST:
        return GOAL_REWARD
    if progress < D_MOVE:
        return PUNISHMENT
    return 0.0


def stacking_reward(stacked: bool, chose: bool) -> float:
    """Eq. 3.15: 1000 once the stack is as high as the table, -100 for choosing an object."""
    if stacked:
        return GOAL_REWARD
    return PUNISHMENT if chose else 0.0


def search_reward(bits: str) -> float:
    """App. A: 1000 when the centre of the image sees the target, else nothing."""
    return GOAL_REWARD if centre_seen(bits) else 0.0


@dataclass(frozen=True)
class View:
    """The state a learner sees: its bits and the object in front (None: nothing, or search)."""

    bits: str
    obj: str | None


@dataclass(frozen=True)
class StepResult:
    """What one action brought: reward, end of trial, success, and the push effect (if any)."""

    reward: float
    done: bool
    success: bool
    effect: int | None = None


class Task(Protocol):
    """An episodic task over a MuJoCo world."""

    actions: tuple[str, ...]
    names: dict[str, str]

    def reset(self, trial: int) -> View: ...
    def perform(self, action: int) -> tuple[StepResult, View]: ...
    def view(self) -> View: ...
    def applicable(self, view: View) -> tuple[int, ...] | None: ...


def _view(state: ObjectState) -> View:
    return View(state.bits, state.object_bits if state.front is not None else None)


class NavigationTask:
    """Reach the destination past the two boxes (§3.5.1); the boxes swap after a while."""

    names = NAVIGATION_ACTIONS
    actions = tuple(NAVIGATION_ACTIONS)

    def __init__(self, world: NavigationWorld, perception: ObjectPerception,
                 exchange_after: int = 10, start: str = "right_lane", seed: int = 0):
        """Drive ``world`` and perceive it with ``perception``. ``start``: every trial in the
        right-most lane, or ``anywhere`` (§3.5.7): a lane drawn for each trial from ``seed``."""
        if start not in NAVIGATION_STARTS:
            raise ValueError(f"unknown start {start!r}; use {' or '.join(NAVIGATION_STARTS)}")
        self.world, self.perception, self.exchange_after = world, perception, exchange_after
        self.start, self.seed = start, seed
        self.state = perception.observe(world)

    def view(self) -> View:
        """What the robot perceived after its last action."""
        return _view(self.state)

    def applicable(self, view: View) -> None:
        """Every action applies anywhere (walking into a box or off the table is allowed)."""
        return None

    def reset(self, trial: int) -> View:
        """Start trial ``trial`` (0-based): the boxes are exchanged from ``exchange_after`` on."""
        self.world.reset(exchanged=trial >= self.exchange_after, lane=self.start_lane(trial))
        self.state = self.perception.observe(self.world)
        return _view(self.state)

    @staticmethod
    def best_payoff(lane: float, exchanged: bool) -> float:
        """The most payoff (eq. 3.16) a trial starting in ``lane`` can earn: a punished step
        sideways (eq. 3.14) per lane to the nearest one facing the movable box, which is on
        the right (-y) until the exchange, then pushes to the destination (+1000)."""
        facing = [i for i, y in enumerate(LANES) if (y < 0) != exchanged]
        steps = min(abs(LANES.index(lane) - i) for i in facing)
        return GOAL_REWARD + PUNISHMENT * steps

    def start_lane(self, trial: int) -> float:
        """Where trial ``trial`` starts: the right-most lane, or one drawn from (seed, trial)."""
        if self.start == "right_lane":
            return START_LANE
        return LANES[int(np.random.default_rng([self.seed, trial]).integers(len(LANES)))]

    def perform(self, action: int) -> tuple[StepResult, View]:
        """Walk or push, then reward by eq. 3.14; falling off the table ends the trial."""
        name = self.names[self.actions[action]]
        before, distance = self.state, self.world.distance_to_destination()
        if name == "push_ahead":
            self.world.push()
        else:
            self.world.walk(name.removeprefix("walk_"))
        self.state = self.perception.observe(self.world)
        now = self.world.distance_to_destination()
        reward = navigation_reward(now, distance - now)
        success = now < D_DST
        effect = push_effect(before, self.state) if name == "push_ahead" else None
        return StepResult(reward, success or self.world.fallen, success, effect), _view(self.state)


class StackingTask:
    """Make a stack beside the table as high as the table (Fig. 3.4)."""

    names = STACKING_ACTIONS
    actions = tuple(STACKING_ACTIONS)

    def __init__(self, world: StackingWorld, perception: ObjectPerception,
                 push_needs_object: bool = True):
        """Drive ``world`` and perceive it with ``perception``; with ``push_needs_object``
        (§3.5.4) a push applies only when an object is perceived in front."""
        self.world, self.perception = world, perception
        self.push_needs_object = push_needs_object
        self.state = perception.observe(world)
        self._choices = tuple(i for i, a in enumerate(self.actions)
                              if self.names[a].startswith("choose"))

    def applicable(self, view: View) -> tuple[int, ...] | None:
        """Only the choices while nothing is perceived in front (§3.5.4), else every action."""
        return self._choices if self.push_needs_object and view.obj is None else None

    def view(self) -> View:
        """What the robot perceived after its last action."""
        return _view(self.state)

    def reset(self, trial: int) -> View:
        """Start a trial: the lift up and empty, every object back with the operator."""
        self.world.reset()
        self.state = self.perception.observe(self.world)
        return _view(self.state)

    def perform(self, action: int) -> tuple[StepResult, View]:
        """Push in a pose or ask for an object, then reward by eq. 3.15."""
        name = self.names[self.actions[action]]
        before = self.state
        verb, what = name.split("_")
        if verb == "push":
            self.world.push(what)
        else:
            self.world.choose(what)
        self.state = self.perception.observe(self.world)
        stacked = self.world.state().stacked
        effect = push_effect(before, self.state) if verb == "push" else None
        return (StepResult(stacking_reward(stacked, verb == "choose"), stacked, stacked, effect),
                _view(self.state))


class SearchTask:
    """Turn the head until the centre of the image sees the target (App. A)."""

    names = SEARCH_ACTIONS
    actions = tuple(SEARCH_ACTIONS)

    def __init__(self, world: SearchWorld, perception: GridPerception,
                 places: tuple[str, str] = ("up_left", "right"), move_after: int = 10):
        """The target stands at ``places[0]`` for ``move_after`` trials, then at ``places[1]``."""
        self.world, self.perception = world, perception
        self.places, self.move_after = places, move_after

    def reset(self, trial: int) -> View:
        """Start a trial from the resting pose, the target where this trial has it."""
        self.world.place_target(self.places[int(trial >= self.move_after)])
        self.world.rest()
        return self.view()

    def applicable(self, view: View) -> None:
        """Every look applies anywhere (past the boundary the head is reset)."""
        return None

    def view(self) -> View:
        """What the head camera sees now."""
        return View(self.perception.observe(self.world), None)

    def perform(self, action: int) -> tuple[StepResult, View]:
        """Turn the head one step (reset past the boundary) and reward what the centre sees."""
        self.world.look(self.names[self.actions[action]].removeprefix("look_"))
        view = self.view()
        found = centre_seen(view.bits)
        return StepResult(search_reward(view.bits), found, found), view
