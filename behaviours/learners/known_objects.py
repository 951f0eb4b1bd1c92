"""The database of known objects O_kn (thesis §5.5.2): what was learned on each object.

A ``KnownObject`` keeps an object's parts (Table 5.1 descriptors), their ``above`` relations,
the action types' bounds, every pair model's samples (θ, e_ψ, e_o) and the functional pair
that achieved the goal. ``KnownObjectDatabase`` persists them as one versioned JSON file,
rewritten atomically (``persist.write_text_atomically``) on every change, so a crash never
leaves half a database. Models are stored as their samples and refitted when first used
after loading (the samples are the truth; the coefficients are written for human readers
only). A file is checked by its schema, then for what the schema cannot say (numbers that
JSON reads as infinite or too large for a float, one sample per index, parts the models
name), so a hostile file is a DatabaseError naming the record, never a crash.
"""

from __future__ import annotations

import json
import math
import os
import reprlib
from collections.abc import Iterable, Iterator, Mapping
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
_NUMBER_TYPES = frozenset({int, float})
"""What JSON numbers are read as (``true`` is no number, though Python's bool is an int)."""


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
        if isinstance(self.models, StoredModels):
            models = [self.models.record(pair) for pair in self.models]
        else:
            models = [_model_record(pair, model) for pair, model in self.models.items()]
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
        """Rebuild from a record that passed the schema (ValueError saying what else is
        wrong); the pair models are fitted on their samples when first asked for."""
        functional = record.get("functional")
        return cls(
            name=record["name"],
            parts={name: _descriptor(values, name) for name, values in record["parts"].items()},
            above=frozenset((a, b) for a, b in record["above"]),
            bounds={a: check_bounds(b, f"bounds of {a!r}") for a, b in record["bounds"].items()},
            models=StoredModels(_model_entry(entry) for entry in record["models"]),
            functional=None if functional is None else FunctionalPair(
                functional["part"], functional["action"],
                _numbers([functional["theta"]], "the functional theta")[0]),
            n_actions=record.get("n_actions", 0),
            source=record.get("source"),
            extra=dict(record.get("extra") or {}),
        )


class StoredModels(Mapping[Pair, PartActionModel]):
    """An object's pair models as read from a database: each entry's samples are checked
    when the file is read and the model is fitted on them when first asked for, so loading
    costs no fitting (a database of 150,000 models loads in seconds), and a rewrite (after
    ``forget``) writes the entries of models nobody asked for back as they were read."""

    def __init__(self, entries: Iterable[tuple[Pair, dict]]) -> None:
        self._entries = dict(entries)
        self._fitted: dict[Pair, PartActionModel] = {}

    def __getitem__(self, pair: Pair) -> PartActionModel:
        model = self._fitted.get(pair)
        if model is None:
            entry = self._entries[pair]
            model = PartActionModel().fit(entry["theta"], entry["displacement"],
                                          entry["effect"])
            self._fitted[pair] = model
        return model

    def __iter__(self) -> Iterator[Pair]:
        return iter(self._entries)

    def __len__(self) -> int:
        return len(self._entries)

    def record(self, pair: Pair) -> dict:
        """The database entry of ``pair``'s model."""
        entry = self._entries[pair]
        if pair not in self._fitted and "g" in entry and "h" in entry:
            return entry
        return _model_record(pair, self[pair])


def _model_record(pair: Pair, model: PartActionModel) -> dict:
    """The database entry of a fitted pair model: its samples (the truth) and, for human
    readers, the coefficients of ĝ and ĥ."""
    return {"part": pair[0], "action": pair[1],
            "theta": model.theta_.tolist(), "displacement": model.displacement_.tolist(),
            "effect": model.effect_.tolist(),
            "g": [model.g_intercept_, model.g_slope_], "h": [model.h_intercept_, model.h_slope_]}


def _model_entry(entry: dict) -> tuple[Pair, dict]:
    """A pair model's entry (its structure checked by the schema), checked for finite
    numbers and one sample (θ, e_ψ, e_o) per index."""
    pair = (entry["part"], entry["action"])
    for key in ("theta", "displacement", "effect", "g", "h"):
        if key in entry and not _finite_numbers(entry[key]):
            raise ValueError(f"{key} of {pair} must hold finite numbers only, got "
                             f"{reprlib.repr(entry[key])}")
    if not len(entry["theta"]) == len(entry["displacement"]) == len(entry["effect"]):
        raise ValueError(f"the model of {pair} has not one theta, displacement and effect "
                         "per sample")
    return pair, entry


def _finite_numbers(values: object) -> bool:
    """Whether ``values`` is a non-empty list of finite JSON numbers. JSON reads ``1e400``
    as infinity and ``10**400`` as an integer no float holds; the schema passes both.
    Checked in C where it can be (``map(type, ...)``, ``math.fsum``: a sum is finite exactly
    when every term is, and a 400-digit integer overflows it): a database holds hundreds of
    thousands of these short lists, for which numpy costs more than the check."""
    if type(values) is not list or not values:
        return False
    try:
        return _NUMBER_TYPES.issuperset(map(type, values)) and math.isfinite(math.fsum(values))
    except (OverflowError, ValueError):  # ValueError: inf and -inf in one list
        return False


def _numbers(values: object, what: str) -> list:
    """``values`` if it is a non-empty list of finite numbers, else a ValueError naming
    ``what``."""
    if not _finite_numbers(values):
        raise ValueError(f"{what} must be a non-empty list of finite numbers, got "
                         f"{reprlib.repr(values)}")
    return values  # type: ignore[return-value]


def _descriptor(values: object, name: object) -> np.ndarray:
    """A part descriptor as a finite float vector, or a ValueError naming the part."""
    return np.asarray(_numbers(values, f"the descriptor of part {reprlib.repr(name)}"))


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
            except (KeyError, TypeError, ValueError, AttributeError, OverflowError) as exc:
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
