"""Fuzzing the loaders and the command line (issues 14 and 19): every input ends in an answer
or a located user error, never a traceback, within a time bound per input (a hang fails and
names its input) and without the worker's memory running away. Inputs run in a child
process (tests/attacks/fuzz_worker.py) that is killed when it is late; the whole module is bounded
to about a minute by its example counts."""

from __future__ import annotations

import json
import os
import re
import select
import signal
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from goalagent.beliefs import read_belief_file

pytestmark = pytest.mark.heavy  # run first (tests/conftest.py)

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "agents" / "examples"
PER_INPUT_SECONDS = 30  # generous for a loaded machine; an input normally takes milliseconds
SCALE = float(os.environ.get("GOALAGENT_FUZZ_SCALE", "1"))  # more examples: e.g. 20
GROWTH_MB = 300  # how much the worker's peak memory may grow over the whole fuzz
FUZZ = settings(deadline=None, database=None,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large,
                                       HealthCheck.function_scoped_fixture])


class Worker:
    """The fuzz worker child: one request at a time, each with a time bound."""

    def __init__(self, folder: Path) -> None:
        self.folder = folder
        self.process: subprocess.Popen[str] | None = None
        self.baseline_mb: float | None = None

    def ask(self, kind: str, value: object) -> dict:
        if self.process is None or self.process.poll() is not None:
            self.process = subprocess.Popen(
                [sys.executable, str(Path(__file__).with_name("fuzz_worker.py"))],
                cwd=self.folder, stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True,
                env={**os.environ, "PYTHONPATH": str(ROOT)})
        assert self.process.stdin is not None and self.process.stdout is not None
        self.process.stdin.write(json.dumps({"kind": kind, "input": value}) + "\n")
        self.process.stdin.flush()
        ready, _, _ = select.select([self.process.stdout], [], [], PER_INPUT_SECONDS)
        if not ready:
            self.process.kill()
            self.process.wait()
            self.process = None
            pytest.fail(f"no answer within {PER_INPUT_SECONDS} s (a hang) for {kind} input "
                        f"{value!r:.3000}")
        line = self.process.stdout.readline()
        if not line:
            code = self.process.wait()
            self.process = None
            pytest.fail(f"the worker died (exit {code}) on {kind} input {value!r:.3000}")
        answer = json.loads(line)
        assert "escaped" not in answer, f"{kind} input {value!r:.3000}:\n{answer['escaped']}"
        if self.baseline_mb is None:
            self.baseline_mb = answer["rss_mb"]
        assert answer["rss_mb"] - self.baseline_mb < GROWTH_MB, (kind, value, answer)
        return answer

    def close(self) -> None:
        if self.process is not None:
            self.process.stdin.close()  # type: ignore[union-attr]
            self.process.wait(timeout=60)


@pytest.fixture(scope="module")
def worker(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Worker]:
    started = Worker(tmp_path_factory.mktemp("fuzz"))
    yield started
    started.close()


# ------------------------------------------------------------------ inputs

SEEDS = [(EXAMPLES / name).read_text() for name in (
    "hello_world.goal", "stack_builder.goal", "nested_rules.goal", "listall_macros.goal",
    "user_modules.goal", "coffee_maker.goal")]
BOMBS = [
    "#define m0 bel(p(X)).\n" + "".join(f"#define m{i} m{i - 1}, m{i - 1}.\n"
                                        for i in range(1, 25)),
    "[" * 300, "]" * 300, "(" * 250 + ")" * 250, "f(" * 220 + "a" + ")" * 220,
    "1" * 5000, "0x" + "f" * 9000, "X is 10^300000", "'\\=", '"a\\=b"', "0'", "\\u0000",
    "\x00", "é", "\U0001F600", "/*", "%", "\n", ":- initialization(halt).", "'$ga_gm'(x)",
    "#import \"/dev/zero.pl\".", '#import "a\\=.pl".', "p :- " + ", ".join(["q"] * 400),
    "1" + "+1" * 400, "- " * 300 + "1", "{" * 220, "a" * 100_000,
]
PIECES = ["(", ")", "{", "}", "[", "]", ".", ",", "'", '"', "%", "+", "\\+", "not(", "bel(",
          "goal(", "a-goal(", "if", "then", "forall", "do", "X", "_", "#define m(X) bel(X).",
          "module", "[exit=never]", ":-", "->", ";", "!", "@int", "insert(", "print(", "\n",
          " ", "listall", "<-", "exit-module", "send(", "a.send(:p)", "actionspec {"]


