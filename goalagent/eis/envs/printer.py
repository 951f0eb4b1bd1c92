"""The printer of GOAL's script-printing example agents.

Action ``printText(T)`` prints ``T`` on stdout as one line: an atom or string as its text, any
other term as Prolog text. Percept ``printedText(N)``: the number of lines printed so far.
"""

from __future__ import annotations

import sys
from collections.abc import Iterable

from goalagent.eis.pyenv import PerceptLike, PythonEnvironment, action
from goalagent.kb.terms import format_term


class Printer(PythonEnvironment):
    """Prints text lines on stdout and counts them."""

    name = "printer"
    entity_names = ("printer",)
    default_entity_type = "printer"
    parameters: dict[str, object] = {}

    def on_init(self, params: dict[str, object]) -> None:
        """Start with nothing printed."""
        self.printed = 0

    def percepts(self, entity: str) -> Iterable[PerceptLike]:
        """``printedText(N)``: lines printed so far."""
        return [("printedText", self.printed)]

    @action("printText")
    def print_text(self, entity: str, text: object) -> None:
        """Print ``text`` as one line on stdout and count it."""
        shown = text if isinstance(text, str) else format_term(text)
        sys.stdout.write(f"{shown}\n")
        sys.stdout.flush()
        self.printed += 1
