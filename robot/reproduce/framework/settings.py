"""``--set KEY=VALUE`` and ``--grid KEY=V1,V2,...``: values typed and validated against the
study's config, unknown keys answered with the closest parameter names.

A value is first read as the text it is (``400`` for an int, ``1e-4`` for a float, ``true``
for a bool, ``camera`` for a choice) and, if the field does not take that, as JSON (``null``,
``["o1", "o3"]``): pydantic validates both against the field's type and limits."""

from __future__ import annotations

import difflib
import json
from collections.abc import Iterable, Sequence

from pydantic import ValidationError

from robot.reproduce.framework.study import Study, StudyConfig


class SettingError(ValueError):
    """A ``--set`` or ``--grid`` the config does not take (one line, for exit 2)."""


def split_assignment(text: str, option: str) -> tuple[str, str]:
    """``KEY=VALUE`` -> (KEY, VALUE)."""
    key, equals, value = text.partition("=")
    if not equals or not key.strip():
        raise SettingError(f"{option} {text!r}: write KEY=VALUE")
    return key.strip(), value.strip()


def check_key(study: Study, key: str, option: str) -> None:
    """SettingError naming the closest parameters when ``key`` is not one of the config's."""
    fields = list(study.config.model_fields)
    if key in fields:
        return
    close = difflib.get_close_matches(key, fields, n=3, cutoff=0.6)
    close += [f for f in fields if f.lower() == key.lower() and f not in close]
    hint = f"did you mean {' or '.join(repr(c) for c in close)}? " if close else ""
    raise SettingError(f"{option} {key}: {study.name} has no parameter {key!r}; {hint}its "
                       f"parameters: {', '.join(fields)}")


def _candidates(raw: str) -> list[object]:
    """The text itself, then its JSON reading when it has one that is not that text."""
    try:
        parsed = json.loads(raw)
    except ValueError:
        return [raw]
    return [raw] if parsed == raw else [raw, parsed]


def with_value(study: Study, config: StudyConfig, key: str, raw: str,
               option: str) -> StudyConfig:
    """``config`` with ``key`` set from the text ``raw``, validated as a whole."""
    check_key(study, key, option)
    first_error: ValidationError | None = None
    for candidate in _candidates(raw):
        try:
            return study.config.model_validate({**config.model_dump(), key: candidate})
        except ValidationError as error:
            first_error = first_error or error
    assert first_error is not None
    detail = first_error.errors()[0]
    where = ".".join(str(part) for part in detail["loc"]) or "the config"
    raise SettingError(f"{option} {key}={raw}: {where}: {detail['msg']} "
                       f"({study.config.describe(key) or 'no description'})")


def apply(study: Study, config: StudyConfig, settings: Iterable[str]) -> StudyConfig:
    """``config`` with every ``KEY=VALUE`` of ``settings`` (later ones win)."""
    for text in settings:
        key, raw = split_assignment(text, "--set")
        config = with_value(study, config, key, raw, "--set")
    return config


def split_values(text: str) -> list[str]:
    """``V1,V2,...`` -> the values; commas inside [...] or quotes stay in their value."""
    values, current, depth, quote = [], [], 0, ""
    for char in text:
        if quote:
            quote = "" if char == quote else quote
        elif char in "\"'":
            quote = char
        elif char == "[":
            depth += 1
        elif char == "]":
            depth -= 1
        elif char == "," and depth == 0:
            values.append("".join(current).strip())
            current = []
            continue
        current.append(char)
    values.append("".join(current).strip())
    return values


def parse_grid(study: Study, config: StudyConfig,
               items: Sequence[str]) -> dict[str, list[object]]:
    """``--grid KEY=V1,V2`` options -> {KEY: [typed values]}, each value validated on
    ``config``; SettingError for an empty grid, an empty value or a key given twice."""
    if not items:
        raise SettingError("a sweep needs at least one --grid KEY=V1,V2,...")
    grid: dict[str, list[object]] = {}
    for text in items:
        key, raw = split_assignment(text, "--grid")
        check_key(study, key, "--grid")
        if key in grid:
            raise SettingError(f"--grid {key}: given twice; list all its values in one --grid")
        values = split_values(raw)
        if not raw or any(not value for value in values):
            raise SettingError(f"--grid {text!r}: give the values as {key}=V1,V2,... "
                               "(none may be empty)")
        typed = [getattr(with_value(study, config, key, value, "--grid"), key)
                 for value in values]
        if len({json.dumps(_plain(v)) for v in typed}) != len(typed):
            raise SettingError(f"--grid {text!r}: a value is given twice")
        grid[key] = typed
    return grid


def _plain(value: object) -> object:
    return list(value) if isinstance(value, tuple) else value


def format_value(value: object) -> str:
    """A config value as ``--set`` reads it back."""
    if isinstance(value, str):
        return value
    return json.dumps(_plain(value), separators=(",", ":"))
