"""The robot application as a goalagent extension (entry point ``robot`` in the group
``goalagent.extensions``, see ``pyproject.toml``).

Everything the robot adds to the language is declared here and nowhere else: the ``garbage``
environment (and the ch.3-5 task worlds as they arrive under ``robot/envs/``), the Prolog
library ``affordance.pl`` agents ``#import`` (eq. 6.3, roulette choice, the rule bands), the
robot commands (``robot/cli.py``), the afford/6 report and ``--plot`` of ``goalagent run``
(``robot/afford_report.py``), ``afford/6`` as a predicate ``--save-beliefs`` writes, and the
mind inspector's panels (``robot/inspector.py``). This module
and what it imports stay light (no MuJoCo, no OpenCV): goalagent loads it for every command.
"""

from __future__ import annotations

from pathlib import Path

from goalagent.extensions import Extension
from robot.afford_report import PLOT_OPTION, AffordanceReport
from robot.affordance import AFFORD
from robot.cli import add_commands
from robot.inspector import AffordancePanel, CameraPanel
from sim.headless import use_headless_rendering

EXTENSION = Extension(
    name="robot",
    environments={"garbage": "robot.envs.garbage:GarbageEnvironment",
                  "navigation": "robot.envs.navigation:NavigationEnvironment",
                  "stacking": "robot.envs.stacking:StackingEnvironment",
                  "search": "robot.envs.search:SearchEnvironment"},
    prolog_libraries=(Path(__file__).with_name("affordance.pl"),),
    add_commands=add_commands,
    run_options=(PLOT_OPTION,),
    run_hooks=(AffordanceReport,),
    saved_predicates=(AFFORD,),
    prepare=use_headless_rendering,
    inspector_panels=(AffordancePanel, CameraPanel),
)