@st.composite
def agent_texts(draw: st.DrawFn) -> str:
    """A shipped example with characters deleted, pieces or bombs inserted."""
    text = draw(st.sampled_from(SEEDS))
    for _ in range(draw(st.integers(1, 4))):
        where = draw(st.integers(0, len(text)))
        kind = draw(st.sampled_from(["delete", "piece", "piece", "bomb"]))
        if kind == "delete":
            text = text[:where] + text[where + draw(st.integers(1, 8)):]
        else:
            pool = PIECES if kind == "piece" else BOMBS
            text = text[:where] + draw(st.sampled_from(pool)) + text[where:]
    return text


PATHS = ["a.goal", "/dev/zero", "/dev/null", ".", "fifo", "missing.goal", "a\\=b.goal",
         "../a.goal", "a.goal\\u0000", "/proc/self/mem", "a" * 300 + ".goal"]


@st.composite
def mas_texts(draw: st.DrawFn) -> str:
    """`.mas2g` files from fuzzed parts: environment, agent files, launch rules."""
    parts = []
    if draw(st.booleans()):
        env = draw(st.sampled_from(["blocksworld", "\"printer\"", "nosuch", "'a:b'", "1" * 5000,
                                    "[" * 300]))
        init = draw(st.sampled_from(["", " init = [x = 1].", " init = [x].", " init = y.",
                                     " init = [state = " + "[" * 250 + "]."]))
        parts.append(f"environment {{ env = {env}.{init} }}")
    files = draw(st.lists(st.tuples(st.sampled_from(PATHS), st.sampled_from(
        ["", " [name=a]", " [number=2]", " [number=x]", " [nam=a]", " [number=" + "9" * 40 + "]"])),
        min_size=0, max_size=3))
    parts.append("agentfiles { " + " ".join(f'"{path}"{options}.' for path, options in files)
                 + " }")
    if draw(st.booleans()):
        parts.append(draw(st.sampled_from(["launchpolicy { launch a:a. }",
                                           "launchpolicy { launch b:zz. }",
                                           "launchpolicy { when [type=robot, max=1]@env do "
                                           "launch *:a. }", "launchpolicy { launch"])))
    text = "\n".join(parts)
    if draw(st.booleans()):
        where = draw(st.integers(0, len(text)))
        text = text[:where] + draw(st.sampled_from(PIECES + BOMBS)) + text[where:]
    return text


FACTS = ["afford(lid, push, opened, 3, 1, 0.33).", "visited(a, 1).", "p.", ":- halt.",
         "p :- q.", "p(X).", "atom(a).", "user:p.", "42.", "(a, b).", "afford(l,p,o,x,1,2).",
         "afford(l, p, o, 1, 2, 0.5).", "afford(l, p, o, 2, 1, 1.5).", "p(\"a\\=b\").",
         "p(" + "f(" * 250 + ")" * 250 + ").", "p(" + "9" * 6000 + ").", "p('$ga').",
         "end_of_file.", "p(a) % comment", "/* open", "p(0'a).", "'\\x41\\'(b)."]


@st.composite
def fact_texts(draw: st.DrawFn) -> str:
    lines = draw(st.lists(st.sampled_from(FACTS), min_size=0, max_size=6))
    text = "\n".join(lines) + "\n"
    if draw(st.booleans()):
        where = draw(st.integers(0, len(text)))
        text = text[:where] + draw(st.sampled_from(PIECES)) + text[where:]
    return text


@st.composite
def store_texts(draw: st.DrawFn) -> str:
    record = {"key": draw(st.sampled_from([["o1", "lid", "push"], [], "abc", [1, 2], None])),
              "bounds": draw(st.sampled_from([[0, 1], [1, 0], ["a"], None, [0, "nan"]])),
              "theta": draw(st.sampled_from([[0.1, 0.2], [], ["x"], [1e308, -1e308], 3])),
              "effect": draw(st.sampled_from([[0.0, 0.1], [0.0], None])),
              "fit_intercept": draw(st.sampled_from([True, "yes", None]))}
    text = json.dumps({"format": draw(st.sampled_from(["goalagent-effect-models",
                                                       "goalagent-learner", 3])),
                       "version": draw(st.sampled_from([1, 2, "1"])), "kind": "cacla",
                       "params": draw(st.sampled_from([{}, [], None])), "state": {},
                       "models": draw(st.sampled_from([[record], record, None, []]))})
    if draw(st.booleans()):
        where = draw(st.integers(0, len(text)))
        text = text[:where] + draw(st.sampled_from(["[" * 3000, "1" * 5000, "}", "\x00", ""]
                                                   )) + text[where:]
    return text


