"""What every goalagent Gymnasium environment checks before it touches its world.

A bad keyword of ``gymnasium.make`` is a ``ValueError`` naming the keyword and what it takes;
an unknown ``reset`` option a ``ValueError`` listing the known ones; ``step`` before ``reset``
(or after the episode ended) Gymnasium's ``ResetNeeded``; an action outside the action space
Gymnasium's ``InvalidAction``. Every check runs before the world is touched, so a refused call
leaves the environment exactly as it was.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from numbers import Integral
from typing import Any, TypeVar

import gymnasium as gym
from gymnasium.error import InvalidAction, ResetNeeded

T = TypeVar("T")


def choice(name: str, value: T, allowed: tuple[T, ...]) -> T:
    """``value`` if it is one of ``allowed``, else a ValueError naming ``name``."""
    if value not in allowed:
        listed = ", ".join(repr(a) for a in allowed)
        raise ValueError(f"{name} must be one of {listed}; got {value!r}")
    return value


def whole(name: str, value: object, low: int, high: int | None = None) -> int:
    """``value`` as an int if it is a whole number within low..high (no bools)."""
    if isinstance(value, bool) or not isinstance(value, Integral):
        raise ValueError(f"{name} must be a whole number, got {value!r}")
    if value < low or (high is not None and value > high):
        bound = f"{low}..{high}" if high is not None else f"{low} or more"
        raise ValueError(f"{name} must be {bound}, got {value}")
    return int(value)


def reset_options(options: Mapping[str, Any] | None,
                  known: Mapping[str, Callable[[object], object]]) -> dict[str, object]:
    """The options of ``reset`` checked by ``known`` (name -> checker returning the value)."""
    if options is None:
        return {}
    if not isinstance(options, Mapping):
        raise ValueError(f"reset options must be a dict, got {type(options).__name__}")
    unknown = sorted(str(key) for key in options if key not in known)
    if unknown:
        listed = ", ".join(repr(k) for k in known) or "none"
        raise ValueError(f"unknown reset option(s) {', '.join(map(repr, unknown))}; "
                         f"this environment takes {listed}")
    return {key: known[key](value) for key, value in options.items()}


def ready_to_step(started: bool, over: bool) -> None:
    """ResetNeeded unless an episode is running."""
    if not started:
        raise ResetNeeded("cannot call step() before reset(): reset() sets the task up")
    if over:
        raise ResetNeeded("the episode has ended (terminated or truncated); call reset() to "
                          "start the next one")


def valid_action(space: gym.Space, action: object, meaning: str) -> None:
    """InvalidAction unless ``space`` contains ``action``; ``meaning`` says what the actions
    are."""
    try:
        contained = space.contains(action)
    except (TypeError, ValueError):  # e.g. a string given to a Box
        contained = False
    if not contained:
        raise InvalidAction(f"action {action!r} is not in the action space {space} "
                            f"({meaning})")
