"""How long a received message stays: GOAL 6+ (an agent definition's module files) keeps it
for the one cycle after it arrives -- GOAL's MentalState says "a message base is cleared
after every decision cycle" -- while a GOAL 4/5 .goal file keeps ``received/2`` until the
agent deletes it (those programs delete their messages themselves)."""

from __future__ import annotations

import io
import textwrap
from pathlib import Path

from goalagent.kb.terms import Struct
from goalagent.mas import MultiAgentSystem

TELLER = """
    module teller {
        if bel(not(told)) then allother.send:(hello) + insert(told).
    }
"""
LISTENER = """
    use listener as beliefs.
    module listener {
        if (S).sent:(hello), bel(seen(N), M is N + 1) then delete(seen(N)) + insert(seen(M)).
    }
"""
SYSTEM = """
    define teller as agent { use teller as main module. }
    define listener as agent { use listener as main module. }
    launchpolicy { launch teller. launch listener. }
"""
SINGLE_TELLER = """
    main module {
        program { if bel(not(told)) then allother.send(hello) + insert(told). }
    }
"""
SINGLE_LISTENER = """
    init module { beliefs { seen(0). } }
    main module {
        program {
            if bel(received(S, hello), seen(N), M is N + 1) then delete(seen(N)) + insert(seen(M)).
        }
    }
"""
SINGLE_SYSTEM = """
    agentfiles { "teller.goal" [name = teller]. "listener.goal" [name = listener]. }
    launchpolicy { launch teller : teller. launch listener : listener. }
"""


def times_seen(path: Path) -> list:
    """The listener's seen/1 beliefs after 6 cycles of both agents."""
    system = MultiAgentSystem.from_mas_file(path, output=io.StringIO(), warn=lambda m: None)
    try:
        system.run(max_cycles=6)
        listener = next(agent for agent in system.agents if agent.name == "listener")
        return [b for b in listener.beliefs() if isinstance(b, Struct) and b.name == "seen"]
    finally:
        system.close()


def test_a_goal6_agent_sees_a_message_in_one_cycle_only(tmp_path: Path) -> None:
    (tmp_path / "teller.mod2g").write_text(textwrap.dedent(TELLER))
    (tmp_path / "listener.mod2g").write_text(textwrap.dedent(LISTENER))
    (tmp_path / "listener.pl").write_text("seen(0).\n")
    (tmp_path / "hello.mas2g").write_text(textwrap.dedent(SYSTEM))
    assert times_seen(tmp_path / "hello.mas2g") == [Struct("seen", (1,))]


def test_a_goal5_agent_keeps_a_message_until_it_deletes_it(tmp_path: Path) -> None:
    (tmp_path / "teller.goal").write_text(textwrap.dedent(SINGLE_TELLER))
    (tmp_path / "listener.goal").write_text(textwrap.dedent(SINGLE_LISTENER))
    (tmp_path / "hello.mas2g").write_text(textwrap.dedent(SINGLE_SYSTEM))
    seen = times_seen(tmp_path / "hello.mas2g")
    assert len(seen) == 1 and seen[0].args[0] >= 4, seen
