"""The research workbench's framework, which knows no particular study: what a study declares
(``study``), finding it by name (``registry``), ``--set`` and ``--grid`` (``settings``), its
(config, seed) tasks (``tasks``) run on this machine (``backends``) or a Ray cluster
(``cluster``; ``local_cluster`` starts one here) with a cache of finished ones (``cache``),
the statistics (``statistics``), the versioned JSON with its provenance (``documents``,
``provenance``), the pages and plots (``pages``, ``plots``), reproductions and sweeps
(``runner``, ``sweeps``). The ``goalagent reproduce`` / ``sweep`` commands are
``robot/reproduce/commands.py``.

A study imports what it declares from here."""

from robot.reproduce.framework.pages import markdown_table
from robot.reproduce.framework.plots import Figure, Panel, Reference, Series
from robot.reproduce.framework.study import (
    Claim,
    Deviation,
    Metric,
    Progress,
    Reading,
    ScaledConfig,
    SeedResult,
    Study,
    StudyConfig,
    in_turn,
)

__all__ = ["Claim", "Deviation", "Figure", "Metric", "Panel", "Progress", "Reading",
           "Reference", "ScaledConfig", "SeedResult", "Series", "Study", "StudyConfig",
           "in_turn", "markdown_table"]
