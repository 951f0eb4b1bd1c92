"""The ``stacking`` EIS environment: thesis §3.5's stacking task (Fig. 3.4) for an agent.

The robot asks for an object (``choose(box|foam)``, actions 110 and 111) and pushes it off the
table onto the stack in a pose (``push(stand|squat)``, actions 100 and 101), or runs a whole XCS
trial (``run_trial(explore|exploit)``); it perceives the 8-bit state of eq. 3.12, the object in
front, the learned movability and the stack's height. See ``robot/envs/README.md``.
"""

from __future__ import annotations

from behaviours.object_state import make_object_perception
from behaviours.xcs_tasks import StackingTask, Task
from goalagent.eis.exceptions import ActionRefused
from goalagent.eis.pyenv import PerceptLike, action
from robot.envs.xcs_task import XcsTaskEnvironment
from sim.stacking import KINDS, StackingWorld


class StackingEnvironment(XcsTaskEnvironment):
    """The robot at the table edge, a high box, low foams and the lift beside the table."""

    name = "stacking"
    parameters = dict(XcsTaskEnvironment.common_parameters)

    def make_task(self) -> Task:
        """The world and the task, perceived in the chosen mode."""
        self.world = StackingWorld()
        return StackingTask(self.world, make_object_perception(self.mode, "stacking"))

    def close_world(self) -> None:
        """Free the renderer."""
        self.world.close()

    def task_percepts(self) -> list[PerceptLike]:
        """Object in front, affordances, the stack's height and whether it is high enough."""
        state = self.world.state()
        result = self.object_percepts()
        result.append(("stack_height", round(state.stack_height, 3)))
        if state.stacked:
            result.append("stacked")
        return result

    @action("choose")
    def choose(self, entity: str, kind: str) -> None:
        """Ask the operator for the high box (object 1) or a low foam (object 2)."""
        if kind not in KINDS:
            raise ActionRefused(f"choose({kind}): the operator has a box and foams")
        self.primitive(f"choose_{kind}")

    @action("push")
    def push(self, entity: str, pose: str) -> None:
        """Push the object in front standing or squatting."""
        if pose not in ("stand", "squat"):
            raise ActionRefused(f"push({pose}): the robot pushes standing or squatting")
        self.primitive(f"push_{pose}")
