"""The database of known objects O_kn (thesis §5.5.2): what was learned on each object.

A ``KnownObject`` keeps an object's parts (Table 5.1 descriptors), their ``above`` relations,
the action types' bounds, every pair model's samples (θ, e_ψ, e_o) and the functional pair
that achieved the goal. ``KnownObjectDatabase`` persists them as one versioned JSON file,
rewritten atomically (``persist.write_text_atomically``) on every change, so a crash never
leaves half a database. Models are stored as their samples and refitted on
load (the samples are the truth; the coefficients are written for human readers only).
"""

from __future__ import annotations

import json
import math
import os
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from behaviours.learners.part_models import (
    Bounds,
    FunctionalPair,
    Pair,
    PartActionModel,
    check_bounds,
)
from behaviours.learners.persist import check_store, read_store, write_text_atomically

DATABASE_FORMAT = "goalagent-known-objects"
DATABASE_VERSION = 1


class DatabaseError(ValueError):
    """A known-object database file that cannot be read, or a bad request to one."""


@dataclass(frozen=True)
class KnownObject:
    """What the robot learned about one object."""

    name: str
    parts: Mapping[str, np.ndarray]
    above: frozenset[tuple[str, str]]
    bounds: Mapping[str, Bounds]
    models: Mapping[Pair, PartActionModel]
    functional: FunctionalPair | None = None
    n_actions: int = 0
    source: str | None = None
    """The known object it was learned from by transfer (None: learned from scratch)."""
    extra: Mapping[str, object] = field(default_factory=dict)
    """Free-form facts for readers (e.g. which can file it came from)."""

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name:
            raise ValueError(f"a known object needs a non-empty name, got {self.name!r}")
        for (part, action) in self.models:
            if part not in self.parts:
                raise ValueError(f"{self.name}: model for unknown part {part!r}")
            if action not in self.bounds:
                raise ValueError(f"{self.name}: model for action {action!r} without bounds")

    @classmethod
    def learned(cls, name: str, learner: object,
                extra: Mapping[str, object] | None = None) -> KnownObject:
        """What a fitted ``PartBasedLearner`` or ``TransferLearner`` learned on an object."""
        if not hasattr(learner, "models_"):
            raise ValueError("the learner has not been fitted on an object yet")
        view = learner.view_  # type: ignore[attr-defined]
        return cls(name=name, parts=dict(view.parts), above=frozenset(view.above),
                   bounds=dict(learner.bounds_),  # type: ignore[attr-defined]
                   models=dict(learner.models_),  # type: ignore[attr-defined]
                   functional=learner.functional_,  # type: ignore[attr-defined]
                   n_actions=learner.n_actions_,  # type: ignore[attr-defined]
                   source=getattr(learner, "source_", None), extra=dict(extra or {}))

    def to_record(self) -> dict:
        """A JSON-ready record."""
        models = []
        for (part, action), model in self.models.items():
            models.append({
                "part": part, "action": action,
                "theta": model.theta_.tolist(), "displacement": model.displacement_.tolist(),
                "effect": model.effect_.tolist(),
                "g": [model.g_intercept_, model.g_slope_],
                "h": [model.h_intercept_, model.h_slope_],
            })
        functional = None if self.functional is None else {
            "part": self.functional.part, "action": self.functional.action,
            "theta": self.functional.theta}
        return {
            "name": self.name,
            "parts": {name: [float(x) for x in d] for name, d in self.parts.items()},
            "above": sorted([list(pair) for pair in self.above]),
            "bounds": {action: list(b) for action, b in self.bounds.items()},
            "models": models,
            "functional": functional,
            "n_actions": self.n_actions,
            "source": self.source,
            "extra": dict(self.extra),
        }

    @classmethod
    def from_record(cls, record: dict) -> KnownObject:
        """Rebuild from a record, refitting each model on its samples (KeyError/ValueError)."""
        parts = {str(name): _descriptor(values, name) for name, values in record["parts"].items()}
        models: dict[Pair, PartActionModel] = {}
        for entry in record["models"]:
            pair = (str(entry["part"]), str(entry["action"]))
            models[pair] = PartActionModel().fit(entry["theta"], entry["displacement"],
                                                 entry["effect"])
        functional = record.get("functional")
        return cls(
            name=str(record["name"]),
            parts=parts,
            above=frozenset((str(a), str(b)) for a, b in record["above"]),
            bounds={str(a): check_bounds(b, f"bounds of {a!r}")
                    for a, b in record["bounds"].items()},
            models=models,
            functional=None if functional is None else FunctionalPair(
                str(functional["part"]), str(functional["action"]), float(functional["theta"])),
            n_actions=int(record.get("n_actions", 0)),
            source=None if record.get("source") is None else str(record["source"]),
            extra=dict(record.get("extra") or {}),
        )


