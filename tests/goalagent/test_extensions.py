"""The extension seam: entry points, run options and hooks, saved predicates, lazy loading."""

from __future__ import annotations

from pathlib import Path

import pytest
from typer.testing import CliRunner

from goalagent import extensions
from goalagent.cli import create_app
from goalagent.eis import load_environment
from goalagent.extensions import Extension, RunContext, RunHook, RunOption, installed_extensions
from goalagent.parser import GoalSyntaxError, parse_agent_file
from tests.conftest import ROOT, cli, goalagent, python

HELLO = ROOT / "agents" / "examples" / "hello_world.goal"
VISITS = """
main: walker {
    init module { beliefs { visited(a, 1). visited('B c', 2). here(a). } }
    main module [exit=always] { program { if true then insert(visited(c, 3.5)). } }
}
"""


def test_the_robot_extension_is_found_by_its_entry_point():
    (robot,) = [e for e in installed_extensions() if e.name == "robot"]
    assert robot.environments == {
        "garbage": "robot.envs.garbage:GarbageEnvironment",
        "navigation": "robot.envs.navigation:NavigationEnvironment",
        "stacking": "robot.envs.stacking:StackingEnvironment",
        "search": "robot.envs.search:SearchEnvironment"}
    assert [p.indicator for p in robot.saved_predicates] == ["afford/6"]
    assert load_environment("garbage").__module__ == "robot.envs.garbage"


def test_check_on_a_plain_agent_loads_the_extension_but_not_mujoco_or_opencv():
    result = python(f"""
        import sys
        from goalagent.cli import create_app
        try:
            create_app()(["check", {str(HELLO)!r}])
        except SystemExit as stop:
            print("exit", stop.code)
        print(sorted(m for m in ("robot.extension", "mujoco", "cv2", "sim.world")
                     if m in sys.modules))
    """)
    assert result.stdout.splitlines() == ["exit 0", "['robot.extension']"], result.stderr


def test_no_import_sets_an_environment_variable_and_the_garbage_environment_chooses_egl(
        monkeypatch: pytest.MonkeyPatch):
    monkeypatch.delenv("MUJOCO_GL", raising=False)  # the children start without it
    result = python("""
        import importlib, os, pkgutil
        # third-party libraries may set variables of their own (OpenCV, OpenMP, Gymnasium's
        # PYGAME_HIDE_SUPPORT_PROMPT): not ours
        for library in ("numpy", "scipy", "sklearn", "cv2", "mujoco", "matplotlib", "pyswip",
                        "lark", "typer", "rich", "imageio", "gymnasium"):
            importlib.import_module(library)
        before = dict(os.environ)
        names = []
        for package in ("goalagent", "sim", "behaviours", "robot", "ondisk"):
            names.append(package)
            module = importlib.import_module(package)
            for info in pkgutil.walk_packages(module.__path__, package + "."):
                if info.name.endswith(".__main__"):  # that one runs the CLI
                    continue
                importlib.import_module(info.name)
                names.append(info.name)
        print(len(names), "sim.world" in names, "robot.envs.garbage" in names)
        print(sorted(set(os.environ.items()) ^ set(before.items())))
        from goalagent.eis import load_environment  # imported above, changing nothing
        load_environment("garbage")
        print(os.environ.get("MUJOCO_GL"))
    """)
    count, changes, chosen = result.stdout.splitlines()
    assert count.endswith(" True True") and int(count.split()[0]) > 40, result.stderr
    assert changes == "[]"
    assert chosen == "egl", result.stderr


class Recorder(RunHook):
    """Notes what a run showed its hooks."""

    events: list[str] = []

    def start(self, run: RunContext) -> None:
        self.events.append(f"start {[a.name for a in run.system.agents]} {run.options['mark']}")

    def after_cycle(self, run: RunContext, agent) -> None:
        self.events.append(f"cycle {agent.cycle}")

    def finish(self, run: RunContext) -> None:
        run.console.print(f"finished with mark {run.options['mark']}", markup=False)
        self.events.append("finish")


def test_an_extension_adds_a_run_option_a_hook_and_a_command():
    def add_commands(app):
        @app.command()
        def hello() -> None:
            print("hello from the extension")

    extension = Extension(name="test", run_options=(RunOption("mark", int, "A number."),),
                          run_hooks=(Recorder,), add_commands=add_commands)
    app = create_app([extension])
    Recorder.events = []
    result = CliRunner().invoke(app, ["run", str(HELLO), "--mark", "7"])
    assert result.exit_code == 0, result.output
    assert Recorder.events == ["start ['helloWorld'] 7", "cycle 1", "cycle 2", "cycle 3",
                               "finish"]
    assert "finished with mark 7" in result.stderr
    assert CliRunner().invoke(app, ["hello"]).stdout == "hello from the extension\n"
    assert CliRunner().invoke(app, ["snapshot"]).exit_code == 2  # not the robot's app: no such


