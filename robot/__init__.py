"""The robot application on top of goalagent, behaviours and sim: EIS environments over the
MuJoCo worlds, afford/6 reports and plots, snapshots and the robot commands of ``goalagent``
(registered through the ``goalagent.extensions`` entry point, ``robot/extension.py``)."""
