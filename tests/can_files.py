"""Can files written in the tests (YAML text), as a user writes a can the repository does not
ship; shared by the tests of more than one layer."""

HIGH_STEEP_HANDLE = """\
# A lift handle high on a narrow can, geared steeply: lifted far, it stands over the rim.
name: high_lift
mechanism:
  type: lift_handle
  gear: 18.0
dimensions:
  width: 0.18
  depth: 0.24
  height: 0.30
lid:
  height: 0.03
  marker_z: 0.015
handle:
  drop: 0.06
"""
