"""Multi-agent systems: launch policies, scheduling, failures and isolation."""

from __future__ import annotations

import io
import time
from pathlib import Path

from goalagent.mas import MultiAgentSystem
from goalagent.parser import parse_agent, parse_mas_file

COUNTER = """
init module { beliefs { n(0). } }
main module { program {
    if bel(me(Me), n(N), N < 3, M is N + 1) then delete(n(N)) + insert(n(M)) + print(Me-M).
} }
"""


def system(tmp_path: Path, mas: str, **agents: str) -> MultiAgentSystem:
    for name, text in agents.items():
        (tmp_path / f"{name}.goal").write_text(text)
    (tmp_path / "sys.mas2g").write_text(mas)
    return MultiAgentSystem.from_mas_file(tmp_path / "sys.mas2g", output=io.StringIO(),
                                          warn=lambda message: None)


def test_agents_take_turns_one_cycle_each(tmp_path: Path) -> None:
    mas = system(tmp_path, """
        agentfiles { "counter.goal" [name = c]. }
        launchpolicy { launch a : c. launch b : c. }
    """, counter=COUNTER)
    mas.run(max_cycles=5)
    assert mas.output.getvalue().split() == ["a-1", "b-1", "a-2", "b-2", "a-3", "b-3"]


def test_number_launches_numbered_copies(tmp_path: Path) -> None:
    mas = system(tmp_path, """
        agentfiles { "counter.goal" [name = c, number = 3]. }
        launchpolicy { launch worker : c. }
    """, counter=COUNTER)
    assert [agent.name for agent in mas.agents] == ["worker1", "worker2", "worker3"]
    assert {str(a["A"]) for a in mas.agents[0].query("bel", "agent(A)")} == {
        "worker1", "worker2", "worker3"}


def test_entity_launch_rule_respects_type_and_max(tmp_path: Path) -> None:
    mas = system(tmp_path, """
        environment { env = "blocksworld". init = [robots = 3, blocks = 2, seed = 1]. }
        agentfiles { "counter.goal" [name = c]. }
        launchpolicy { when [type = gripper, max = 2]@env do launch bot : c. }
    """, counter=COUNTER)
    assert [agent.name for agent in mas.agents] == ["bot", "bot2"]
    env = mas.environment
    assert [env.associated_entities(agent.name) for agent in mas.agents] == [
        ["gripper1"], ["gripper2"]]
    mas.close()


def test_star_names_the_agent_after_its_entity(tmp_path: Path) -> None:
    mas = system(tmp_path, """
        environment { env = "blocksworld". init = [robots = 2, blocks = 2]. }
        agentfiles { "counter.goal" [name = c]. }
        launchpolicy { when entity@env do launch * : c. }
    """, counter=COUNTER)
    assert [agent.name for agent in mas.agents] == ["gripper1", "gripper2"]
    mas.close()


def test_a_failing_agent_is_reported_and_the_others_go_on(tmp_path: Path) -> None:
    broken = """
        main module { program { if true then insert(X). } }
    """
    mas = system(tmp_path, """
        agentfiles { "counter.goal" [name = c]. "broken.goal" [name = b]. }
        launchpolicy { launch good : c. launch bad : b. }
    """, counter=COUNTER, broken=broken)
    summaries = {s.name: s for s in mas.run(max_cycles=4)}
    assert summaries["good"].actions == 9  # delete + insert + print, three times
    assert mas.output.getvalue().split() == ["good-1", "good-2", "good-3"]
    assert summaries["bad"].status in ("failed", "stopped at the cycle limit")


def test_agents_cannot_see_each_others_beliefs(tmp_path: Path) -> None:
    secret = """
        init module { beliefs { secret(42). } }
        main module { program { if true then insert(mine). } }
    """
    spy = """
        main module { program [order=linearall] {
            if bel(secret(X)) then print(X).
            if true then insert(spying).
        } }
    """
    mas = system(tmp_path, """
        agentfiles { "secret.goal" [name = s]. "spy.goal" [name = p]. }
        launchpolicy { launch holder : s. launch spy : p. }
    """, secret=secret, spy=spy)
    mas.run(max_cycles=2)
    holder, spy_agent = mas.agents
    assert mas.output.getvalue() == ""
    assert "mine" not in spy_agent.beliefs() and "spying" not in holder.beliefs()
    assert "mine" in holder.beliefs() and "spying" in spy_agent.beliefs()
    assert holder.query("bel", "secret(X)") == [{"X": 42}]


def test_launch_of_an_unknown_agent_file_is_a_warning_and_launches_nothing(tmp_path: Path):
    # GOAL's validator: AGENTFILE_NONEXISTANT_REFERENCE is a warning
    mas = system(tmp_path, """
        agentfiles { "counter.goal" [name = c]. }
        launchpolicy {
            launch x : nobody.
            launch y : c.
        }
    """, counter=COUNTER)
    try:
        assert [agent.name for agent in mas.agents] == ["y"]
    finally:
        mas.close()
    warnings = parse_mas_file(tmp_path / "sys.mas2g").warnings
    assert len(warnings) == 1 and "launch refers to unknown agent 'nobody'" in warnings[0]


def test_every_agent_sees_every_agent_also_those_launched_later() -> None:
    mas = MultiAgentSystem(output=io.StringIO(), warn=lambda message: None)
    program = parse_agent(COUNTER, "counter.goal")
    first = mas.launch("first", program)
    assert first.query("bel", "agent(A)") == [{"A": "first"}]
    mas.launch("second", program)
    for agent in mas.agents:
        assert [str(a["A"]) for a in agent.query("bel", "agent(A)")] == ["first", "second"]
        assert agent.query("bel", "me(M)") == [{"M": agent.name}]
    mas.close()


def test_launching_many_agents_is_linear() -> None:
    """The agent list is shared, not copied into every agent on each launch (that took 7.6 s
    for 200 agents): 400 launches stay well under a second each way."""
    mas = MultiAgentSystem(output=io.StringIO(), warn=lambda message: None)
    program = parse_agent(COUNTER, "counter.goal")
    start = time.perf_counter()
    for index in range(400):
        mas.launch(f"a{index}", program)
    elapsed = time.perf_counter() - start
    assert len(mas.agents[0].query("bel", "agent(A)")) == 400
    assert len(mas.agents[-1].query("bel", "agent(A)")) == 400
    mas.close()
    assert elapsed < 5.0, f"launching 400 agents took {elapsed:.1f} s"


def test_a_message_to_one_agent_reaches_only_it_among_many(tmp_path: Path) -> None:
    mas = system(tmp_path, """
        agentfiles { "pinger.goal" [name = p, number = 5]. }
        launchpolicy { launch p : p. }
    """, pinger="""
init module { beliefs { sent_once(no). } }
main module { program {
    if bel(me(p1), sent_once(no)) then p3.send(ping) + delete(sent_once(no)).
} }
""")
    mas.run(max_cycles=2)
    heard = {agent.name: agent.query("bel", "received(S, ping)") for agent in mas.agents}
    assert heard == {"p1": [], "p2": [], "p3": [{"S": "p1"}], "p4": [], "p5": []}
