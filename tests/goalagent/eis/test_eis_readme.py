"""The example environment in goalagent/eis/README.md runs as documented."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from goalagent.eis import ActionRefused, load_environment
from goalagent.eis.terms import Action

README = Path(__file__).resolve().parents[3] / "goalagent" / "eis" / "README.md"


def test_readme_lamp_example() -> None:
    match = re.search(r"```python\n(.*?)```", README.read_text(), re.S)
    assert match is not None
    exec(compile(match.group(1), str(README), "exec"), {"__name__": "eis_readme_example"})
    env = load_environment("lamp")()
    env.init({"on": True})
    env.start()
    env.register_agent("a")
    env.associate_entity("a", "switch")
    env.perform_action("a", Action.of("toggle"))
    assert [str(p) for p in env.get_all_percepts("a")["switch"]] == ["lamp(off)"]
    env.perform_action("a", Action.of("toggle", 3))
    assert [str(p) for p in env.get_all_percepts("a")["switch"]] == ["lamp(on)"]
    with pytest.raises(ActionRefused, match="times must be 0 or more"):
        env.perform_action("a", Action.of("toggle", -1))
