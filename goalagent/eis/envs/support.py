"""What the simulated environments (bw4t, elevator, hanoi) share: rounds of agent cycles,
lenient init-parameter values, and PNG snapshots written atomically.

Simulated time: the Java environments run in real time beside the agents. Here the world is
advanced in *rounds*: a round ends when an entity perceives a second time since the last
round began, i.e. when every agent that is still running has had its cycle (agents take turns,
one cycle each, in ``MultiAgentSystem.run``). Each environment then advances its clock by one
round's worth of time before computing that entity's percepts. Deterministic, and the world
moves at the same pace whatever the machine's speed.
"""

from __future__ import annotations

import io
import os
from collections.abc import Callable, Mapping
from pathlib import Path

from goalagent.eis.exceptions import ManagementException
from goalagent.extras import install_hint
from goalagent.kb.terms import Atom
from ondisk import write_atomically

_TRUE = {"true", "yes", "on", "1"}
_FALSE = {"false", "no", "off", "0"}


class RoundClock:
    """Counts rounds of agent cycles from perceive calls (see the module docstring)."""

    def __init__(self) -> None:
        self.rounds = 0
        self._seen: set[str] = set()

    def perceive(self, entity: str) -> bool:
        """Note that ``entity`` perceives; True when this begins a new round."""
        if entity in self._seen:
            self._seen = {entity}
            self.rounds += 1
            return True
        self._seen.add(entity)
        return False


def _text(value: object) -> str | None:
    """Atoms and strings as text (``"3"``, ``'Banana'``), anything else None."""
    return str(value) if isinstance(value, (str, Atom)) else None


def int_param(env: str, params: Mapping[str, object], key: str, default: int,
              minimum: int | None = None, maximum: int | None = None) -> int:
    """An integer init parameter; GOAL programs often pass numbers as strings (``"3"``)."""
    value = params.get(key, default)
    text = _text(value)
    if text is not None:
        try:
            value = int(text.strip())
        except ValueError:
            raise ManagementException(
                f"environment '{env}': init parameter '{key}' must be a whole number, "
                f"got {text!r}"
            ) from None
    if isinstance(value, float) and value.is_integer():
        value = int(value)
    if isinstance(value, bool) or not isinstance(value, int):
        raise ManagementException(
            f"environment '{env}': init parameter '{key}' must be a whole number, got {value!r}"
        )
    if (minimum is not None and value < minimum) or (maximum is not None and value > maximum):
        low = "-inf" if minimum is None else minimum
        high = "inf" if maximum is None else maximum
        bounds = f"{low}..{high}"
        raise ManagementException(
            f"environment '{env}': init parameter '{key}' must be in {bounds}, got {value}"
        )
    return value


def float_param(env: str, params: Mapping[str, object], key: str, default: float) -> float:
    """A number init parameter, also accepted as a string (``"0.5"``)."""
    value = params.get(key, default)
    text = _text(value)
    try:
        if text is not None:
            return float(text.strip())
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            return float(value)
    except ValueError:
        pass
    raise ManagementException(
        f"environment '{env}': init parameter '{key}' must be a number, got {value!r}"
    )


def bool_param(env: str, params: Mapping[str, object], key: str, default: bool) -> bool:
    """A yes/no init parameter: ``true``/``false`` as atoms, strings or booleans."""
    value = params.get(key, default)
    if isinstance(value, bool):
        return value
    text = _text(value)
    if text is not None and text.strip().lower() in _TRUE | _FALSE:
        return text.strip().lower() in _TRUE
    raise ManagementException(
        f"environment '{env}': init parameter '{key}' must be true or false, got {value!r}"
    )


def text_param(env: str, params: Mapping[str, object], key: str, default: str) -> str:
    """A name or path init parameter (an atom or a string)."""
    value = params.get(key, default)
    text = _text(value)
    if text is None:
        raise ManagementException(
            f"environment '{env}': init parameter '{key}' must be a name or string, got {value!r}"
        )
    return text


def check_known(env: str, params: Mapping[str, object], known: Mapping[str, str]) -> None:
    """Refuse init parameters not in ``known`` (name -> what it does), listing the known ones."""
    for key in params:
        if key not in known:
            raise ManagementException(
                f"environment '{env}' has no init parameter '{key}' (known: {', '.join(known)})"
            )


def write_png(target: str | os.PathLike[str], draw: Callable[[object], None]) -> Path:
    """Draw a matplotlib figure with ``draw`` and save it as PNG, atomically
    (``ondisk.write_atomically``).

    matplotlib is imported only here, when a picture is asked for (Agg, no display needed).
    """
    try:
        from matplotlib.figure import Figure
    except ModuleNotFoundError as error:
        raise ManagementException(f"a picture of the environment {install_hint(error.name)}"
                                  ) from None

    figure = Figure(figsize=(6, 6), dpi=80)
    draw(figure)
    picture = io.BytesIO()
    figure.savefig(picture, format="png")
    return write_atomically(target, picture.getvalue())


class SnapshotWriter:
    """Writes ``<prefix>-<round>.png`` into a directory (made if missing), each atomically."""

    def __init__(self, directory: str | os.PathLike[str], prefix: str) -> None:
        self.directory = Path(directory)
        self.prefix = prefix
        try:
            self.directory.mkdir(parents=True, exist_ok=True)
        except OSError as error:
            raise ManagementException(
                f"cannot create snapshot directory '{self.directory}': {error.strerror}"
            ) from None

    def path_for(self, round_number: int) -> Path:
        """Where the snapshot of ``round_number`` goes."""
        return self.directory / f"{self.prefix}-{round_number:06d}.png"

    def write(self, round_number: int, draw: Callable[[object], None]) -> Path:
        """Draw and save the snapshot of ``round_number``."""
        return write_png(self.path_for(round_number), draw)
