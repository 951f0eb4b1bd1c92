"""The database of known objects O_kn (thesis §5.5.2): what was learned on each object.

A ``KnownObject`` keeps an object's parts (Table 5.1 descriptors), their ``above`` relations,
the action types' bounds, every pair model's samples (θ, e_ψ, e_o) and the functional pair
that achieved the goal. ``KnownObjectDatabase`` persists them as one versioned JSON file,
rewritten atomically (``persist.write_text_atomically``) on every change, so a crash never
leaves half a database. Models are stored as their samples and refitted when first used
after loading (the samples are the truth; the coefficients are written for human readers
only); every value read is checked first, so a hostile file is a DatabaseError naming the
record, never a crash.
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
from behaviours.learners.persist import StoreFileError, read_json, write_text_atomically

DATABASE_FORMAT = "goalagent-known-objects"
DATABASE_VERSION = 1
MAX_NAME_CHARS = 200
"""Longest object, part or action name read from a database."""
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
        """Rebuild from a record (KeyError/TypeError/ValueError saying what is wrong). Every
        value is checked now; the pair models are fitted on their samples when first read."""
        parts = {_text(name, "a part name"): _descriptor(values, name)
                 for name, values in record["parts"].items()}
        functional = record.get("functional")
        source = record.get("source")
        return cls(
            name=_text(record["name"], "the name"),
            parts=parts,
            above=frozenset((_text(a, "a part name"), _text(b, "a part name"))
                            for a, b in record["above"]),
            bounds={_text(a, "an action name"): check_bounds(b, f"bounds of {a!r}")
                    for a, b in record["bounds"].items()},
            models=StoredModels(_model_entry(entry) for entry in record["models"]),
            functional=None if functional is None else FunctionalPair(
                _text(functional["part"], "a part name"),
                _text(functional["action"], "an action name"),
                _numbers([functional["theta"]], "the functional theta")[0]),
            n_actions=_count(record.get("n_actions", 0)),
            source=None if source is None else _text(source, "the source"),
            extra=_extra(record.get("extra")),
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
    """A pair model's database entry, checked: one finite sample (θ, e_ψ, e_o) per index and
    the coefficients of ĝ and ĥ, when written, as two finite numbers each."""
    pair = (_text(entry["part"], "a part name"), _text(entry["action"], "an action name"))
    theta, displacement, effect = entry["theta"], entry["displacement"], entry["effect"]
    checked = {"part": pair[0], "action": pair[1], "theta": theta,
               "displacement": displacement, "effect": effect}
    for key in ("g", "h"):
        if key in entry:
            checked[key] = entry[key]
    for key, values in checked.items():
        if key not in ("part", "action") and not _finite_numbers(values):
            raise ValueError(f"{key} of {pair} must be a non-empty list of finite numbers, "
                             f"got {reprlib.repr(values)}")
    if not len(theta) == len(displacement) == len(effect):
        raise ValueError(f"the model of {pair} has not one theta, displacement and effect "
                         "per sample")
    if any(key in checked and len(checked[key]) != 2 for key in ("g", "h")):
        raise ValueError(f"the model of {pair} needs g and h as [intercept, slope]")
    return pair, checked


def _text(value: object, what: str) -> str:
    """``value`` if it is a non-empty string of at most MAX_NAME_CHARS, else a ValueError."""
    if not isinstance(value, str) or not value or len(value) > MAX_NAME_CHARS:
        raise ValueError(f"{what} must be a string of 1 to {MAX_NAME_CHARS} characters, got "
                         f"{reprlib.repr(value)}")
    return value


def _finite_numbers(values: object) -> bool:
    """Whether ``values`` is a non-empty list of finite JSON numbers. Checked in C where it
    can be (``map(type, ...)``, ``math.fsum``: a sum is finite exactly when every term is,
    and a 400-digit integer overflows it): a database holds hundreds of thousands of these
    short lists, for which numpy costs more than the check."""
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


def _count(value: object) -> int:
    """A non-negative whole number (the actions an object was learned with)."""
    if type(value) is not int or value < 0:
        raise ValueError(f"n_actions must be a whole number of at least 0, got "
                         f"{reprlib.repr(value)}")
    return value


def _extra(value: object) -> dict:
    """The free-form facts of a record: a mapping (or nothing)."""
    if value is None:
        return {}
    if not isinstance(value, dict):
        raise ValueError(f"extra must be a mapping, got {reprlib.repr(value)}")
    return dict(value)


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
        """Read every object from the file, or raise DatabaseError naming the file."""
        where = str(self.path)
        try:
            data = read_json(self.path, "known-object database")
        except StoreFileError as exc:
            raise DatabaseError(str(exc)) from None
        if not isinstance(data, dict) or data.get("format") != DATABASE_FORMAT:
            raise DatabaseError(f"{where!r} is not a goalagent known-object database")
        if data.get("version") != DATABASE_VERSION:
            raise DatabaseError(f"known-object database {where!r} has version "
                                f"{data.get('version')!r}; this goalagent reads version "
                                f"{DATABASE_VERSION}")
        records = data.get("objects")
        if not isinstance(records, list):
            raise DatabaseError(f"known-object database {where!r} has no list of objects")
        for index, record in enumerate(records):
            try:
                known = KnownObject.from_record(record)
            except (KeyError, TypeError, ValueError, AttributeError, OverflowError) as exc:
                raise DatabaseError(f"known-object database {where!r} has a bad record (object "
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
