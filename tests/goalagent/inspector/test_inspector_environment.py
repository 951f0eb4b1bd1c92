"""The mind inspector draws an environment that can draw itself (bw4t's map, the elevator's
shaft, hanoi's pins), again only when an agent has had a cycle; others get no panel."""

from __future__ import annotations

import io
from pathlib import Path

import cv2
import numpy as np
import pytest

from goalagent.extensions import RunContext
from goalagent.inspector import _panel_json
from goalagent.inspector.environment_panel import EnvironmentPanel
from goalagent.mas import MultiAgentSystem

EXAMPLES = Path(__file__).resolve().parents[3] / "agents" / "examples"


def _decoded(png: bytes) -> np.ndarray:
    return cv2.imdecode(np.frombuffer(png, np.uint8), cv2.IMREAD_COLOR)


def test_hanoi_is_drawn_and_drawn_again_after_a_move() -> None:
    system = MultiAgentSystem.for_agent_file(EXAMPLES / "hanoi_solver.goal", environment="hanoi",
                                             env_params={"discs": [0, 0, 0]},
                                             output=io.StringIO())
    try:
        panel, run = EnvironmentPanel(), RunContext(system, {}, None)  # type: ignore[arg-type]
        (agent,) = system.agents
        first = panel.view(run, agent)
        assert first is not None and first.title == "environment: Hanoi"
        picture = _decoded(first.png)
        assert picture.shape[:2] == (480, 480)
        assert panel.view(run, agent).png is first.png  # no cycle: not drawn again
        agent.step()  # one disc moves
        moved = panel.view(run, agent)
        assert moved.png != first.png
        assert np.abs(_decoded(moved.png).astype(int) - picture.astype(int)).sum() > 0
        assert _panel_json(moved)["image"].startswith("data:image/png;base64,")
    finally:
        system.close()


@pytest.mark.parametrize("mas", ["bw4t_team.mas2g", "elevator.mas2g"])
def test_bw4t_and_elevator_are_drawn(mas: str) -> None:
    system = MultiAgentSystem.from_mas_file(EXAMPLES / mas, output=io.StringIO())
    try:
        view = EnvironmentPanel().view(RunContext(system, {}, None),  # type: ignore[arg-type]
                                       system.agents[0])
        assert view is not None and _decoded(view.png).std() > 0
    finally:
        system.close()


def test_an_environment_that_cannot_draw_itself_has_no_panel() -> None:
    system = MultiAgentSystem.for_agent_file(EXAMPLES / "blocks_builder.goal",
                                             environment="blocksworld", output=io.StringIO())
    try:
        assert EnvironmentPanel().view(RunContext(system, {}, None),  # type: ignore[arg-type]
                                       system.agents[0]) is None
    finally:
        system.close()
