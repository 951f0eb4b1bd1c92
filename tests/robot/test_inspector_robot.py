"""The robot's mind-inspector panels, reached through the extension seam: the afford/6 table
with its reliability plot, and the garbage environment's camera frame with perception
boxes (a real MuJoCo world, rendered and perceived)."""

from __future__ import annotations

import io
from pathlib import Path

import cv2
import numpy as np

from goalagent.extensions import RunContext, installed_extensions
from goalagent.inspector import _panel_json
from goalagent.mas import MultiAgentSystem

ROOT = Path(__file__).resolve().parents[2]


def robot_panels():
    (robot,) = [e for e in installed_extensions() if e.name == "robot"]
    return {make.__name__: make() for make in robot.inspector_panels}


def _decoded(png: bytes) -> np.ndarray:
    return cv2.imdecode(np.frombuffer(png, np.uint8), cv2.IMREAD_COLOR)


def test_afford_panel_shows_the_table_and_a_plot_drawn_again_only_on_change(tmp_path: Path):
    program = tmp_path / "afford.goal"
    program.write_text("""
        init module { beliefs { afford(lid, push, opened, 1, 1, 1.0). n(0). } }
        main module { program {
            if bel(n(0)) then delete(n(0)) + insert(n(1)).
            if bel(n(1)) then delete(afford(lid, push, opened, 1, 1, 1.0)) + delete(n(1))
                + insert(afford(lid, push, opened, 2, 1, 0.55)) + insert(n(2)).
        } }
    """)
    system = MultiAgentSystem.for_agent_file(program, output=io.StringIO())
    try:
        panel = robot_panels()["AffordancePanel"]
        run = RunContext(system, {}, None)  # type: ignore[arg-type]
        (agent,) = system.agents
        first = panel.view(run, agent)
        assert first is not None and first.rows == (("lid", "push", "opened", "1", "1",
                                                     "1.000"),)
        assert _decoded(first.png).shape[0] > 100
        agent.step()
        assert panel.view(run, agent).png is first.png  # nothing changed: the same plot
        agent.step()
        changed = panel.view(run, agent)
        assert changed.rows[0][-1] == "0.550" and changed.png != first.png
        assert _panel_json(changed)["image"].startswith("data:image/png;base64,")
    finally:
        system.close()


def test_camera_panel_shows_the_frame_with_the_parts_the_robot_perceives():
    system = MultiAgentSystem.from_mas_file(ROOT / "agents" / "garbage_disposal.mas2g",
                                            output=io.StringIO())
    try:
        panels = robot_panels()
        run = RunContext(system, {}, None)  # type: ignore[arg-type]
        (agent,) = system.agents
        agent.step()
        view = panels["CameraPanel"].view(run, agent)
        assert view is not None and "lid" in view.caption and "opening" in view.caption
        image = _decoded(view.png)
        assert image.shape[:2] == (480, 640)  # the 320x240 frame drawn twice its size
        table = panels["AffordancePanel"].view(run, agent)
        assert table is not None and {row[0] for row in table.rows} <= {"lid", "handle"}
    finally:
        system.close()


def test_camera_panel_is_silent_on_other_environments(tmp_path: Path):
    system = MultiAgentSystem.for_agent_file(ROOT / "agents" / "examples" / "hello_world.goal",
                                             output=io.StringIO())
    try:
        run = RunContext(system, {}, None)  # type: ignore[arg-type]
        assert robot_panels()["CameraPanel"].view(run, system.agents[0]) is None
    finally:
        system.close()
