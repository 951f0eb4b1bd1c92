"""Launch sizes over what the process can hold are refused before any agent is built
(goalagent.mas_capacity): one located line naming the limit and how to raise it, exit 2."""

from __future__ import annotations

import io
import re
import resource
import subprocess
import sys
from pathlib import Path

import pytest

from goalagent.agent import AgentError
from goalagent.mas import MultiAgentSystem
from goalagent.mas_capacity import (
    BYTES_PER_AGENT,
    MEMORY_SHARE,
    agent_capacity,
    available_memory,
    capacity_message,
)
from goalagent.parser import GoalSyntaxError, parse_agent

IDLE = "init module { beliefs { n(0). } }\n"


def write_system(tmp_path: Path, launches: str) -> Path:
    (tmp_path / "idle.goal").write_text(IDLE)
    path = tmp_path / "sys.mas2g"
    path.write_text('agentfiles { "idle.goal" [name = idle, number = 6]. }\n'
                    f"launchpolicy {{ {launches} }}\n")
    return path


def test_a_launch_over_max_agents_is_refused_before_any_agent_is_built(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    built: list[str] = []
    launch = MultiAgentSystem.launch
    monkeypatch.setattr(MultiAgentSystem, "launch",
                        lambda self, name, *args, **kw: built.append(name)
                        or launch(self, name, *args, **kw))
    path = write_system(tmp_path, "launch a : idle.\n launch b : idle.")
    with pytest.raises(GoalSyntaxError) as caught:
        MultiAgentSystem.from_mas_file(path, output=io.StringIO(), max_agents=10)
    assert built == []
    assert str(caught.value).startswith(f"{path}:3:2: 12 agents are more than --max-agents 10")
    assert "raise it with --max-agents N" in str(caught.value)
    system = MultiAgentSystem.from_mas_file(path, output=io.StringIO(), max_agents=12)
    assert len(system.agents) == 12
    system.close()


def test_launching_one_agent_more_than_the_limit_is_an_agent_error() -> None:
    system = MultiAgentSystem(output=io.StringIO(), max_agents=2)
    program = parse_agent(IDLE, "idle.goal")
    system.launch("a", program)
    system.launch("a", program)
    with pytest.raises(AgentError, match="3 agents are more than --max-agents 2"):
        system.launch("a", program)
    assert [agent.name for agent in system.agents] == ["a", "a2"]
    system.close()


def test_the_default_limit_is_what_the_memory_available_holds(
        tmp_path: Path) -> None:
    soft, hard = resource.getrlimit(resource.RLIMIT_DATA)
    data = _status_kib("VmData") * 1024
    room = 200 * 2**20  # 200 MiB more than the process holds as data now
    resource.setrlimit(resource.RLIMIT_DATA, (data + room, hard))
    try:
        assert available_memory() <= room
        capacity = agent_capacity()
        path = write_system(tmp_path, "\n".join(f"launch a{i} : idle." for i in range(600)))
        with pytest.raises(GoalSyntaxError) as caught:
            MultiAgentSystem.from_mas_file(path, output=io.StringIO())
    finally:
        resource.setrlimit(resource.RLIMIT_DATA, (soft, hard))
    assert capacity <= int(room * MEMORY_SHARE) // BYTES_PER_AGENT  # 2,400 at most
    named = re.search(r"the limit is ([\d,]+) agents", str(caught.value))
    assert named is not None  # (the process's data grew a little between the two readings)
    assert 0.95 * capacity <= int(named.group(1).replace(",", "")) <= capacity
    assert "free memory, or raise it with --max-agents N" in str(caught.value)


def test_the_message_says_the_memory_needed() -> None:
    # 100,000 agents x 64 KiB = 6.5536 GB; a limit of 1,000 agents is 65.536 MB
    assert capacity_message(100_000, 1_000, by_hand=False) == (
        "100,000 agents need about 6.6 GB, more than the 66 MB this process may use (75% of "
        "the memory available): the limit is 1,000 agents; free memory, or raise it with "
        "--max-agents N")
    assert capacity_message(3, 2, by_hand=True) == (  # 196,608 bytes
        "3 agents are more than --max-agents 2 allows (about 197 kB); raise it with "
        "--max-agents N")


def test_run_refuses_with_one_line_and_exit_2(tmp_path: Path) -> None:
    path = write_system(tmp_path, "launch a : idle.")
    done = subprocess.run([sys.executable, "-m", "goalagent", "run", str(path),
                           "--max-agents", "5", "--max-cycles", "1"],
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 2
    assert done.stdout == ""
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1, done.stderr
    assert lines[0] == (f"error: {path}:2:16: 6 agents are more than --max-agents 5 allows "
                        "(about 393 kB); raise it with --max-agents N")


def _status_kib(field: str) -> int:
    with open("/proc/self/status") as status:
        for line in status:
            if line.startswith(f"{field}:"):
                return int(line.split()[1])
    raise AssertionError(f"no {field}")
