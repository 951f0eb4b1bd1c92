"""Towers of Hanoi as an EIS environment, with the vocabulary of eishub's ``hanoi`` (GOAL's).

One entity, ``entity`` of type ``hanoicontroller``. Three pins, ``0``, ``1``, ``2``. Discs are
numbered from 1; a higher number is a smaller disc, so disc 1 is the largest. Percepts, every
cycle: ``disc(D, L)`` for each disc, ``L`` its level (10 at the bottom of a pin, one less per
disc above, as the Java model counts it); ``pins(3)``; ``on(D, P, Below)`` for each disc, with
the disc under it or ``0``. Action ``move(D, P)``: put disc ``D``, the top of its pin, on pin
``P`` when ``P`` is empty or its top disc is larger; refused (world unchanged) otherwise. (The
Java environment silently ignores a move of a disc that is not on top; here it is refused with
a reason, as every other bad move.)

Init parameter ``discs = [P1, P2, ...]``: disc ``i`` starts on pin ``Pi`` (listed from the
largest; default ``[0,0,0,0]``); ``snapshots = Dir`` writes one PNG per round.
"""

from __future__ import annotations

from collections.abc import Iterable

from goalagent.eis.envs.support import RoundClock, SnapshotWriter, check_known, text_param
from goalagent.eis.envs.support import write_png as _write_png
from goalagent.eis.exceptions import ActionRefused, ManagementException
from goalagent.eis.pyenv import PerceptLike, PythonEnvironment, action

PINS = 3
BOTTOM_LEVEL = 10
MAX_DISCS = 9  # the Java model draws discs for at most 9 sizes
KNOWN_PARAMETERS = {"discs": "pin of each disc, largest first", "snapshots": "PNG directory"}


class Hanoi(PythonEnvironment):
    """Discs on three pins, moved one at a time onto larger ones."""

    name = "hanoi"
    entity_names = ("entity",)
    default_entity_type = "hanoicontroller"

    @classmethod
    def init_parameters(cls) -> dict[str, str]:
        return KNOWN_PARAMETERS

    def on_init(self, params: dict[str, object]) -> None:
        """Stack the discs as ``discs`` says: disc i on pin discs[i-1], in order."""
        check_known(self.name, params, KNOWN_PARAMETERS)
        start = params.get("discs", [0, 0, 0, 0])
        if not isinstance(start, list) or not all(
            isinstance(pin, int) and not isinstance(pin, bool) for pin in start
        ):
            raise ManagementException(
                f"hanoi: discs must be a list of pin numbers, e.g. [0,0,0], got {start!r}"
            )
        if not 1 <= len(start) <= MAX_DISCS or not all(0 <= pin < PINS for pin in start):
            raise ManagementException(
                f"hanoi: discs must list 1 to {MAX_DISCS} pins, each 0, 1 or 2, got {start}"
            )
        self.pins: list[list[int]] = [[] for _ in range(PINS)]
        for disc, pin in enumerate(start, 1):
            self.pins[pin].append(disc)  # later discs are smaller: they go on top
        self.clock = RoundClock()
        self.snapshots = None
        if params.get("snapshots") is not None:
            self.snapshots = SnapshotWriter(text_param(self.name, params, "snapshots", ""),
                                            "hanoi")

    def percepts(self, entity: str) -> Iterable[PerceptLike]:
        """``disc/2``, ``pins/1`` and ``on/3``, every cycle."""
        if self.clock.perceive(entity) and self.snapshots is not None:
            self.snapshots.write(self.clock.rounds, self.draw)
        result: list[PerceptLike] = []
        for pin in self.pins:
            for height, disc in reversed(list(enumerate(pin))):
                result.append(("disc", disc, BOTTOM_LEVEL - height))
        result.append(("pins", PINS))
        for number, pin in enumerate(self.pins):
            for height, disc in reversed(list(enumerate(pin))):
                result.append(("on", disc, number, pin[height - 1] if height else 0))
        return result

    def pin_of(self, disc: int) -> int | None:
        for number, pin in enumerate(self.pins):
            if disc in pin:
                return number
        return None

    @action("move")
    def move(self, entity: str, disc: int, to: int) -> None:
        """Move ``disc`` (the top of its pin) onto pin ``to``."""
        what = f"move({disc},{to})"
        source = self.pin_of(disc)
        if source is None:
            raise ActionRefused(f"{what}: there is no disc {disc}")
        if not 0 <= to < PINS:
            raise ActionRefused(f"{what}: there is no pin {to} (pins 0, 1, 2)")
        if self.pins[source][-1] != disc:
            raise ActionRefused(f"{what}: disc {disc} is under disc {self.pins[source][-1]}")
        if source == to:
            raise ActionRefused(f"{what}: disc {disc} is on pin {to} already")
        target = self.pins[to]
        if target and target[-1] > disc:
            raise ActionRefused(f"{what}: disc {disc} is larger than disc {target[-1]} on "
                                f"pin {to}")
        self.pins[source].pop()
        target.append(disc)

    def draw(self, figure: object) -> None:
        """Three pins with their discs (wider for lower numbers)."""
        from matplotlib.patches import Rectangle

        axes = figure.add_subplot(1, 1, 1)
        count = sum(len(pin) for pin in self.pins)
        for number, pin in enumerate(self.pins):
            centre = number * 3 + 1.5
            axes.add_patch(Rectangle((centre - 0.05, 0), 0.1, count + 1, facecolor="#b08050"))
            for height, disc in enumerate(pin):
                width = 2.6 * (count - disc + 1) / count
                axes.add_patch(Rectangle((centre - width / 2, height), width, 0.9,
                                         facecolor="#4a78b0", edgecolor="black"))
                axes.text(centre, height + 0.45, str(disc), ha="center", va="center",
                          color="white", fontsize=8)
        axes.set_xlim(0, 9)
        axes.set_ylim(0, count + 1.5)
        axes.set_axis_off()
        axes.set_title(f"hanoi  round {self.clock.rounds}", fontsize=9)

    def snapshot(self, path: str) -> None:
        """Write a PNG of the pins now to ``path`` (atomically)."""
        _write_png(path, self.draw)
