"""The environment's own drawing in the mind inspector: an environment that can draw itself
(a ``draw(figure)`` method taking a matplotlib Figure, as bw4t's map, the elevator's shaft and
hanoi's pins do) is shown as a picture under every agent, drawn again only after a cycle."""

from __future__ import annotations

import io
from typing import TYPE_CHECKING

from goalagent.extensions import InspectorPanel, PanelView, RunContext

if TYPE_CHECKING:
    from goalagent.agent import Agent


class EnvironmentPanel(InspectorPanel):
    """The world as its environment draws it; one picture per state of the run, shared by the
    agents (the key is every agent's cycle count)."""

    def __init__(self) -> None:
        self._drawn: tuple[tuple[int, ...], bytes] | None = None

    def view(self, run: RunContext, agent: Agent) -> PanelView | None:
        environment = run.system.environment
        draw = getattr(environment, "draw", None)
        if not callable(draw):
            return None
        state = tuple(other.cycle for other in run.system.agents)
        if self._drawn is None or self._drawn[0] != state:
            from matplotlib.figure import Figure  # only when a picture is asked for

            figure = Figure(figsize=(6, 6), dpi=80)
            draw(figure)
            image = io.BytesIO()
            figure.savefig(image, format="png")
            self._drawn = (state, image.getvalue())
        return PanelView(f"environment: {type(environment).__name__}", png=self._drawn[1])
