"""Following an agent's afford/6 facts cheaply: a watch reports only what changed, and the
end-of-run report prints a bounded table and a legible plot however many there are."""

from __future__ import annotations

import io
import re
from pathlib import Path

from rich.console import Console

from goalagent.agent import Agent
from goalagent.extensions import RunContext
from goalagent.kb.terms import Atom, Struct
from robot.afford_report import MAX_ROWS, AffordanceReport
from robot.affordance import MAX_SERIES, ReliabilityHistory

AGENT = "main module [exit=always] { program { if true then print(ok). } }\n"


def _afford(obj: str, tot: int, suc: int) -> str:
    return f"afford({obj}, push, opened, {tot}, {suc}, {suc / tot if tot else 0.1})"


def test_a_watch_sees_everything_first_then_only_what_changed():
    agent = Agent.from_string(AGENT, "w.goal")
    try:
        agent.ms.insert(_afford("lid", 1, 1))
        agent.ms.insert(_afford("handle", 2, 0))
        watch = agent.ms.watch("afford", 6)
        gained, lost = watch.changes()
        assert sorted(str(fact.args[0]) for fact in gained) == ["handle", "lid"] and lost == []
        assert watch.changes() == ([], [])
        agent.ms.delete(_afford("lid", 1, 1))
        agent.ms.insert(_afford("lid", 2, 2))
        gained, lost = watch.changes()
        assert gained == [Struct("afford", (Atom("lid"), Atom("push"), Atom("opened"), 2, 2,
                                            1.0))]
        assert [fact.args[3] for fact in lost] == [1]
        watch.close()
    finally:
        agent.close()


class _System:
    def __init__(self, agents: list[Agent]) -> None:
        self.agents = agents


def test_the_report_of_thousands_of_affordances_is_bounded(tmp_path: Path):
    agent = Agent.from_string(AGENT, "many.goal")
    try:
        for index in range(400):
            agent.ms.insert(_afford(f"o{index}", 3, 1))
        stream = io.StringIO()
        run = RunContext(_System([agent]), {"plot": tmp_path / "p.png"},  # type: ignore
                         Console(file=stream, width=120))
        report = AffordanceReport()
        report.start(run)
        for step in range(1, 4):  # three of them change, one of them twice
            agent.ms.delete(_afford(f"o{step}", 3, 1))
            agent.ms.insert(_afford(f"o{step}", 4, 2))
            if step == 2:
                agent.ms.delete(_afford("o2", 4, 2))
                agent.ms.insert(_afford("o2", 5, 4))
            report.after_cycle(run, agent)
        history = report.histories["many"]
        assert len(history.points) == 400
        shown = dict(history.shown())
        assert len(shown) == MAX_SERIES
        assert shown[("o2", "push", "opened")] == [(0, 1 / 3), (0, 0.8)]
        report.finish(run)
        text = stream.getvalue()
        assert len(re.findall(r"^│ o\d+ ", text, re.M)) == MAX_ROWS
        assert f"the first {MAX_ROWS} of 400" in text
        assert (tmp_path / "p.png").stat().st_size > 0
    finally:
        agent.close()


def test_a_few_affordances_are_all_shown():
    history = ReliabilityHistory()
    history.points = {("lid", "push", "opened"): [(0, 0.1)], ("handle", "pull", "opened"): []}
    assert [key for key, _ in history.shown()] == [("handle", "pull", "opened"),
                                                  ("lid", "push", "opened")]
