"""learn(..., transfer) from the garbage agent (thesis §6.4.2 Experiment 1 with chapter 5's
transfer): after o1 is known, o3 is learned with a single exploratory action."""

from __future__ import annotations

import io
from pathlib import Path

import pytest

from behaviours.learners.known_objects import KnownObjectDatabase
from goalagent.eis import ActException, ManagementException, load_environment
from goalagent.eis.terms import Action
from goalagent.kb.terms import Atom
from goalagent.mas import MultiAgentSystem
from robot.affordance import affordances

MAS = Path(__file__).resolve().parents[1] / "agents" / "garbage_disposal.mas2g"


def run(can: str, tmp_path: Path) -> tuple[list[str], dict[tuple[str, str], tuple]]:
    """One trial of the agent on ``can`` in transfer mode; its actions and afford beliefs."""
    params = {"can": Atom(can), "seed": 0, "trials": 1, "learning": Atom("transfer"),
              "models": str(tmp_path / "models.json"),
              "objects": str(tmp_path / "objects.json")}
    system = MultiAgentSystem.from_mas_file(MAS, env_params=params, seed=0,
                                            output=io.StringIO(), warn=lambda message: None)
    actions: list[str] = []
    try:
        (agent,) = system.agents
        system.run(max_cycles=100, after_cycle=lambda a: actions.extend(
            a.last_report.actions if a.last_report else ()))
        assert agent.terminated and agent.query("bel", "disposed(1)")
        beliefs = {(a.obj, a.act): (a.tot, a.suc, a.rel) for a in affordances(agent)}
    finally:
        system.close()
    return actions, beliefs


def test_experiment_1_on_o3_after_o1_needs_one_exploratory_action(tmp_path: Path):
    first, _ = run("o1", tmp_path)
    assert len([a for a in first if a.startswith("learn(")]) == 1  # one learn: Algorithm 4
    database = KnownObjectDatabase(tmp_path / "objects.json")
    assert database.names() == ["o1"] and database.get("o1").source is None
    assert database.get("o1").n_actions == 39

    actions, beliefs = run("o3", tmp_path)
    learns = [a for a in actions if a.startswith("learn(")]
    assert len(learns) == 1 and learns[0].endswith(",opened,transfer)")
    known = KnownObjectDatabase(tmp_path / "objects.json").get("o3")
    assert (known.source, known.n_actions) == ("o1", 1)  # a single exploratory action
    assert (known.functional.part, known.functional.action) == ("lid", "extend_arm")
    assert beliefs[("lid", "extend_arm")] == (2, 2, 1.0)  # learned (1, 1, 1), then used once
    assert actions.index("apply(lid,extend_arm)") > actions.index(learns[0])


def test_the_whole_object_form_and_its_refusals(tmp_path: Path):
    env = load_environment("garbage")()
    env.init({"can": "o5", "objects": str(tmp_path / "objects.json"),
              "models": str(tmp_path / "models.json"), "learning": "transfer"})
    env.start()
    env.register_agent("robot")
    env.associate_entity("robot", "robot")
    env.perform_action("robot", Action.of("learn", "opened", "transfer"))
    seen = {str(p) for p in env.get_all_percepts("robot")["robot"]}
    assert "learning_mode(transfer)" in seen
    assert "afford(handle,contract_arm,opened,1,1,1)" in seen
    assert any(p.startswith("model(handle,contract_arm,") for p in seen)
    assert "opened" not in seen  # the can is left as learning found it
    for args, message in ((("opened", "random"), "needs mode 'transfer'"),
                          (("lid", "push", "opened", "transfer"), "unknown action type"),
                          (("lid", "extend_arm", "moved", "transfer"), "only the effect")):
        with pytest.raises(ActException, match=message):
            env.perform_action("robot", Action.of("learn", *args))
    env.kill()
    with pytest.raises(ManagementException, match="unknown learning mode 'guess'"):
        load_environment("garbage")().init({"learning": "guess"})
    (tmp_path / "bad.json").write_text("{")
    with pytest.raises(ManagementException, match=r"bad.json:1:2: not JSON"):
        load_environment("garbage")().init({"objects": str(tmp_path / "bad.json")})
