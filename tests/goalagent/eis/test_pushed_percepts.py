"""Percepts an environment pushes (EIS agent listeners) reach the agent's next cycle once."""

from __future__ import annotations

import io
from pathlib import Path

from goalagent.eis import PythonEnvironment, action
from goalagent.mas import MultiAgentSystem


class Doorbell(PythonEnvironment):
    """Rings (a pushed percept) when asked to; its state percept says how often."""

    name = "doorbell"
    entity_names = ("door",)

    def on_init(self, params: dict[str, object]) -> None:
        self.rings = 0

    def percepts(self, entity: str):
        return [("rings", self.rings)]

    @action("press")
    def press(self, entity: str) -> None:
        self.rings += 1
        self.push_percept(("ding", self.rings))


def test_a_pushed_percept_is_seen_in_the_next_cycle_only(tmp_path: Path) -> None:
    program = tmp_path / "visitor.goal"
    program.write_text("""
        init module { actionspec { press { pre { true } post { true } } } }
        main module { program [order=linearall] {
            if percept(ding(N)) then print(heard(N)).
            if bel(percept(rings(R)), R < 2) then press.
        } }
    """)
    system = MultiAgentSystem.for_agent_file(
        program, environment=f"{__name__}:Doorbell", output=io.StringIO(),
        warn=lambda message: None)
    system.run(max_cycles=4)
    assert system.output.getvalue().split() == ["heard(1)", "heard(2)"]
    system.close()
