"""The learners' stores checked against JSON Schemas kept as data in ``schemas/``.

Each store (a learner file of each kind, the effect-model store, the known-object database)
has a schema ``schemas/NAME.schema.json`` stating its structure: which fields, their types,
their ranges. `check` validates a document (or one entry of a large one: a compiled validator
is made once per schema, so a database of many entries is checked entry by entry without
re-reading the schema) and raises `SchemaError` at the first defect with its path, e.g.
``state.classifiers[3].fitness: 0.0 is less than or equal to the minimum of 0``. What a schema
cannot state (a value against another field, e.g. an action below the learner's n_actions)
stays in the loaders.

Numbers are JSON numbers that are finite: Python's ``json`` reads ``NaN`` and ``Infinity``,
which no store writes, so the type checker refuses them. Integers are written without a
fraction (``1.0`` is no integer here, as the loaders always had it); numpy's integers count
(records built in memory hold them).
"""

from __future__ import annotations

import json
import math
import numbers
import reprlib
from collections import deque
from collections.abc import Iterable
from functools import cache
from pathlib import Path

import jsonschema
from jsonschema import Draft202012Validator
from jsonschema.exceptions import ValidationError, best_match

__all__ = ["SCHEMA_DIR", "SchemaError", "check", "validator"]

SCHEMA_DIR = Path(__file__).parent / "schemas"
MESSAGE_CHARS = 200
"""Longest message taken from jsonschema (it quotes the offending value, which may be huge)."""


def _is_number(checker: object, value: object) -> bool:
    return (isinstance(value, numbers.Real) and not isinstance(value, bool)
            and math.isfinite(value))


def _is_integer(checker: object, value: object) -> bool:
    return isinstance(value, numbers.Integral) and not isinstance(value, bool)


_TYPES = Draft202012Validator.TYPE_CHECKER.redefine_many(
    {"number": _is_number, "integer": _is_integer})
StoreValidator = jsonschema.validators.extend(Draft202012Validator, type_checker=_TYPES)
"""Draft 2020-12 with finite numbers (see the module doc)."""


class SchemaError(ValueError):
    """A document that does not follow its schema; the message starts with the path."""


@cache
def validator(name: str) -> jsonschema.protocols.Validator:
    """The compiled validator of ``schemas/NAME.schema.json`` (read and checked once)."""
    schema = json.loads((SCHEMA_DIR / f"{name}.schema.json").read_text(encoding="utf-8"))
    StoreValidator.check_schema(schema)
    return StoreValidator(schema)


def check(document: object, name: str, at: Iterable[str | int] = (),
          definition: str | None = None) -> None:
    """Raise SchemaError if ``document`` breaks schema ``name`` (or its ``$defs`` entry
    ``definition``); ``at`` is the document's own path, put before the error's."""
    checker = validator(name)
    if definition is not None:
        checker = checker.evolve(schema={"$ref": f"#/$defs/{definition}",
                                         "$defs": checker.schema["$defs"]})
    error = best_match(checker.iter_errors(document))
    if error is not None:
        raise SchemaError(f"{_path(list(at), error)}: {_message(error)}")


def _path(prefix: list[str | int], error: ValidationError) -> str:
    """``a.b[3].title`` for the failing value: a tuple position whose schema has a title
    (e.g. a classifier's ``fitness``) is named by it."""
    steps: deque[str | int] = deque(prefix)
    steps.extend(error.absolute_path)
    schema_path = list(error.absolute_schema_path)
    in_tuple = len(schema_path) >= 3 and schema_path[-3] == "prefixItems"
    text = ""
    for index, step in enumerate(steps):
        if isinstance(step, int):
            title = error.schema.get("title") if in_tuple and index == len(steps) - 1 else None
            text += f".{title}" if title else f"[{step}]"
        else:
            text += f".{step}" if text else str(step)
    return text or "the document"


def _message(error: ValidationError) -> str:
    """jsonschema's message, the offending value shortened."""
    message = error.message
    if len(message) > MESSAGE_CHARS:
        quoted = repr(error.instance)
        message = message.replace(quoted, reprlib.repr(error.instance))[:MESSAGE_CHARS]
    return message
