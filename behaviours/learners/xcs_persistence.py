"""Saving and loading an XCS learner: a versioned learner file of kind ``xcs`` (``persist``).

Its state holds the state length, the GA clock, the numpy bit generator's state (so a loaded
learner draws the same random numbers the saved one would have) and every macro-classifier as
``[condition, action, prediction, error, fitness, experience, numerosity, action_set_size,
time_stamp]``. Anything else — not JSON, another format, version or kind, a field out of range —
is a ValueError (`LearnerFileError`) naming the file and the field.
"""

from __future__ import annotations

import math
import os
from collections.abc import Iterable
from typing import TYPE_CHECKING

import numpy as np

from .persist import LearnerFileError, json_params, read_learner, write_learner
from .xcs_params import DEFAULTS
from .xcs_population import Classifier, Population, condition_masks

if TYPE_CHECKING:
    from .xcs_agent import XCS

KIND = "xcs"
BIT_GENERATORS = ("PCG64", "PCG64DXSM", "MT19937", "Philox", "SFC64")


def _is_integer(value: object) -> bool:
    return isinstance(value, int | np.integer) and not isinstance(value, bool)


def _is_number(value: object) -> bool:
    return (isinstance(value, int | float | np.integer | np.floating)
            and not isinstance(value, bool) and math.isfinite(value))


def check_records(classifiers: Iterable[Classifier | tuple], n_actions: int,
                  size_limit: int) -> list[Classifier]:
    """Classifier records checked field by field; errors name ``classifiers[i].field``."""
    if isinstance(classifiers, str | bytes | dict) or not isinstance(classifiers, Iterable):
        raise ValueError(f"classifiers must be a list of classifier records, got "
                         f"{type(classifiers).__name__}")
    records: list[Classifier] = []
    seen: dict[tuple[str, int], int] = {}
    for index, raw in enumerate(classifiers):
        where = f"classifiers[{index}]"
        if isinstance(raw, str | bytes) or not isinstance(raw, Iterable):
            raise ValueError(f"{where} must be a record of {len(Classifier._fields)} fields")
        fields = list(raw)
        if len(fields) != len(Classifier._fields):
            raise ValueError(f"{where} must have {len(Classifier._fields)} fields "
                             f"({', '.join(Classifier._fields)}), got {len(fields)}")
        record = Classifier(*fields)
        _check_record(record, where, n_actions)
        if records and len(record.condition) != len(records[0].condition):
            raise ValueError(f"{where}.condition has {len(record.condition)} positions, "
                             f"classifiers[0] has {len(records[0].condition)}")
        key = (record.condition, int(record.action))
        if key in seen:
            raise ValueError(f"{where} repeats the condition and action of "
                             f"classifiers[{seen[key]}]")
        seen[key] = index
        records.append(record)
    total = sum(int(record.numerosity) for record in records)
    if total > size_limit:
        raise ValueError(f"classifiers: total numerosity {total} exceeds N ({size_limit})")
    return records


def _check_record(record: Classifier, where: str, n_actions: int) -> None:
    condition = record.condition
    if not isinstance(condition, str) or not condition or set(condition) - set("01#"):
        raise ValueError(f"{where}.condition must be a non-empty string over 0, 1, #, "
                         f"got {condition!r}")
    if not _is_integer(record.action) or not 0 <= record.action < n_actions:
        raise ValueError(f"{where}.action must be an integer in 0..{n_actions - 1}, "
                         f"got {record.action!r}")
    checks = (("prediction", _is_number(record.prediction)),
              ("error", _is_number(record.error) and record.error >= 0),
              ("fitness", _is_number(record.fitness) and record.fitness > 0),
              ("experience", _is_integer(record.experience) and record.experience >= 0),
              ("numerosity", _is_integer(record.numerosity) and record.numerosity >= 1),
              ("action_set_size", _is_number(record.action_set_size)
               and record.action_set_size >= 0),
              ("time_stamp", _is_integer(record.time_stamp) and record.time_stamp >= 0))
    for field, good in checks:
        if not good:
            raise ValueError(f"{where}.{field} is out of range: {getattr(record, field)!r}")


def fill(population: Population, records: list[Classifier]) -> None:
    """Add checked records to an empty population."""
    for record in records:
        care, value = condition_masks(record.condition)
        population.add(care, value, int(record.action), prediction=float(record.prediction),
                       error=float(record.error), fitness=float(record.fitness),
                       experience=int(record.experience), numerosity=int(record.numerosity),
                       action_set_size=float(record.action_set_size),
                       time_stamp=int(record.time_stamp))


def save(xcs: XCS, path: str | os.PathLike[str]) -> None:
    """Write ``xcs`` to ``path`` atomically as a versioned learner file of kind ``xcs``."""
    state = {"n_bits": xcs.n_bits_, "time": int(xcs.time_),
             "random_generator": xcs._rng.bit_generator.state,
             "classifiers": [list(record) for record in xcs.classifiers()]}
    write_learner(path, KIND, json_params(xcs), state)


def load(cls: type[XCS], path: str | os.PathLike[str]) -> XCS:
    """Read a learner written by `save`; any defect is a ValueError naming ``path``."""
    params, state = read_learner(path, KIND)
    try:
        return _restore(cls, params, state)
    except ValueError as error:
        raise LearnerFileError(f"XCS file {str(path)!r}: {error}") from None


def _restore(cls: type[XCS], params: dict, state: dict) -> XCS:
    expected = {"n_actions", *DEFAULTS}
    if set(params) != expected:
        raise ValueError("params: expected exactly " + ", ".join(sorted(expected)))
    xcs = cls(**params)
    settings = xcs._ready()
    classifiers = state.get("classifiers")
    if not isinstance(classifiers, list):
        raise ValueError("classifiers: expected a list")
    n_bits = state.get("n_bits")
    if n_bits is not None and (not _is_integer(n_bits) or n_bits < 1):
        raise ValueError(f"n_bits must be null or an integer >= 1, got {n_bits!r}")
    records = check_records(classifiers, settings.n_actions, settings.N)
    if records and len(records[0].condition) != n_bits:
        raise ValueError(f"n_bits is {n_bits!r} but conditions have {len(records[0].condition)}")
    time = state.get("time")
    if not _is_integer(time) or time < 0:
        raise ValueError(f"time must be an integer >= 0, got {time!r}")
    xcs.set_classifiers(records, time=time)
    if n_bits is not None and xcs.n_bits_ is None:
        xcs.n_bits_ = n_bits
        xcs.population_ = Population(n_bits, settings.N + settings.n_actions + 2)
    xcs._rng = _generator(state.get("random_generator"))
    return xcs


def _generator(state: object) -> np.random.Generator:
    name = state.get("bit_generator") if isinstance(state, dict) else None
    if name not in BIT_GENERATORS:
        raise ValueError(f"random_generator: unknown bit generator {name!r}")
    bit_generator = getattr(np.random, name)()
    try:
        bit_generator.state = state
    except (TypeError, ValueError, KeyError) as error:
        raise ValueError(f"random_generator: bad state ({error})") from None
    return np.random.Generator(bit_generator)
