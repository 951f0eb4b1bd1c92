"""Prolog variable names in source text, found without reading the text as Prolog (quoted
atoms and strings are skipped), for macro expansion, singleton warnings and descriptions."""

from __future__ import annotations

import re
from collections.abc import Iterator

_VAR_OR_QUOTED = re.compile(
    r"'(?:\\.|''|[^'\\])*'|\"(?:\\.|\"\"|[^\"\\])*\"|`(?:\\.|``|[^`\\])*`|0'(?:\\.|''|.)"
    r"|(?<![A-Za-z0-9_])([A-Z_][A-Za-z0-9_]*)"
)


def variable_occurrences(text: str) -> Iterator[str]:
    """Variable names in Prolog text, once per occurrence (quoted text skipped)."""
    for match in _VAR_OR_QUOTED.finditer(text):
        if match.group(1):
            yield match.group(1)


def rename_variables(text: str, mapping: dict[str, str]) -> str:
    """Replace variables by the texts in ``mapping`` (quoted text untouched)."""

    def substitute(match: re.Match[str]) -> str:
        name = match.group(1)
        return mapping.get(name, match.group(0)) if name else match.group(0)

    return _VAR_OR_QUOTED.sub(substitute, text)
