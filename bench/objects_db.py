"""Loading a large known-object database (issue 24: 16.5 MB did not load in 120 s).

Builds a database of ``--models`` pair models (twelve per object, as the thesis cans have:
two parts by six action types, three samples each), then times in CPU seconds (wall-clock
times on the shared machine swing with others' load), best of ``--repeat``:
the floor, ``json.loads`` of the same bytes (no database can read JSON faster); loading it
with ``KnownObjectDatabase`` (every value checked, no model fitted); and asking every model
once (each fitted on its samples, eq. 5.18). Prints seconds and the ratio to the floor.
Target: loading within 3x the floor.

    .venv/bin/python bench/objects_db.py [--models 150000] [--repeat 3]
"""

from __future__ import annotations

import argparse
import json
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

sys.path[0] = str(Path(__file__).resolve().parents[1])  # the repository, not bench/, first

import numpy as np  # noqa: E402

from behaviours.learners.known_objects import (  # noqa: E402
    DATABASE_FORMAT,
    DATABASE_VERSION,
    KnownObjectDatabase,
)
from ondisk import write_atomically  # noqa: E402

ACTIONS = ("extend_arm", "contract_arm", "sweep_left", "sweep_right", "lift_up", "sweep_down")
PARTS = ("lid", "body")
TARGET_RATIO = 3.0


def database_text(models: int, seed: int = 0) -> str:
    """A database of ``models`` pair models as JSON text."""
    rng = np.random.default_rng(seed)
    per_object = len(PARTS) * len(ACTIONS)
    objects = []
    for index in range(-(-models // per_object)):
        entries = []
        for part in PARTS:
            for action in ACTIONS:
                theta = rng.uniform(0.0, 0.1, 3)
                displacement = 1.2 * theta + rng.normal(0.0, 0.001, 3)
                entries.append({"part": part, "action": action, "theta": theta.tolist(),
                                "displacement": displacement.tolist(),
                                "effect": (0.93 * displacement).tolist(),
                                "g": [0.0, 1.2], "h": [0.0, 0.93]})
        objects.append({"name": f"object{index}", "parts": {p: [0.002, 0.4, 1.0] for p in PARTS},
                        "above": [["lid", "body"]], "bounds": {a: [0.0, 0.1] for a in ACTIONS},
                        "models": entries[:models - index * per_object], "functional": None,
                        "n_actions": 3, "source": None, "extra": {}})
    return json.dumps({"format": DATABASE_FORMAT, "version": DATABASE_VERSION,
                       "objects": objects})


def best(repeat: int, action) -> tuple[float, Any]:
    """The shortest CPU time of ``repeat`` runs of ``action`` and its last result."""
    times, result = [], None
    for _ in range(repeat):
        started = time.process_time()
        result = action()
        times.append(time.process_time() - started)
    return min(times), result


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--models", type=int, default=150_000)
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        path = write_atomically(Path(folder) / "objects.json", database_text(args.models))
        size = path.stat().st_size
        floor, _ = best(args.repeat, lambda: json.loads(path.read_bytes()))
        load, database = best(args.repeat, lambda: KnownObjectDatabase(path))
        fit, _ = best(1, lambda: [known.models[pair] for known in database
                                  for pair in known.models])
    count = sum(len(known.models) for known in database)
    print(f"{count} models in {len(database)} objects, {size / 2**20:.1f} MB")
    print(f"json.loads (floor)       {floor:7.2f} s")
    print(f"load (checked, unfitted) {load:7.2f} s   {load / floor:.2f}x the floor "
          f"(target <= {TARGET_RATIO:.0f}x)")
    print(f"then fit every model     {fit:7.2f} s   {fit / count * 1e6:.0f} us per model")


if __name__ == "__main__":
    main()
