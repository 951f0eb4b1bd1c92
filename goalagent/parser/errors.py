"""The one error the parser raises: a user mistake in a program file, at ``file:line:col``."""

from __future__ import annotations

from goalagent import ast


class GoalSyntaxError(Exception):
    """A user error in a program file, located at ``file:line:col``."""

    def __init__(self, file: str, line: int, col: int, message: str) -> None:
        super().__init__(f"{file}:{line}:{col}: {message}")
        self.file = file
        self.line = line
        self.col = col
        self.message = message

    @classmethod
    def at(cls, pos: ast.Pos, message: str) -> GoalSyntaxError:
        """The error at a source position."""
        return cls(pos.file, pos.line, pos.col, message)
