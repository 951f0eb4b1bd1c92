"""House rule, checked on every Python file of the packages: no file over 600 lines, no class
over 400 (a file or class that grows past them is doing more than one job)."""

from __future__ import annotations

import ast
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
PACKAGES = ("goalagent", "sim", "behaviours", "robot", "ondisk")
MAX_FILE_LINES = 600
MAX_CLASS_LINES = 400


def test_files_and_classes_stay_small() -> None:
    too_big = []
    for path in sorted(p for package in PACKAGES for p in (ROOT / package).rglob("*.py")):
        text = path.read_text(encoding="utf-8")
        name = path.relative_to(ROOT)
        if text.count("\n") > MAX_FILE_LINES:
            too_big.append(f"{name}: {text.count(chr(10))} lines")
        for node in ast.walk(ast.parse(text)):
            if isinstance(node, ast.ClassDef):
                size = node.end_lineno - node.lineno + 1  # type: ignore[operator]
                if size > MAX_CLASS_LINES:
                    too_big.append(f"{name}:{node.lineno}: class {node.name}, {size} lines")
    assert not too_big, "\n".join(too_big)
