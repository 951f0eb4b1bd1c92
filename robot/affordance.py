"""Affordance knowledge seen from Python: afford/6 rows, their history and its plot.

The reasoning itself (eq. 6.3, rules 6.2/6.4/6.12) is Prolog, in the library
``robot/affordance.pl`` (which agents ``#import``, see ``robot/extension.py``) and the agent
program; this module only reads an agent's
``afford/6`` beliefs, keeps their history for a plot, and declares ``afford/6`` to
``--save-beliefs`` (``AFFORD``), which writes them as Prolog facts.
"""

from __future__ import annotations

import io
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, BinaryIO

from goalagent.extensions import SavedPredicate
from goalagent.kb.facts import FactWatch
from goalagent.kb.terms import Atom, Term
from ondisk import write_atomically

if TYPE_CHECKING:
    from goalagent.agent import Agent

AFFORD_QUERY = "afford(Obj, Act, Eff, Tot, Suc, Rel)"


def _canonical_afford(args: tuple[Term, ...]) -> tuple[Term, ...]:
    """Atoms, two counts and a float reliability (``Rel`` = 1 is saved as ``1.0``)."""
    obj, act, eff, tot, suc, rel = args
    return (Atom(str(obj)), Atom(str(act)), Atom(str(eff)), int(tot), int(suc), float(rel))


AFFORD_CHECKS = (
    ("atom(Obj)", "Obj must be an atom"),
    ("atom(Act)", "Act must be an atom"),
    ("atom(Eff)", "Eff must be an atom"),
    ("integer(Tot), Tot >= 0", "Tot must be a non-negative integer"),
    ("integer(Suc), Suc >= 0", "Suc must be a non-negative integer"),
    ("Suc =< Tot", "Suc must not exceed Tot"),
    ("number(Rel), Rel >= 0, Rel =< 1", "the reliability Rel must be a number in [0, 1]"),
)
"""What an ``afford/6`` fact must be (eq. 6.1) for ``--load-beliefs`` to accept it."""

AFFORD = SavedPredicate("afford", 6, "afford(Obj, Act, Eff, Tot, Suc, Rel) beliefs",
                        canonical=_canonical_afford, template=AFFORD_QUERY,
                        checks=AFFORD_CHECKS)
"""``afford/6`` as ``goalagent run --save-beliefs`` writes it and ``--load-beliefs`` checks
it."""


@dataclass(frozen=True)
class Affordance:
    """One ``afford(Obj, Act, Eff, Tot, Suc, Rel)`` belief (eq. 6.1)."""

    obj: str
    act: str
    eff: str
    tot: int
    suc: int
    rel: float

    @property
    def key(self) -> tuple[str, str, str]:
        """What the affordance is about: (Obj, Act, Eff)."""
        return (self.obj, self.act, self.eff)


    @classmethod
    def from_term(cls, fact: Term) -> Affordance:
        """The affordance of an ``afford/6`` fact (a ``Struct``)."""
        obj, act, eff, tot, suc, rel = fact.args  # type: ignore[union-attr]
        return cls(str(obj), str(act), str(eff), int(tot), int(suc), float(rel))


def affordances(agent: Agent, limit: int | None = None) -> list[Affordance]:
    """The agent's current ``afford/6`` beliefs, in belief-base order (the first ``limit``)."""
    if not agent.query("bel", "current_predicate(afford/6)"):
        return []
    return [
        Affordance(str(a["Obj"]), str(a["Act"]), str(a["Eff"]), int(a["Tot"]), int(a["Suc"]),
                   float(a["Rel"]))
        for a in agent.ms.query("bel", AFFORD_QUERY, limit=limit)
    ]


def count_affordances(agent: Agent) -> int:
    """How many ``afford/6`` beliefs the agent has (one query, nothing converted)."""
    answers = agent.query("bel", "aggregate_all(count, clause(afford(_, _, _, _, _, _), true),"
                                 " N)")
    return int(answers[0]["N"]) if answers else 0  # type: ignore[arg-type]


MAX_SERIES = 20
"""The most affordances one reliability plot shows (those whose reliability changed most)."""


@dataclass
class ReliabilityHistory:
    """Reliability of each affordance after every cycle, against the actions taken so far.

    Only the ``afford/6`` facts that changed since the last record are read from the agent
    (a watch compares them in Prolog), so following 100,000 affordances costs little."""

    points: dict[tuple[str, str, str], list[tuple[int, float]]] = field(default_factory=dict)
    last_action: int = 0
    _watch: FactWatch | None = None

    def record(self, agent: Agent) -> None:
        """Note every reliability that changed (or appeared) since the last record."""
        self.last_action = agent.total_actions
        if self._watch is None:
            self._watch = agent.ms.watch("afford", 6)
        gained, _ = self._watch.changes()
        for fact in gained:
            affordance = Affordance.from_term(fact)
            series = self.points.setdefault(affordance.key, [])
            if not series or series[-1][1] != affordance.rel:
                series.append((agent.total_actions, affordance.rel))

    def close(self) -> None:
        """Stops following the agent (frees what the watch kept)."""
        if self._watch is not None:
            self._watch.close()
            self._watch = None

    def shown(self) -> list[tuple[tuple[str, str, str], list[tuple[int, float]]]]:
        """The series a plot shows, by key: all, or the MAX_SERIES that changed most."""
        items = sorted(self.points.items())
        if len(items) <= MAX_SERIES:
            return items
        return sorted(sorted(items, key=lambda item: -len(item[1]))[:MAX_SERIES])

    def plot(self, path: Path | BinaryIO, title: str, tau: float = 0.6) -> None:
        """A step plot of every affordance's reliability over the actions taken (PNG, to a
        file or a binary stream)."""
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        figure, axes = plt.subplots(figsize=(9, 5))
        colours = plt.get_cmap("tab20").colors
        shown = self.shown()
        if len(shown) < len(self.points):
            title += f" ({len(shown)} of {len(self.points)}: those that changed most)"
        for index, ((obj, act, eff), series) in enumerate(shown):
            xs = [x for x, _ in series] + [self.last_action]
            ys = [y for _, y in series] + [series[-1][1]]
            axes.step(xs, ys, where="post", color=colours[index % len(colours)],
                      label=f"{obj} {act} ({eff})")
            axes.plot(xs[:-1], ys[:-1], "o", markersize=3,
                      color=colours[index % len(colours)])
        axes.axhline(tau, color="grey", linestyle="--", linewidth=1, label=f"tau = {tau}")
        axes.set_xlabel("actions taken")
        axes.set_ylabel("reliability Rel")
        axes.set_ylim(-0.05, 1.05)
        axes.set_title(title)
        axes.legend(fontsize=7, loc="center left", bbox_to_anchor=(1.0, 0.5))
        figure.tight_layout()
        if isinstance(path, Path):  # a file is put in place whole, never half drawn
            picture = io.BytesIO()
            figure.savefig(picture, dpi=110, format="png")
            write_atomically(path, picture.getvalue())
        else:
            figure.savefig(path, dpi=110, format="png")
        plt.close(figure)
