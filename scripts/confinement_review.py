"""The review of goalagent's confinement against SWI-Prolog's manual: docs/confinement-review.md.

Every predicate the manual documents (its chapters on built-ins, extensions, modules,
tabling, coroutining, threads, engines, foreign code, the hackers' corner, profiling, saved
states, ...), section by section, with what confine.pl does with it when an agent writes it:
without the sandbox and with it (see scripts/confinement_review.pl). The table is re-checked
by tests/goalagent/kb/test_confinement_review.py; after a change to the confinement, write it again:

    .venv/bin/python scripts/confinement_review.py            # from the table's own rows
    .venv/bin/python scripts/confinement_review.py --manual DIR   # from a manual's sources

(``DIR``: swipl-devel's ``man/`` at the version installed, e.g. ``git show V9.0.4:man/X.doc``
for each file). The ``issue 24`` column is kept as it is: what that review closed.
Hand-written because no tool reads SWI-Prolog's LaTeX manual sources.
"""

from __future__ import annotations

import re
from collections import Counter
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Annotated

import typer

from ondisk import write_atomically

ROOT = Path(__file__).resolve().parents[1]
DOC = ROOT / "docs" / "confinement-review.md"
PROBE = Path(__file__).with_name("confinement_review.pl")
# The manual's files whose predicates an agent could call, in the manual's order.
MANUAL_FILES = ("overview.doc", "ide.doc", "builtin.doc", "extensions.doc", "ssu.doc",
                "module.doc", "tabling.doc", "attvar.doc", "threads.doc", "engines.doc",
                "foreign.doc", "runtime.doc", "profile.doc", "hack.doc", "dialect.doc",
                "license.doc", "heaps.doc", "xref.doc")
_ENTRY = re.compile(
    r"\\(chapter|section|subsection)\*?\{((?:[^{}]|\{[^{}]*\})*)\}"
    r"|\\(predicate|directive|dcg|prefixop|infixop)(?:\[[^\]]*\])?"
    r"\{((?:[^{}]|\{[^{}]*\})*)\}\{((?:[^{}]|\{[^{}]*\})*)\}")
# Files that are part of a chapter (or the library) without naming it.
_CHAPTERS = {"ssu.doc": "SWI-Prolog extensions", "profile.doc": "Built-in Predicates",
             "xref.doc": "Initialising and Managing a Prolog Project",
             "heaps.doc": "The SWI-Prolog library: library(heaps)"}
_MACROS = {r"\Scut": "!", r"\Sneck": ":-", r"\Sifthen": "->", r"\Ssoftcut": "*->",
           r"\Snot": "\\+", r"\Sbar": "|", r"\Suniv": "=..", r"\Seqbowtie": "=@=",
           r"\Snebowtie": "\\=@=", r"\Sidiv": "//", r"\Scomma": ","}
HEADER = ("| predicate | exists | without sandbox | with sandbox | issue 24 |",
          "| --- | --- | --- | --- | --- |")


@dataclass(frozen=True)
class Row:
    """One documented predicate, where the manual has it, and what confinement does."""

    section: str
    name: str
    arity: int
    exists: str = ""
    plain: str = ""
    sandbox: str = ""
    issue24: str = ""

    @property
    def indicator(self) -> str:
        return f"{self.name}/{self.arity}"


def manual_rows(folder: Path) -> list[Row]:
    """Every predicate the manual's sources in ``folder`` document, once, in their order."""
    rows: list[Row] = []
    seen: set[tuple[str, int]] = set()
    for file in MANUAL_FILES:
        chapter, section = _CHAPTERS.get(file, ""), ""
        for match in _ENTRY.finditer((folder / file).read_text(errors="replace")):
            if match.group(1):
                title = re.sub(r"\\[a-zA-Z]+\{([^}]*)\}", r"\1", match.group(2)).strip()
                if match.group(1) == "chapter":
                    chapter, section = title, ""
                elif match.group(1) == "section":
                    section = title
                continue
            kind, name, second = match.group(3), match.group(4).strip(), match.group(5)
            for macro, text in _MACROS.items():
                name = name.replace(macro, text)
            name = name.replace("\\_", "_").replace("{}", "")
            arity = {"infixop": 2, "prefixop": 1}.get(kind)
            if arity is None:
                if not second.strip().isdigit():
                    continue
                arity = int(second) + (2 if kind == "dcg" else 0)
            if ":" in name.strip(":") or (name, arity) in seen:
                continue  # a hook of another module (prolog:message//1), or seen already
            seen.add((name, arity))
            rows.append(Row(f"{chapter}: {section}" if section else chapter, name, arity))
    return rows


