"""The ``navigation`` EIS environment: thesis §3.5's navigation task (Fig. 3.3) for an agent.

The robot walks (``walk(left|ahead|right)``) and pushes (``push``) on the table, or runs a whole
XCS trial (``run_trial(explore|exploit)``); it perceives the 8-bit state of eq. 3.12, the object
in front, the learned movability and how far the destination is. The boxes are exchanged from
trial ``exchange_after`` + 1 on (§3.5.7), or from the start with ``exchanged=true``. See
``robot/envs/README.md`` and ``robot/envs/xcs_task.py`` for what all three task environments
share.
"""

from __future__ import annotations

from typing import ClassVar

from behaviours.object_state import make_object_perception
from behaviours.xcs_tasks import NavigationTask, Task
from goalagent.eis.exceptions import ActionRefused
from goalagent.eis.pyenv import PerceptLike, action
from robot.envs.xcs_task import XcsTaskEnvironment
from sim.navigation import NavigationWorld


class NavigationEnvironment(XcsTaskEnvironment):
    """The robot, the movable and the fixed box, and the destination line."""

    name = "navigation"
    parameters: ClassVar[dict[str, object]] = {
        **XcsTaskEnvironment.common_parameters, "exchange_after": int, "exchanged": bool}

    def task_params(self, params: dict[str, object]) -> None:
        """``exchange_after`` trials before the boxes swap (0 with ``exchanged=true``)."""
        self.exchange_after = 0 if params.get("exchanged") else int(
            params.get("exchange_after", 10))
        if self.exchange_after < 0:
            self._bad(f"exchange_after must be 0 or more, got {self.exchange_after}")

    def make_task(self) -> Task:
        """The world and the task, perceived in the chosen mode."""
        self.world = NavigationWorld()
        return NavigationTask(self.world, make_object_perception(self.mode, "navigation"),
                              exchange_after=self.exchange_after)

    def close_world(self) -> None:
        """Free the renderer."""
        self.world.close()

    def task_percepts(self) -> list[PerceptLike]:
        """Object in front, affordances, distance to go, and the trial's end if it came."""
        result = self.object_percepts()
        result.append(("distance", round(self.world.distance_to_destination(), 3)))
        if self.world.exchanged:
            result.append("exchanged")
        if self.world.fallen:
            result.append("fallen")
        if self.success:
            result.append("at_destination")
        return result

    @action("walk")
    def walk(self, entity: str, direction: str) -> None:
        """Walk d_walk = 0.15 m left, ahead or right (actions 000, 001, 011)."""
        if direction not in ("left", "ahead", "right"):
            raise ActionRefused(f"walk({direction}): the robot walks left, ahead or right")
        self.primitive(f"walk_{direction}")

    @action("push")
    def push(self, entity: str) -> None:
        """Push d_walk ahead, leaning into whatever is in front (action 010)."""
        self.primitive("push_ahead")
