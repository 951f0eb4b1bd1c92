"""Saving and loading an XCS learner: a versioned learner file of kind ``xcs`` (``persist``).

Its state holds the state length, the GA clock, the numpy bit generator's state (so a loaded
learner draws the same random numbers the saved one would have) and every macro-classifier as
``[condition, action, prediction, error, fitness, experience, numerosity, action_set_size,
time_stamp]``. The JSON Schema ``schemas/xcs.schema.json`` states every field; what it cannot
(an action against n_actions, conditions of one length, no repeated classifier, numerosities
within N, n_bits against the conditions) is checked here. Anything wrong is a ValueError
(`LearnerFileError`) naming the file and the field.
"""

from __future__ import annotations

import math
import os
from collections.abc import Iterable
from typing import TYPE_CHECKING

import numpy as np

from .persist import LearnerFileError, json_params, read_learner, write_learner
from .schemas import check
from .xcs_population import Classifier, Population, condition_masks

if TYPE_CHECKING:
    from .xcs_agent import XCS

KIND = "xcs"


def check_records(classifiers: Iterable[Classifier | tuple], n_actions: int,
                  size_limit: int) -> list[Classifier]:
    """Classifier records checked against the schema's ``classifier`` and each other; errors
    name ``classifiers[i].field``."""
    if isinstance(classifiers, str | bytes | dict) or not isinstance(classifiers, Iterable):
        raise ValueError(f"classifiers must be a list of classifier records, got "
                         f"{type(classifiers).__name__}")
    records: list[Classifier] = []
    seen: dict[tuple[str, int], int] = {}
    for index, raw in enumerate(classifiers):
        where = f"classifiers[{index}]"
        fields = [field.item() if isinstance(field, np.generic) else field
                  for field in raw] if isinstance(raw, tuple | list) else raw
        check(fields, KIND, at=("classifiers", index), definition="classifier")
        record = Classifier(*fields)
        for name in ("prediction", "error", "fitness", "action_set_size"):
            if not math.isfinite(getattr(record, name)):  # (files hold no NaN: read_json)
                raise ValueError(f"{where}.{name} must be a finite number, got "
                                 f"{getattr(record, name)!r}")
        if record.action >= n_actions:
            raise ValueError(f"{where}.action must be an action index 0..{n_actions - 1}, "
                             f"got {record.action!r}")
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
    """The learner from a file that passed the schema."""
    xcs = cls(**params)
    settings = xcs._ready()  # the parameters' own constraints
    records = check_records(state["classifiers"], settings.n_actions, settings.N)
    n_bits = state["n_bits"]
    if records and len(records[0].condition) != n_bits:
        raise ValueError(f"n_bits is {n_bits!r} but conditions have {len(records[0].condition)}")
    xcs.set_classifiers(records, time=state["time"])
    if n_bits is not None and xcs.n_bits_ is None:
        xcs.n_bits_ = n_bits
        xcs.population_ = Population(n_bits, settings.N + settings.n_actions + 2)
    xcs._rng = _generator(state["random_generator"])
    return xcs


def _generator(state: dict) -> np.random.Generator:
    """numpy's generator in the saved state (the schema checked the bit generator's name)."""
    bit_generator = getattr(np.random, state["bit_generator"])()
    try:
        bit_generator.state = state
    except (TypeError, ValueError, KeyError) as error:
        raise ValueError(f"random_generator: bad state ({error})") from None
    return np.random.Generator(bit_generator)
