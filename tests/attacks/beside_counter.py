"""Attack agents run the way a user reaches them: ``goalagent run`` of a ``.mas2g`` in a child
process with a timeout, beside a counter agent that must still finish (a regression would
otherwise take the test process down with it or hang the suite)."""

from __future__ import annotations

from pathlib import Path

from tests.measured import Measured, goalagent_measured

COUNTER = """
init module { beliefs { n(0). } goals { n(5). } }
main module [exit=nogoals] { program {
    if bel(n(N), N < 5, M is N + 1) then delete(n(N)) + insert(n(M)).
} }
"""


def beside_counter(folder: Path, programs: dict[str, str], *options: str) -> list[str]:
    """The arguments of ``goalagent run OPTIONS`` of one agent per program (NAME.goal) and
    the counter, whose files it writes into ``folder``."""
    for name, program in programs.items():
        (folder / f"{name}.goal").write_text(program)
    (folder / "counter.goal").write_text(COUNTER)
    files = " ".join(f'"{name}.goal".' for name in [*programs, "counter"])
    (folder / "s.mas2g").write_text(f"agentfiles {{ {files} }}\n")
    return ["run", str(folder / "s.mas2g"), *options]


def run_beside_counter(tmp_path: Path, programs: dict[str, str], *options: str,
                       timeout: float = 120) -> Measured:
    """``goalagent run OPTIONS`` of one agent per program (NAME.goal) and the counter."""
    return goalagent_measured(*beside_counter(tmp_path, programs, *options), timeout=timeout)


def counter_finished(result: Measured) -> None:
    """The run raised nothing and the counter finished its five cycles."""
    assert "Traceback" not in result.stderr, result.stderr
    assert "counter: terminated after 5 cycles" in result.stderr, result.stderr
