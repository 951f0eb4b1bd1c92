"""Installing without root: a fresh virtualenv, ``pip install .`` of this tree (no extras),
against the machine's SWI-Prolog, gives a ``goalagent`` that runs, checks and tests plain GOAL
agents; what the extras bring is named when it is missing; a missing SWI-Prolog is one line
saying how to install it.

The tree is copied first (pip would otherwise leave ``build/`` in it) and installed in the
ordinary way, by the pip of the environment running the tests (``pip --python``: a fresh
virtualenv without a pip of its own is made in a moment), which builds it in an isolated
build environment and takes the dependencies from its cache or index as a user's pip would.
One thing differs: pip compiles no bytecode (neither in the build environment nor in the
virtualenv), and the installed command's children may write it: they compile only the
modules they import, once, where pip compiled every file of every dependency (Pygments'
lexers, pydantic, setuptools), about 2 of the fixture's 6 s of CPU. Nothing checked here
depends on bytecode.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import venv
from pathlib import Path

import pytest

from goalagent.swi import install_line, too_old, version_text

pytestmark = pytest.mark.heavy  # run first (tests/conftest.py)

ROOT = Path(__file__).resolve().parents[2]
DISTRIBUTED = ("goalagent", "ondisk", "robot", "sim", "behaviours")
HELLO = ROOT / "agents" / "examples" / "hello_world.goal"
TEST_FILE = ROOT / "agents" / "examples" / "goal6" / "coffee" / "coffee.test2g"


@pytest.fixture(scope="module")
def installed(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A fresh virtualenv with ``pip install .`` of a copy of this tree; its bin folder."""
    base = tmp_path_factory.mktemp("install")
    tree = base / "tree"
    tree.mkdir()
    for name in ("pyproject.toml", "README.md"):
        shutil.copy(ROOT / name, tree / name)
    ignore = shutil.ignore_patterns("__pycache__", "*.pyc")
    for package in DISTRIBUTED:
        shutil.copytree(ROOT / package, tree / package, ignore=ignore)
    home = base / "venv"
    venv.create(home, with_pip=False)  # (this pip installs into it: --python, pip >= 22.3)
    bin_dir = home / "bin"
    # PIP_COMPILE reaches the pip that fills the isolated build environment too (a flag
    # would not)
    pip = subprocess.run([sys.executable, "-m", "pip", "--python", str(bin_dir / "python"),
                          "install", "-q", str(tree)], capture_output=True, text=True,
                         timeout=600, env={**os.environ, "PIP_COMPILE": "0"})
    assert pip.returncode == 0, pip.stderr[-3000:]
    return bin_dir


def _environment(**extra: str) -> dict[str, str]:
    """The installed command's environment: this one's, but its children may write bytecode
    (into the throwaway virtualenv: see the module's docstring), and ``extra``."""
    environment = {key: value for key, value in os.environ.items()
                   if key != "PYTHONDONTWRITEBYTECODE"}
    return {**environment, **extra}


def _goalagent(bin_dir: Path, *args: str, env: dict[str, str] | None = None,
               cwd: Path | None = None) -> subprocess.CompletedProcess[str]:
    return subprocess.run([str(bin_dir / "goalagent"), *args], capture_output=True, text=True,
                          timeout=120, env=env or _environment(), cwd=cwd)


def _python(bin_dir: Path, code: str) -> subprocess.CompletedProcess[str]:
    """The virtualenv's Python running ``code`` in its bin folder (from this tree's root,
    ``-c`` would import this tree's packages instead of the installed ones)."""
    return subprocess.run([str(bin_dir / "python"), "-c", code], capture_output=True,
                          text=True, timeout=300, env=_environment(), cwd=bin_dir)


def test_the_plain_install_runs_a_goal_agent(installed: Path) -> None:
    run = _goalagent(installed, "run", str(HELLO))
    assert run.returncode == 0, run.stderr
    assert run.stdout == "Hello, world!\n" * 3
    assert run.stderr == "helloWorld: terminated after 3 cycles, 9 actions, 0 goals left\n"


