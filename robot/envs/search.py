"""The ``search`` EIS environment: Appendix A's head-camera search (Fig. 7.2) for an agent.

The robot turns its head one step (``look(up|right|down|left)``, actions 00, 01, 10, 11) or runs
a whole XCS trial (``run_trial(explore|exploit)``, with App. A's consistent-action exploration);
it perceives the 9-bit blob grid as its state, its head angles, whether the centre of the image
sees the target, and how often the operator has moved the target (after ``move_after`` trials,
from up-left to the right, as in App. A). See ``robot/envs/README.md``.
"""

from __future__ import annotations

from typing import ClassVar

from behaviours.blob_grid import centre_seen, make_grid_perception
from behaviours.xcs_tasks import SearchTask, Task
from behaviours.xcs_trials import SEARCH_STEPS
from goalagent.eis.exceptions import ActionRefused
from goalagent.eis.pyenv import PerceptLike, action
from robot.envs.xcs_task import XcsTaskEnvironment
from sim.search import SearchWorld


class SearchEnvironment(XcsTaskEnvironment):
    """The robot's pan-tilt head camera and the red target."""

    name = "search"
    parameters: ClassVar[dict[str, object]] = {
        "perception": str, "seed": int, "rules": str, "n_step": int, "move_after": int}
    default_method = "standard_xcs"
    default_n_step = SEARCH_STEPS
    xcs_options: ClassVar[dict[str, bool]] = {"consistent_actions": True}

    def task_params(self, params: dict[str, object]) -> None:
        """``move_after`` trials before the operator moves the target."""
        self.move_after = int(params.get("move_after", 10))
        if self.move_after < 0:
            self._bad(f"move_after must be 0 or more, got {self.move_after}")

    def make_task(self) -> Task:
        """The world and the task, perceived in the chosen mode."""
        self.world = SearchWorld()
        return SearchTask(self.world, make_grid_perception(self.mode),
                          move_after=self.move_after)

    def close_world(self) -> None:
        """Free the renderer."""
        self.world.close()

    def task_percepts(self) -> list[PerceptLike]:
        """Head angles, whether the target is in the centre, how often it was moved."""
        yaw, pitch = self.world.setpoint
        result: list[PerceptLike] = [("head", round(yaw, 2), round(pitch, 2)),
                                     ("moves", int(self.trial >= self.move_after))]
        if centre_seen(self.view.bits):
            result.append("found")
        return result

    @action("look")
    def look(self, entity: str, direction: str) -> None:
        """Turn the head 0.1 rad (past the movement boundary it resets to rest)."""
        if direction not in ("up", "right", "down", "left"):
            raise ActionRefused(f"look({direction}): the head looks up, right, down or left")
        self.primitive(f"look_{direction}")