def read_doc(path: Path = DOC) -> list[Row]:
    """The rows of the review table as written."""
    rows, section = [], ""
    for line in path.read_text(encoding="utf-8").splitlines():
        if line.startswith("### "):
            section = re.sub(r" \(\d+\)$", "", line[4:])
        elif line.startswith("| `"):
            cells = [cell.strip() for cell in line.strip("|").split(" | ")]
            name, _, arity = cells[0].strip("`").replace("\\|", "|").rpartition("/")
            rows.append(Row(section, name, int(arity), *cells[1:5]))
    return rows


def _short(verdict) -> str:
    """A verdict in the table's words (the first words of a refusal say why)."""
    text = str(verdict)
    if not text.startswith("refused("):
        return text
    why = text[len("refused("):-1]
    for words, short in (("whole process", "refused: process-wide"),
                         ("would reveal", "refused: reveals modules"),
                         ("reserved", "refused: reserved"),
                         ("not allowed in the sandbox", "refused: not safe"),
                         ("sandbox cannot tell", "refused: not safe"),
                         ("is not a predicate the sandbox knows", "refused: unknown"),
                         ("loads code", "refused: loads code"),
                         ("attribute hooks", "refused: attribute hook"),
                         ("lambda form", "refused: unchecked lambda"),
                         ("~@", "refused: hidden goal"),
                         ("format", "refused: format")):
        if words in why:
            return short
    return "refused"


def judge(rows: list[Row]) -> list[Row]:
    """``rows`` with what confine.pl does with each now (and whether it exists)."""
    import io

    from goalagent.agent import Agent
    from goalagent.kb.engine import get_engine
    from goalagent.kb.limits import Limits
    from goalagent.kb.terms import Atom
    from goalagent.parser import parse_agent

    engine = get_engine()
    engine.call("load_files", Atom(str(PROBE)), [], module="user")
    agent = Agent(parse_agent("main module { program { if true then print(x). } }", "r.goal"),
                  limits=Limits(sandbox=True), output=io.StringIO(), warn=lambda m: None)
    try:
        judged = []
        for row in rows:
            found = engine.call("verdict", agent.ms.belief_module, Atom(row.name), row.arity,
                                None, None, module="ga_review")
            assert found is not None
            exists = engine.call("current_predicate_or_library", Atom(row.name), row.arity,
                                 module="ga_review")
            judged.append(replace(row, exists="yes" if exists is not None else "no",
                                  plain=_short(found[3]), sandbox=_short(found[4])))
        return judged
    finally:
        agent.close()


def _cell(text: str) -> str:
    return text.replace("|", "\\|")


def write_doc(rows: list[Row], path: Path = DOC) -> None:
    """The review as markdown: the summary, then per section its counts and rows."""
    sections: dict[str, list[Row]] = {}
    for row in rows:
        sections.setdefault(row.section, []).append(row)
    totals = Counter((row.plain.split(":")[0], row.sandbox.split(":")[0]) for row in rows)
    closed = Counter(row.issue24 for row in rows if row.issue24)
    lines = [path.read_text(encoding="utf-8").split("\n## Sections")[0].rstrip(), "",
             "## Sections", "",
             f"{len(rows)} predicates in {len(sections)} sections. Without / with the "
             "sandbox: " + ", ".join(f"{a} / {b}: {n}" for (a, b), n in sorted(totals.items()))
             + ". Issue 24: " + ", ".join(f"{what}: {n}" for what, n in sorted(closed.items()))
             + ".", ""]
    lines += ["| section | reviewed | refused without / with sandbox | per agent | issue 24 "
              "closed |", "| --- | --- | --- | --- | --- |"]
    for section, members in sections.items():
        refused = [sum(getattr(row, mode).startswith("refused") for row in members)
                   for mode in ("plain", "sandbox")]
        lines.append(f"| {section} | {len(members)} | {refused[0]} / {refused[1]} | "
                     f"{sum(row.plain == 'agent' for row in members)} | "
                     f"{sum('closed' in row.issue24 for row in members)} |")
    lines.append("")
    for section, members in sections.items():
        lines += [f"### {section} ({len(members)})", "", *HEADER]
        lines += [f"| `{_cell(row.indicator)}` | {row.exists} | {row.plain} | {row.sandbox} | "
                  f"{row.issue24} |" for row in members]
        lines.append("")
    write_atomically(path, "\n".join(lines))


def main(manual: Annotated[Path | None, typer.Option(
        help="The manual's sources (swipl-devel man/) to take the predicates from.")] = None
         ) -> None:
    """Write docs/confinement-review.md again with what confine.pl does now."""
    kept = {row.indicator: row.issue24 for row in read_doc()} if DOC.exists() else {}
    rows = manual_rows(manual) if manual is not None else read_doc()
    rows = [replace(row, issue24=kept.get(row.indicator, row.issue24)) for row in rows]
    write_doc(judge(rows))
    print(f"{DOC}: {len(rows)} predicates")


if __name__ == "__main__":
    typer.run(main)