HELLO = str(EXAMPLES / "hello_world.goal")
VALUES = ["", "0", "-1", "3", "9" * 30, "x", "a=b", "=", "x=" + "[" * 300, "x=" + "9" * 5000,
          "{tmp}/out.pl", "{tmp}/fifo", "{tmp}", "/dev/zero", "visited/2", "v/99999", "/2",
          "30s", "0s", "end", "1e9h", "blocksworld", "garbage", "a:b", "os:system", "\x00",
          "state=[on(a,table)]", "can=o9", "models={tmp}/fifo", "ü", "-" * 3]
OPTIONS = ["--env", "--env-param", "--max-cycles", "--seed", "--trace", "--load-beliefs",
           "--save-beliefs", "--save-predicate", "--save-every", "--plot", "--help", "--nope"]


@st.composite
def command_lines(draw: st.DrawFn) -> list[str]:
    """``goalagent`` command lines from the real options with hostile values; a run is kept
    short by a cycle limit unless the line sets its own."""
    command = draw(st.sampled_from(["run", "run", "run", "check", "snapshot", "nope", ""]))
    path = draw(st.sampled_from([HELLO, str(EXAMPLES / "coffee.mas2g"), "{tmp}/fifo",
                                 "/dev/zero", "{tmp}", "missing.goal", "x.mas2g", "--env"]))
    args = [command, path] if command else [path]
    for _ in range(draw(st.integers(0, 4))):
        option = draw(st.sampled_from(OPTIONS))
        args.append(option)
        if option not in ("--trace", "--help") and draw(st.integers(0, 5)):
            args.append(draw(st.sampled_from(VALUES)))
    if command == "run" and "--max-cycles" not in args:
        args += ["--max-cycles", "2"]
    if command == "snapshot":
        args += ["--out", "{tmp}/frame.png"]
    return args


# ------------------------------------------------------------------ properties

@settings(FUZZ, max_examples=int(200 * SCALE))
@given(text=agent_texts())
def test_agent_files(worker: Worker, text: str):
    worker.ask("agent", text)


@settings(FUZZ, max_examples=int(100 * SCALE))
@given(text=mas_texts())
def test_mas_files(worker: Worker, text: str):
    worker.ask("mas", text)


@settings(FUZZ, max_examples=int(100 * SCALE))
@given(text=fact_texts())
def test_belief_files(worker: Worker, text: str):
    worker.ask("facts", text)


@settings(FUZZ, max_examples=int(50 * SCALE))
@given(text=store_texts())
def test_model_and_learner_stores(worker: Worker, text: str):
    worker.ask("store", text)


@settings(FUZZ, max_examples=int(100 * SCALE))
@given(args=command_lines())
def test_command_lines(worker: Worker, args: list[str]):
    worker.ask("cli", args)


WALKER = """
init module { beliefs { at(0). } program { if true then print(started). } }
main module { program {
    if bel(at(N), M is N + 1) then delete(at(N)) + insert(at(M)) + insert(visited(M)).
} }
"""


@settings(FUZZ, max_examples=4)
@given(how=st.sampled_from([signal.SIGINT, signal.SIGTERM, signal.SIGKILL]),
       delay=st.floats(0, 0.5))
def test_kill_points(tmp_path: Path, how: int, delay: float):
    """A run saving every cycle stopped by a signal at a drawn moment: its exit code says
    which, within the time bound, and the saved file is whole and complete. The moments
    that differ come early: before the first save (the run prints ``started`` before its
    first cycle), during the first ones, then any moment of the loop, which saves every few
    milliseconds (half a second is dozens of saves; a later moment only finds a longer
    file, and each second the run goes on costs its CPU)."""
    program = tmp_path / "walker.goal"
    program.write_text(WALKER)
    saved = tmp_path / f"saved-{how}-{delay}.pl"
    child = subprocess.Popen([sys.executable, "-m", "goalagent", "run", str(program),
                              "--save-beliefs", str(saved), "--save-predicate", "visited/1",
                              "--save-every", "1"], cwd=tmp_path, stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, text=True,
                             env={**os.environ, "PYTHONUNBUFFERED": "1"})
    assert child.stdout is not None and child.stdout.readline() == "started\n"
    time.sleep(delay)
    child.send_signal(how)
    try:
        _, stderr = child.communicate(timeout=PER_INPUT_SECONDS)
    except subprocess.TimeoutExpired:
        child.kill()
        pytest.fail(f"{signal.Signals(how).name} after {delay} s did not end the run")
    assert child.returncode == {signal.SIGINT: 130, signal.SIGTERM: 143,
                                signal.SIGKILL: -9}[how], stderr
    assert "Traceback" not in stderr
    if saved.exists():
        with read_belief_file(saved, []) as facts:  # it loads: whole
            assert facts.count >= 0
        visited = [int(n) for n in re.findall(r"^visited\((\d+)\)\.$", saved.read_text(), re.M)]
        assert visited == list(range(1, len(visited) + 1))  # and complete
