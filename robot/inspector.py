"""The robot's panels in the mind inspector (``goalagent run --inspect``), declared in
``robot/extension.py``: each agent's ``afford/6`` table with its reliability plot, and on
the garbage environment the head camera's latest frame with the perception boxes.

They are asked for on the thread running the agents, after cycles; heavy parts (matplotlib,
MuJoCo rendering, OpenCV) are imported only then, so the extension module stays light.
"""

from __future__ import annotations

import io
from typing import TYPE_CHECKING

from goalagent.extensions import InspectorPanel, PanelView, RunContext
from robot.affordance import ReliabilityHistory, affordances

if TYPE_CHECKING:
    from goalagent.agent import Agent


class AffordancePanel(InspectorPanel):
    """The afford/6 beliefs as a table and their reliabilities over the actions taken (the
    plot is drawn again only when a reliability changed)."""

    def __init__(self) -> None:
        self._histories: dict[str, ReliabilityHistory] = {}
        self._plots: dict[str, tuple[int, bytes]] = {}

    def view(self, run: RunContext, agent: Agent) -> PanelView | None:
        rows = affordances(agent)
        if not rows:
            return None
        history = self._histories.setdefault(agent.name, ReliabilityHistory())
        history.record(agent)
        points = sum(len(series) for series in history.points.values())
        cached = self._plots.get(agent.name)
        if cached is None or cached[0] != points:
            image = io.BytesIO()
            history.plot(image, f"Affordance reliabilities of {agent.name}")
            cached = self._plots[agent.name] = (points, image.getvalue())
        return PanelView(
            "afford/6", ("Obj", "Act", "Eff", "Tot", "Suc", "Rel"),
            tuple((row.obj, row.act, row.eff, str(row.tot), str(row.suc), f"{row.rel:.3f}")
                  for row in rows), png=cached[1])


class CameraPanel(InspectorPanel):
    """The garbage environment's head-camera frame as the robot perceives it now, with each
    part boxed (as ``goalagent snapshot`` draws it)."""

    def view(self, run: RunContext, agent: Agent) -> PanelView | None:
        environment = run.system.environment
        if type(environment).__module__ != "robot.envs.garbage":
            return None
        import cv2

        from behaviours.perception import observe_image
        from robot.snapshot import annotate

        image = environment.world.render("head")  # type: ignore[union-attr]
        observation = observe_image(image)
        ok, png = cv2.imencode(".png", cv2.cvtColor(annotate(image, observation),
                                                    cv2.COLOR_RGB2BGR))
        if not ok:
            return None
        parts = ", ".join(sorted(observation.parts)) or "none"
        return PanelView("head camera", png=png.tobytes(),
                         caption=f"parts seen: {parts}; opening {observation.opening:.3f} m")