def _descriptor(values: object, name: object) -> np.ndarray:
    """A part descriptor as a finite float vector, or a ValueError naming the part."""
    array = np.asarray(values, dtype=float)
    if array.ndim != 1 or array.size == 0 or not np.all(np.isfinite(array)):
        raise ValueError(f"part {name!r} has a bad descriptor {values!r}")
    return array


class KnownObjectDatabase:
    """Known objects by name, oldest first, persisted as JSON at ``path``."""

    def __init__(self, path: str | os.PathLike[str]) -> None:
        self.path = Path(path)
        self._objects: dict[str, KnownObject] = {}
        if self.path.exists():
            self._load()

    def _load(self) -> None:
        """Read every object from the file, checked by
        ``schemas/known_objects.schema.json``, or raise DatabaseError naming the file and
        where in it."""
        what = "known-object database"
        data = read_store(self.path, what, DATABASE_FORMAT, DATABASE_VERSION, DatabaseError)
        check_store(data, "known_objects", self.path, what, DatabaseError)
        for index, record in enumerate(data["objects"]):
            try:
                known = KnownObject.from_record(record)
            except (KeyError, TypeError, ValueError, AttributeError) as exc:
                raise DatabaseError(f"{what} {str(self.path)!r} has a bad record (object "
                                    f"{index}): {exc!r}") from None
            self._objects[known.name] = known

    def __iter__(self) -> Iterator[KnownObject]:
        """The known objects, oldest first."""
        return iter(list(self._objects.values()))

    def __len__(self) -> int:
        return len(self._objects)

    def __contains__(self, name: object) -> bool:
        return name in self._objects

    def names(self) -> list[str]:
        """Names of the known objects, oldest first."""
        return list(self._objects)

    def get(self, name: str) -> KnownObject:
        """The known object called ``name``, or a DatabaseError listing the known names."""
        try:
            return self._objects[name]
        except KeyError:
            known = ", ".join(self._objects) or "none"
            raise DatabaseError(f"no known object {name!r}; known objects: {known}") from None

    def add(self, known: KnownObject) -> None:
        """Store (or replace, as the newest) an object; the database changes only if saved."""
        objects = {k: v for k, v in self._objects.items() if k != known.name}
        objects[known.name] = known
        self._write(objects)
        self._objects = objects

    def forget(self, name: str) -> KnownObject:
        """Remove an object and return it (DatabaseError if it is not known)."""
        known = self.get(name)
        objects = {k: v for k, v in self._objects.items() if k != name}
        self._write(objects)
        self._objects = objects
        return known

    def _write(self, objects: Mapping[str, KnownObject]) -> None:
        """Write the objects, all or nothing (``persist.write_text_atomically``)."""
        payload = {"format": DATABASE_FORMAT, "version": DATABASE_VERSION,
                   "objects": [known.to_record() for known in objects.values()]}
        text = json.dumps(payload, indent=1, allow_nan=False, default=_plain)
        write_text_atomically(self.path, text)


def _plain(value: object) -> object:
    """numpy scalars in ``extra`` as plain numbers (json's fallback)."""
    if isinstance(value, np.generic):
        number = value.item()
        if isinstance(number, float) and not math.isfinite(number):
            raise ValueError(f"cannot store the non-finite number {number}")
        return number
    raise TypeError(f"cannot store {type(value).__name__} {value!r} in the database")