def test_save_predicate_writes_declared_beliefs_that_load_back(tmp_path: Path):
    agent = tmp_path / "walker.goal"
    agent.write_text(VISITS)
    saved = tmp_path / "saved.pl"
    result = cli("run", str(agent), "--save-beliefs", str(saved),
                 "--save-predicate", "visited/2", "--save-predicate", "here/1")
    assert result.exit_code == 0, result.stderr
    assert f"saved 4 visited/2, here/1 beliefs to {saved}" in result.stderr  # no afford/6
    assert saved.read_text() == (
        "% visited/2 beliefs saved by goalagent\n"
        "% here/1 beliefs saved by goalagent\n"
        "% agent walker\n"
        "visited(a,1).\nvisited('B c',2).\nvisited(c,3.5).\nhere(a).\n")
    again = tmp_path / "again.pl"
    empty = tmp_path / "empty.goal"
    empty.write_text("main: walker { main module [exit=always] { program { "
                     "if true then print(x). } } }")
    result = cli("run", str(empty), "--load-beliefs", str(saved), "--save-beliefs",
                 str(again), "--save-predicate", "visited/2", "--save-predicate", "here/1")
    assert result.exit_code == 0, result.stderr
    assert again.read_text() == saved.read_text()


def test_a_bad_save_predicate_is_a_user_error(tmp_path: Path):
    result = cli("run", str(HELLO), "--save-beliefs", str(tmp_path / "x.pl"),
                 "--save-predicate", "visited")
    assert result.exit_code == 2
    assert result.stderr.strip() == ("error: --save-predicate 'visited': expected NAME/ARITY, "
                                     "e.g. visited/2")
    assert "Traceback" not in result.stderr and not (tmp_path / "x.pl").exists()


def test_a_broken_extension_is_a_warning_and_the_language_still_runs(tmp_path: Path):
    info = tmp_path / "broken_ext-1.0.dist-info"
    info.mkdir()
    (info / "METADATA").write_text("Metadata-Version: 2.1\nName: broken-ext\nVersion: 1.0\n")
    (info / "entry_points.txt").write_text(
        "[goalagent.extensions]\nbroken = no_such_module.anywhere:EXTENSION\n")
    result = goalagent("check", str(HELLO), env={"PYTHONPATH": str(tmp_path)})
    assert result.returncode == 0, result.stderr
    assert ("warning: goalagent extension 'broken' (no_such_module.anywhere:EXTENSION) could "
            "not be loaded: ModuleNotFoundError: No module named 'no_such_module'"
            in result.stderr)
    assert "Traceback" not in result.stderr and f"{HELLO}: ok" in result.stderr


def test_an_extension_brings_prolog_libraries_agents_import_by_name(tmp_path: Path,
                                                                     monkeypatch) -> None:
    library = tmp_path / "lib" / "greetings.pl"
    library.parent.mkdir()
    library.write_text("greeting(hello).\n")
    extension = Extension(name="greeter", prolog_libraries=(library,))
    monkeypatch.setattr(extensions, "installed_extensions", lambda: (extension,))
    agent = tmp_path / "agents" / "greeter.goal"
    agent.parent.mkdir()
    agent.write_text('main: greeter {\n    knowledge { #import "greetings". }\n'
                     "    main module [exit=always] { program { if true then print(hi). } }\n}\n")
    program = parse_agent_file(agent)
    assert [clause.text for clause in program.knowledge] == ["greeting(hello)"]
    (agent.parent / "greetings.pl").write_text("greeting(next_to_the_program).\n")
    program = parse_agent_file(agent)  # a file next to the program comes first
    assert [clause.text for clause in program.knowledge] == ["greeting(next_to_the_program)"]
    agent.write_text(agent.read_text().replace('"greetings"', '"farewells.pl"'))
    with pytest.raises(GoalSyntaxError, match="cannot #import 'farewells.pl': no such file next "
                       "to this program nor among the installed extensions' Prolog libraries"):
        parse_agent_file(agent)


def test_the_robot_brings_the_affordance_library():
    assert extensions.prolog_library("affordance.pl") == ROOT / "robot" / "affordance.pl"
    assert extensions.prolog_library("no_such_library.pl") is None
