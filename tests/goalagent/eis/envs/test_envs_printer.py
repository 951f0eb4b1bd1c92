"""The printer environment: printText prints one line on stdout; printedText counts them."""

from __future__ import annotations

import pytest

from goalagent.eis import ActException, Action, Function, Identifier, Numeral, load_environment


def test_print_text_prints_lines_and_counts_them(capsys: pytest.CaptureFixture[str]) -> None:
    env = load_environment("printer")()
    env.init({})
    env.start()
    env.register_agent("ag")
    env.associate_entity("ag", "printer")
    assert [str(p) for p in env.get_all_percepts("ag")["printer"]] == ["printedText(0)"]
    env.perform_action("ag", Action.of("printText", "Hello world"))
    env.perform_action("ag", Action("printText", (Identifier("it's done", string=True),)))
    env.perform_action("ag", Action("printText", (Numeral(-2.5),)))
    env.perform_action("ag", Action("printText", (Function("f", (Identifier("X"),)),)))
    assert capsys.readouterr().out == "Hello world\nit's done\n-2.5\nf('X')\n"
    assert [str(p) for p in env.get_all_percepts("ag")["printer"]] == ["printedText(4)"]
    with pytest.raises(ActException, match="printText expects 1 parameter"):
        env.perform_action("ag", Action.of("printText"))
    assert capsys.readouterr().out == ""
