"""bench/locality.py's reading of callgrind's output: self costs per shared object."""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "bench"))

from locality import self_costs  # noqa: E402

# Two objects; a call from libpython into libswipl whose inclusive cost (the line after
# calls=) must not count as libpython's own; names given once with their id, then by id.
PROFILE = """\
version: 1
positions: line
events: Ir D1mr DLmr
ob=(1) /usr/lib/libpython3.11.so
fl=(1) ceval.c
fn=(1) eval
10 100 4 1
+2 50 1
cob=(2) /usr/lib/x86_64-linux-gnu/libswipl.so.9
cfn=(2) PL_next_solution
calls=3 0
12 9000 300 30
ob=(2)
fl=(2) pl-wam.c
fn=(2)
0 9000 300 30
* 7
ob=(1)
fn=(1)
14 5 0 0
"""


def test_self_costs_are_summed_per_object_without_calls_inclusive_costs():
    costs = self_costs(PROFILE)
    assert dict(costs["libpython3.11.so"]) == {"Ir": 155, "D1mr": 5, "DLmr": 1}
    assert dict(costs["libswipl.so.9"]) == {"Ir": 9007, "D1mr": 300, "DLmr": 30}
