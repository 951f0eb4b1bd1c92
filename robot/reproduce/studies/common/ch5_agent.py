"""What ``ch5-agent`` (and tests/robot/reproduce/test_transfer_agent.py) run: the garbage
disposal agent on a sequence of cans, each with the known objects learned before it, as
``goalagent run agents/garbage_disposal.mas2g --env-param learning=transfer`` runs it; and
Algorithm 6 alone on a can from the same known objects (its N, Table 5.4).

MuJoCo, the agents and the learners are imported inside the functions (``goalagent
reproduce --list`` imports every study and must stay light).
"""

from __future__ import annotations

import io
import shutil
from dataclasses import dataclass
from pathlib import Path

MAS = Path(__file__).resolve().parents[4] / "agents" / "garbage_disposal.mas2g"
ENVIRONMENT_ACTIONS = ("grasp(", "drop(ball)", "close_lid", "apply(", "learn(")
"""The agent's actions that reach the robot (the rest change its own mind or print)."""


@dataclass
class AgentRun:
    """What one run of the agent on one can did."""

    actions: list[tuple[int, str]]
    """Every action with the number of balls disposed of before it."""
    beliefs: dict[tuple[str, str], tuple[int, int, float]]
    """(part, action) -> afford/6's (Tot, Suc, Rel) at the end."""
    exploratory: int
    """The agent's own count of its learning's exploratory actions."""
    disposed: int
    trials: int
    terminated: bool
    cycles: int
    output: str

    @property
    def finished(self) -> bool:
        """Every ball asked for disposed of, and the agent stopped by itself."""
        return self.terminated and self.disposed == self.trials

    def learns(self) -> list[tuple[int, str]]:
        """The learn requests, each with the balls disposed of before it."""
        return [(trial, text) for trial, text in self.actions if text.startswith("learn(")]

    def robot_actions(self) -> int:
        """How many of the agent's actions reached the robot."""
        return sum(text.startswith(ENVIRONMENT_ACTIONS) for _, text in self.actions)

    def record(self) -> dict:
        """The run's numbers, as the ``ch5-agent`` study keeps them."""
        return {"finished": self.finished, "disposed": self.disposed,
                "exploratory_actions": self.exploratory, "robot_actions": self.robot_actions(),
                "total_actions": len(self.actions), "cycles": self.cycles,
                "learn_requests": len(self.learns()),
                "gave_up": "cannot_open(" in self.output}


def agent_run(can: str, folder: Path, *, seed: int = 0, trials: int = 5,
              learning: str = "transfer", perception: str = "truth",
              max_cycles: int = 400) -> AgentRun:
    """The agent on ``can`` (a shipped can's name or a can file) with the known objects and
    the learned models kept in ``folder`` (read, and written as it learns)."""
    from goalagent.kb.terms import Atom
    from goalagent.mas import MultiAgentSystem
    from robot.affordance import affordances

    params = {"can": can, "seed": seed, "trials": trials, "learning": Atom(learning),
              "perception": Atom(perception), "models": str(folder / "models.json"),
              "objects": str(folder / "objects.json")}
    output = io.StringIO()
    system = MultiAgentSystem.from_mas_file(MAS, env_params=params, seed=seed, output=output,
                                            warn=lambda message: None)
    actions: list[tuple[int, str]] = []

    def record(agent) -> None:
        done = int(agent.query("bel", "disposed(K)")[0]["K"])
        if agent.last_report is not None:
            actions.extend((done, text) for text in agent.last_report.actions)

    try:
        (agent,) = system.agents
        system.run(max_cycles=max_cycles, after_cycle=record)
        return AgentRun(
            actions, {(a.obj, a.act): (a.tot, a.suc, a.rel) for a in affordances(agent)},
            int(agent.query("bel", "exploratory_actions(T)")[0]["T"]),
            int(agent.query("bel", "disposed(K)")[0]["K"]), trials, agent.terminated,
            agent.cycle, output.getvalue())
    finally:
        system.close()


def algorithm6_n(can: str, objects: Path, scratch: Path, *, seed: int = 0,
                 perception: str = "truth") -> int:
    """N of Algorithm 6 alone on ``can`` from the known objects in ``objects`` (a copy of
    them, in ``scratch``, is what it adds the can to): what the ch5-transfer study measures."""
    from behaviours.learners.known_objects import KnownObjectDatabase
    from behaviours.part_learning import learn_by_transfer
    from behaviours.perception import make_perception
    from sim.canfile import find_can
    from sim.world import GarbageWorld

    spec = find_can(can)
    copy = scratch / f"algorithm6-{spec.name}.json"
    if objects.exists():
        shutil.copy(objects, copy)
    world = GarbageWorld(spec, seed=seed)
    try:
        return learn_by_transfer(world, make_perception(perception), KnownObjectDatabase(copy),
                                 random_state=seed).actions
    finally:
        world.close()