def test_the_plain_install_checks_and_tests_agents(installed: Path) -> None:
    check = _goalagent(installed, "check", str(HELLO))
    assert check.returncode == 0, check.stderr
    test = _goalagent(installed, "test", TEST_FILE.name, cwd=TEST_FILE.parent)
    assert test.returncode == 0, test.stdout + test.stderr
    assert "0 failed" in test.stdout


def test_the_plain_install_has_no_robot_weight(installed: Path) -> None:
    """The language alone: no MuJoCo, OpenCV, numpy or web server came with it."""
    for module in ("mujoco", "cv2", "numpy", "sklearn", "starlette"):
        found = _python(installed, f"import {module}")
        assert found.returncode != 0, f"{module} was installed without its extra"


EXTRA_MODULES = ("goalagent.inspector",)  # the mind inspector: the inspector extra


def test_every_module_of_the_language_imports_with_the_core_dependencies(
        installed: Path) -> None:
    """Nothing of goalagent but the inspector needs an extra (numpy, pydantic, ... stay in
    the robot application)."""
    script = (
        "import importlib, pkgutil, goalagent, sysconfig\n"
        "assert goalagent.__file__.startswith(sysconfig.get_paths()['purelib'])\n"
        "failed = []\n"
        "for info in pkgutil.walk_packages(goalagent.__path__, 'goalagent.'):\n"
        f"    if info.name.endswith('.__main__') or info.name.startswith({EXTRA_MODULES!r}):\n"
        "        continue\n"
        "    try:\n"
        "        importlib.import_module(info.name)\n"
        "    except ImportError as error:\n"
        "        failed.append(f'{info.name}: {error}')\n"
        "print(*failed, sep='\\n')\n")
    result = _python(installed, script)
    assert result.returncode == 0, result.stderr[-3000:]
    assert result.stdout == "\n", result.stdout


def test_a_missing_extra_is_named(installed: Path, tmp_path: Path) -> None:
    agent = tmp_path / "a.goal"
    agent.write_text("main module [exit=always] { program { if true then print(hi). } }\n")
    garbage = _goalagent(installed, "run", str(agent), "--env", "garbage")
    assert garbage.returncode == 2
    assert "pip install 'goalagent[robot]'" in garbage.stderr
    assert "Traceback" not in garbage.stderr
    inspect = _goalagent(installed, "run", str(agent), "--inspect", "--port", "0")
    assert inspect.returncode == 2
    assert inspect.stderr.strip().endswith("pip install 'goalagent[inspector]'")


def test_no_swi_prolog_is_one_line_saying_how_to_install_it(installed: Path) -> None:
    """SWI-Prolog where none is (LIBSWIPL_PATH names pyswip's library outright)."""
    env = _environment(LIBSWIPL_PATH="/nonexistent/libswipl.so", SWI_HOME_DIR="/nonexistent")
    run = _goalagent(installed, "run", str(HELLO), env=env)
    assert run.returncode == 2
    assert run.stdout == ""
    [line] = run.stderr.splitlines()
    assert line.startswith("error: goalagent needs SWI-Prolog 9.0 or newer, found none (")
    for way in ("apt-get install swi-prolog-nox", "brew install swi-prolog",
                "conda install -c conda-forge swi-prolog"):
        assert way in line


def test_too_old_a_swi_prolog_is_named_with_its_version() -> None:
    assert version_text(90004) == "9.0.4" and version_text(80502) == "8.5.2"
    assert too_old(80502) and too_old(89999)
    assert not too_old(90000) and not too_old(90004) and not too_old(100100)
    line = install_line(version_text(80502))
    assert line.startswith("goalagent needs SWI-Prolog 9.0 or newer, found 8.5.2. Install")

