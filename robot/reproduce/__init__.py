"""The research workbench: ``goalagent reproduce NAME`` and ``goalagent sweep NAME``.

- ``framework/``: what a study declares, the registry, ``--set``/``--grid``, the runner with
  its local and Ray backends and its cache of finished seeds, the statistics, the versioned
  JSON, the pages and plots. It knows no particular study.
- ``studies/``: one module per thesis table or figure (``xcs-mux`` is ``studies/xcs_mux.py``,
  its ``STUDY``); what several studies share is in ``studies/common/``.
- ``commands.py``: the command line.

Adding a study or a parameter: ``docs/research.md``.
"""
