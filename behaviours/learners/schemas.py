"""The learners' stores checked against JSON Schemas kept as data in ``schemas/``.

Each store (a learner file of each kind, the effect-model store, the known-object database)
has a schema ``schemas/NAME.schema.json`` (draft-07) stating its structure: which fields,
their types, their ranges. `check` validates a document, or one ``definitions`` entry of it
(a database is checked object by object), and raises `SchemaError` at the first defect with
its path, e.g. ``state.classifiers[3].fitness: must be bigger than 0, got 0.0``. What a
schema cannot state (a value against another field, e.g. an action below the learner's
n_actions) stays in the loaders.

Why ``fastjsonschema`` rather than ``jsonschema`` (which checks the can files): it compiles
a schema into Python code once, and checks a known object of three pair models in ~32 µs
where ``jsonschema`` takes ~790 µs (a database of 150,000 models: 1.6 s against 40 s,
measured on this machine; reading its JSON takes ~2 s). The stores are read by
``persist.read_json``, which refuses ``NaN`` and ``Infinity`` (not JSON, and written by no
store), so every number a schema passes is finite.
"""

from __future__ import annotations

import json
import reprlib
from collections.abc import Callable, Iterable
from functools import cache
from pathlib import Path

import fastjsonschema

__all__ = ["SCHEMA_DIR", "SchemaError", "check"]

SCHEMA_DIR = Path(__file__).parent / "schemas"


class SchemaError(ValueError):
    """A document that does not follow its schema; the message starts with the path."""


@cache
def _schema(name: str) -> dict:
    return json.loads((SCHEMA_DIR / f"{name}.schema.json").read_text(encoding="utf-8"))


@cache
def _validator(name: str, definition: str | None) -> Callable[[object], object]:
    """The compiled check of schema ``name``, or of its entry ``definitions/definition``."""
    schema = _schema(name)
    if definition is not None:
        schema = {"$schema": schema["$schema"], "definitions": schema["definitions"],
                  "$ref": f"#/definitions/{definition}"}
    return fastjsonschema.compile(schema)


def check(document: object, name: str, at: Iterable[str | int] = (),
          definition: str | None = None) -> None:
    """Raise SchemaError if ``document`` breaks schema ``name`` (or its ``definitions`` entry
    ``definition``); ``at`` is the document's own path, put before the error's."""
    try:
        _validator(name, definition)(document)
    except fastjsonschema.JsonSchemaValueException as error:
        raise SchemaError(f"{_path([*at, *error.path[1:]], error.definition)}: "
                          f"{_message(error)}") from None


def _path(steps: list[str | int], failed: dict | None) -> str:
    """``a.b[3].title`` for the failing value: a tuple position whose schema has a title
    (e.g. a classifier's ``fitness``) is named by it."""
    text = ""
    for index, step in enumerate(steps):
        if isinstance(step, int) or str(step).isdigit():
            title = (failed or {}).get("title") if index == len(steps) - 1 else None
            text += f".{title}" if title else f"[{step}]"
        else:
            text += f".{step}" if text else str(step)
    return text or "the document"


def _message(error: fastjsonschema.JsonSchemaValueException) -> str:
    """fastjsonschema's message without its ``data...`` prefix (the path says where), and
    the value (shortened)."""
    message = error.message
    if message.startswith(error.name):
        message = message[len(error.name):].strip()
    return f"{message}, got {reprlib.repr(error.value)}"
